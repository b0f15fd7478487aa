"""Everything the project writes is strict JSON: no NaN, no Infinity, which Python writes by
default and every other reader (a browser, jq, rclpy's peers) refuses. Each output is produced
for real and parsed by a parser that rejects both."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from stuart_bt.core.clock import ManualClock
from stuart_bt.core.events import Event, EventStream
from stuart_bt.core.jsonfile import compact_encoder, to_json
from stuart_bt.ros.topics import EventTranslator
from stuart_bt.run.snapshot import TreeSnapshot

REPO = Path(__file__).resolve().parents[1]


def strict(text: str) -> Any:
    """Parse ``text``, failing on NaN, Infinity and -Infinity."""
    def refuse(name: str) -> None:
        raise AssertionError(f"{name} in output: {text[:200]}")
    return json.loads(text, parse_constant=refuse)


def test_to_json_writes_non_finite_numbers_as_null_however_deep():
    value = {"speed": math.inf, "poses": [{"x": math.nan}, (1.0, -math.inf)], "ok": 1.5}
    assert strict(to_json(value)) == {"speed": None, "poses": [{"x": None}, [1.0, None]], "ok": 1.5}


def test_to_json_also_cleans_what_a_default_hook_returns():
    class Odd:
        pass
    assert strict(to_json({"thing": Odd()}, default=lambda o: {"value": math.nan})) == {"thing": {"value": None}}


JSON_LIKE = st.recursive(st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8),
                         lambda inner: st.lists(inner, max_size=4) | st.tuples(inner, inner)
                         | st.dictionaries(st.text(max_size=5), inner, max_size=4), max_leaves=25)


@settings(max_examples=300, deadline=None)
@given(JSON_LIKE, st.booleans())
def test_the_compact_encoder_writes_what_to_json_writes(value, ensure_ascii):
    """The daemon protocol's encoder (made once, for speed) against the reference: the same
    text for any value, NaN and infinities as null included."""
    expected = to_json(value, separators=(",", ":"), ensure_ascii=ensure_ascii)
    assert compact_encoder(ensure_ascii)(value) == expected
    strict(expected)


def test_the_compact_encoder_without_the_c_accelerator_writes_the_same(monkeypatch):
    value = {"a": [1.5, math.nan, "é\n"], "b": {"c": None, "d": True}}
    fast = compact_encoder(ensure_ascii=False)(value)
    monkeypatch.setattr(json.encoder, "c_make_encoder", None)
    assert compact_encoder(ensure_ascii=False)(value) == fast == '{"a":[1.5,null,"é\\n"],"b":{"c":null,"d":true}}'


def test_the_compact_encoder_refuses_a_loop_and_an_unknown_type_as_json_dumps_does():
    looped: list[Any] = []
    looped.append(looped)
    encode = compact_encoder()
    with pytest.raises(ValueError, match="Circular reference"):
        encode({"a": looped})
    with pytest.raises(TypeError, match="not JSON serializable"):
        encode({"when": object()})
    assert encode({"still": "fine"}) == '{"still":"fine"}'  # a failed call leaves nothing behind


@pytest.mark.parametrize("backend", ["dry", pytest.param("sim", marks=pytest.mark.slow)])
def test_a_run_writes_its_log_and_report_as_strict_json(tmp_path: Path, backend: str):
    if backend == "sim":
        pytest.importorskip("mujoco", reason="the sim backend needs the 'sim' extra")
    log, report = tmp_path / "run.jsonl", tmp_path / "report.json"
    done = subprocess.run([sys.executable, "-m", "stuart_bt.cli", "run", "trees/greet.yaml", "--backend", backend,
                           "--view", "none", "--speed", "20" if backend == "dry" else "0", "--log", str(log),
                           "--report", str(report)], cwd=REPO, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-1000:]
    lines = log.read_text().splitlines()
    events = [strict(line) for line in lines]
    starts = [e for e in events if e["kind"] == "run" and e.get("phase") == "start"]
    assert starts and "speed" in starts[0]  # the field that once was Infinity in sim runs
    body = strict(report.read_text())
    assert body["status"] == "SUCCESS"


def test_parse_jsonl_output_is_strict_json():
    done = subprocess.run([sys.executable, "-m", "stuart_bt.cli", "parse", "--jsonl"], input=(
        "Hey Stuart, turn left 1e999 degrees\nHey Stuart, go to the kitchen\nnan\n"), capture_output=True,
        text=True, timeout=60, cwd=REPO)
    assert done.returncode in (0, 1), done.stderr
    assert len([strict(line) for line in done.stdout.splitlines()]) == 3


def test_events_snapshots_and_ros_messages_are_strict_json_even_with_infinite_values():
    events = EventStream(ManualClock())
    snapshot = TreeSnapshot(events)
    translator = EventTranslator()
    seen: list[Event] = []
    events.subscribe(seen.append)
    events.publish("run", phase="start", tree="t.yaml", backend="sim", speed=math.inf)
    events.publish("blackboard", key="battery", value=math.nan)
    events.publish("pose", x=1.0, y=math.inf, yaw=0.0)
    for event in seen:
        strict(event.to_json())
        for out in translator.translate(event):
            if isinstance(out.payload, str):
                strict(out.payload)
    strict(snapshot.to_json())
    snapshot.close()
