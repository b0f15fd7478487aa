"""``stuart-bt parse`` end to end, as scripts use it: one JSON object per utterance, the JSON-lines
mode that never stops and flushes every line, options, and errors without tracebacks.

Runs ``stuart-bt parse`` when the main CLI has the command, else the same code standalone
(``python -m stuart_bt.cli.parse``)."""

from __future__ import annotations

import json
import os
import select
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

REPO = Path(__file__).resolve().parents[1]
MARKERS = REPO / "sim" / "maps" / "lab_markers.json"
KEYS = {"utterance", "wake", "command", "intents", "conversational", "coverage", "doubt"}
INTENT_KEYS = {"action", "target", "x", "y", "yaw", "raw_text"}


def _command() -> list[str]:
    script = Path(sys.executable).with_name("stuart-bt")
    return [str(script), "parse"] if script.exists() else [sys.executable, "-m", "stuart_bt.cli", "parse"]


CLI = _command()


def run(*args: str, stdin: bytes | None = None, timeout: float = 30) -> subprocess.CompletedProcess[bytes]:
    return subprocess.run([*CLI, *args], input=stdin, capture_output=True, timeout=timeout, cwd=REPO, check=False)


def objects(out: bytes) -> list[dict[str, Any]]:
    lines = out.decode("utf-8").splitlines()
    return [json.loads(line) for line in lines]


def test_one_utterance_one_object() -> None:
    done = run("Hey Stewart, go back two metres and then turn right")
    assert done.returncode == 0 and done.stderr == b""
    [obj] = objects(done.stdout)
    assert set(obj) == KEYS
    assert obj["wake"] is True and obj["conversational"] is False
    assert obj["command"] == "go back two metres and then turn right"
    assert [set(i) for i in obj["intents"]] == [INTENT_KEYS, INTENT_KEYS]
    assert [(i["action"], i["x"], round(i["yaw"], 4)) for i in obj["intents"]] == [
        ("move_relative", -2.0, 0.0), ("turn_by_angle", 0.0, -1.5708)]


def test_unquoted_words_are_one_utterance() -> None:
    [obj] = objects(run("hey", "stuart", "wave").stdout)
    assert obj["utterance"] == "hey stuart wave" and obj["intents"][0]["target"] == "wave"


def test_the_three_cases_of_the_contract() -> None:
    [asleep] = objects(run("go to the kitchen").stdout)
    assert (asleep["wake"], asleep["intents"], asleep["conversational"], asleep["command"]) == (False, [], False, "")
    [chat] = objects(run("Hey Stuart, what can you pick up?").stdout)
    assert (chat["wake"], chat["intents"], chat["conversational"]) == (True, [], True)
    assert chat["command"] == "what can you pick up?"
    [cmd] = objects(run("Hey Stuart, stop").stdout)
    assert (cmd["wake"], cmd["conversational"], cmd["intents"][0]["action"]) == (True, False, "stop")


def test_jsonl_keeps_order_and_survives_anything() -> None:
    huge = b"hey stuart " + b"x" * 200_000
    lines = [b"hey stuart stop", b"", b"\xff\xfe\xfd not utf-8", b"\x00\x01\x02", huge,
             b"Hey Stuart, go to the kitchen\r", "hey stuart, café?".encode(), b"   ", b"ok stuart turn left"]
    done = run("--jsonl", stdin=b"\n".join(lines) + b"\n")
    assert done.returncode == 0 and done.stderr == b"", done.stderr[-500:]
    got = objects(done.stdout)
    assert len(got) == len(lines)
    assert all(set(o) >= KEYS for o in got)
    assert got[0]["intents"][0]["action"] == "stop"
    assert got[1]["utterance"] == "" and got[1]["wake"] is False
    assert "\ufffd" in got[2]["utterance"]
    assert got[4].get("truncated") is True and len(got[4]["utterance"]) <= 64 * 1024
    assert got[5]["utterance"] == "Hey Stuart, go to the kitchen" and got[5]["intents"][0]["target"] == "kitchen"
    assert got[6]["conversational"] is True
    assert got[8]["intents"][0]["action"] == "turn_by_angle"


