"""``WS /ws/audio`` (push-to-talk) driven by a Python client against a real ``stuart-bt serve
--mission``: spoken audio (espeak-ng, made here) becomes a mission; the limits (a press too long,
bad frames and messages, a second start, a wrong Origin or Host) are answered with one sentence
and never a traceback. Against ``stuart-bt serve TREE``, what is spoken goes to the running tree."""

from __future__ import annotations

import asyncio
import json
import shutil
import urllib.request
from pathlib import Path
from typing import Any

import pytest

from web_support import EventFeed, Served

pytest.importorskip("starlette", reason="the web view needs the web extra (make test installs it)")
websockets = pytest.importorskip("websockets")
pytest.importorskip("faster_whisper", reason="hearing needs the hearing extra (make test installs it)")

pytestmark = pytest.mark.slow
SOX = shutil.which("sox")


def pcm_48k(tmp_path: Path, text: str) -> bytes:
    """``text`` spoken by espeak-ng, as raw 48 kHz mono int16 (what a browser sends)."""
    from stuart_bt.testing import speak

    if SOX is None or shutil.which("espeak-ng") is None:
        pytest.skip("needs sox and espeak-ng (make test installs them)")
    wav = speak(text, tmp_path / "said.wav")
    raw = tmp_path / "said.raw"
    import subprocess

    subprocess.run([SOX, str(wav), "-r", "48000", "-c", "1", "-b", "16", "-e", "signed-integer", "-t", "raw", str(raw)],
                   check=True, timeout=30)
    return raw.read_bytes()


def ws_url(served: Served) -> str:
    return served.url.replace("http://", "ws://").rstrip("/") + "/ws/audio"


async def talk(url: str, steps: list[Any], answers: int, **connect: Any) -> list[dict[str, Any]]:
    """Send ``steps`` (bytes, or dicts as JSON text) and read ``answers`` messages (strict JSON)."""
    async with websockets.connect(url, max_size=None, open_timeout=30, **connect) as ws:
        for step in steps:
            await ws.send(step if isinstance(step, bytes) else json.dumps(step))
        return [json.loads(await asyncio.wait_for(ws.recv(), 120), parse_constant=_strict) for _ in range(answers)]


def _strict(name: str) -> Any:
    raise AssertionError(f"{name} in an answer")


def frames(pcm: bytes, size: int = 8192) -> list[bytes]:
    return [pcm[i:i + size] for i in range(0, len(pcm), size)]