def test_jsonl_without_final_newline_and_empty_input() -> None:
    assert len(objects(run("--jsonl", stdin=b"hey stuart stop").stdout)) == 1
    done = run("--jsonl", stdin=b"")
    assert done.returncode == 0 and done.stdout == b""


@pytest.mark.skipif(os.name != "posix", reason="select on pipes")
def test_jsonl_answers_each_line_before_the_next_arrives() -> None:
    proc = subprocess.Popen([*CLI, "--jsonl"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, cwd=REPO)
    assert proc.stdin is not None and proc.stdout is not None
    try:
        for utterance, action in (("hey stuart stop", "stop"), ("hey stuart wave", "gesture")):
            proc.stdin.write(utterance.encode() + b"\n")
            proc.stdin.flush()
            ready, _, _ = select.select([proc.stdout], [], [], 20)
            assert ready, "no answer while the input is still open: output not flushed per line"
            obj = json.loads(proc.stdout.readline())
            assert obj["intents"][0]["action"] == action
    finally:
        proc.stdin.close()
        proc.wait(timeout=20)
    assert proc.returncode == 0


def test_name_and_greeting_options() -> None:
    [obj] = objects(run("--name", "Robbie", "hey robby, turn left").stdout)
    assert obj["wake"] is True and obj["intents"][0]["action"] == "turn_by_angle"
    [obj] = objects(run("--name", "Robbie", "hey stuart turn left").stdout)
    assert obj["wake"] is False
    [obj] = objects(run("--greeting", "yo", "hey stuart stop").stdout)
    assert obj["wake"] is False
    [obj] = objects(run("--no-wake", "turn left").stdout)
    assert obj["wake"] is False and obj["intents"][0]["action"] == "turn_by_angle"


def test_markers_add_a_resolution_per_intent() -> None:
    [obj] = objects(run("--markers", str(MARKERS), "hey stuart go to the garage then station three and wave").stdout)
    res = obj["resolution"]
    assert len(res) == len(obj["intents"]) == 3
    assert res[0]["ok"] is False and res[0]["say"].startswith("I don't know where the garage is")
    assert res[1]["name"] == "station_3" and res[2]["name"] == "high wave"


def test_bad_marker_file_is_one_line_not_a_traceback(tmp_path: Path) -> None:
    bad = tmp_path / "m.json"
    bad.write_text("{not json")
    done = run("--markers", str(bad), "hey stuart stop")
    assert done.returncode == 1
    err = done.stderr.decode()
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1 and "m.json" in err


def test_usage_errors() -> None:
    assert run().returncode == 2
    assert run("--jsonl", "hey stuart stop", stdin=b"").returncode == 2


def test_invalid_utf8_argument_still_gives_json() -> None:
    proc = subprocess.run([os.fsencode(a) for a in CLI] + [b"hey stuart go to the caf\xe9"], capture_output=True,
                          timeout=30, cwd=REPO, check=False)
    assert proc.returncode == 0
    [obj] = objects(proc.stdout)
    assert obj["wake"] is True and "\ufffd" in obj["utterance"]


def test_pretty() -> None:
    out = run("--pretty", "hey stuart stop").stdout.decode()
    assert out.startswith("{\n") and json.loads(out)["intents"][0]["action"] == "stop"


def test_many_lines_are_fast() -> None:
    lines = b"\n".join([b"Hey Stuart, go to the kitchen and then pick up the bottle"] * 5000) + b"\n"
    start = time.monotonic()
    done = run("--jsonl", stdin=lines, timeout=60)
    assert done.returncode == 0 and len(objects(done.stdout)) == 5000
    assert time.monotonic() - start < 30