def test_speech_over_the_socket_starts_a_mission_and_the_limits_hold(tmp_path):
    pcm = pcm_48k(tmp_path, "Hey Stuart, go to the kitchen")
    with Served("--mission", "--backend", "dry", "--speed", "20") as served:
        url = ws_url(served)
        answers = asyncio.run(talk(url, [{"type": "start", "rate": 48000}, *frames(pcm), {"type": "stop"}], 2))
        assert answers[0] == {"type": "recording", "rate": 48000, "max_s": 15.0}
        heard = answers[1]
        assert heard["type"] == "heard" and "kitchen" in heard["text"].lower(), served.output()[-3000:]
        assert heard["kind"] == "tasks" and heard["source"] == "browser" and heard["cut"] is False
        assert heard["intents"][0]["action"] == "navigate_to_marker"
        assert 1.0 < heard["audio_s"] < 4.0 and 0 < heard["confidence"] <= 1
        state = json.loads(urllib.request.urlopen(served.url.rstrip("/") + "/api/state", timeout=10).read())
        assert state["mode"] == "mission"

        # a press of 16 s at 16 kHz: cut at 15 s, said at once and in the answer
        silence = bytes(16_000 * 2 * 16)
        steps = [{"type": "start", "rate": 16000}, *frames(silence, 32000), {"type": "stop"}]
        answers = asyncio.run(talk(url, steps, 3))
        assert [a["type"] for a in answers] == ["recording", "cut", "heard"]
        assert "15 s" in answers[1]["message"]
        assert answers[2]["cut"] is True and answers[2]["audio_s"] == pytest.approx(15.0, abs=0.05)
        assert answers[2]["kind"] == "no_speech"

        # mistakes: one sentence each, and the connection goes on
        answers = asyncio.run(talk(url, [
            b"\x00\x00",                                   # audio before a start
            {"type": "start", "rate": 48000},
            {"type": "start", "rate": 48000},              # a second start while recording
            b"\x00\x00\x00",                               # an odd number of bytes
            {"type": "stop"},                              # the odd frame dropped the recording
            {"type": "start", "rate": 3},
            {"type": "dance"},
            {"type": "start", "rate": 16000},
            {"type": "stop"},                              # nothing came
        ], 9))
        errors = [a.get("error", "") for a in answers if a["type"] == "error"]
        assert [a["type"] for a in answers] == ["error", "recording", "error", "error", "error", "error", "error",
                                                "recording", "error"]
        assert "without a start" in errors[0] and "one recording at a time" in errors[1]
        assert "even number of bytes" in errors[2] and "nothing is recording" in errors[3]
        assert "'rate'" in errors[4] and "unknown message type" in errors[5] and "no audio" in errors[6]
        for text in ["not json", "[1]", '{"type": "start", "rate": NaN}']:
            answer = asyncio.run(talk_text(url, text))
            assert answer["type"] == "error" and ("JSON" in answer["error"] or "object" in answer["error"])

        # a frame over the limit closes the socket with 1009 after saying why
        async def too_big() -> tuple[dict[str, Any], int]:
            async with websockets.connect(url, max_size=None) as ws:
                await ws.send(json.dumps({"type": "start", "rate": 16000}))
                await ws.recv()
                await ws.send(bytes(65 * 1024))
                said = json.loads(await ws.recv())
                await ws.wait_closed()
                return said, ws.close_code
        said, code = asyncio.run(too_big())
        assert "at most 65536 bytes" in said["error"] and code == 1009

        # another site's page, or another name for this server: refused before anything is read
        rebound = url.replace("127.0.0.1", "evil.example")  # its name, this address (DNS rebinding)
        for target, options in ((url, {"additional_headers": {"Origin": "http://evil.example"}}),
                                (rebound, {"host": "127.0.0.1", "port": served.port})):
            with pytest.raises(websockets.exceptions.InvalidStatus) as refused:
                asyncio.run(talk(target, [], 0, **options))
            assert refused.value.response.status_code == 403
        assert "Traceback" not in served.output()


async def talk_text(url: str, text: str) -> dict[str, Any]:
    async with websockets.connect(url) as ws:
        await ws.send(text)
        return json.loads(await asyncio.wait_for(ws.recv(), 30))


def test_a_tree_server_with_nothing_running_says_so_when_the_button_is_released():
    with Served("trees/greet.yaml", "--paused") as served:
        answers = asyncio.run(talk(ws_url(served), [{"type": "start", "rate": 16000}, b"\x00\x00",
                                                    {"type": "stop"}], 2))
    assert answers[0] == {"type": "recording", "rate": 16000, "max_s": 15.0}
    assert answers[1]["type"] == "error" and answers[1]["error"].startswith("nothing is running to talk to")


def test_stop_spoken_into_the_button_holds_the_tree_a_tree_server_runs(tmp_path):
    pcm = pcm_48k(tmp_path, "Hey Stuart, stop")
    with Served("trees/lab_tour.yaml", "--backend", "dry", "--speed", "5") as served, EventFeed(served) as feed:
        feed.wait_for(lambda e: e["kind"] == "run" and e.get("phase") == "start")
        answers = asyncio.run(talk(ws_url(served), [{"type": "start", "rate": 48000}, *frames(pcm), {"type": "stop"}],
                                   2))
        hold = feed.wait_for(lambda e: e["kind"] == "hold", timeout=120)
        [said] = feed.of("utterance")
    heard = answers[1]
    assert heard["type"] == "heard" and heard["kind"] == "stop" and heard["source"] == "browser", answers
    assert "stop" in heard["text"].lower() and said["source"] == "browser" and said["data_kind"] == "stop"
    assert hold["reason"].startswith("stop said")
