"""The daemon line protocol's edge: whatever comes over a pipe, in either direction, is refused
with the protocol's own error and a warning, never a crash; NaN and infinity never get in;
a babbling daemon cannot flood the event stream."""

from __future__ import annotations

import json
import math
import select
import subprocess
import sys
import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from stuart_bt.core.clock import ScaledClock
from stuart_bt.core.events import EventRecorder, EventStream
from stuart_bt.core.world import Pose, PoseError
from stuart_bt.daemon import protocol as p
from stuart_bt.daemon.limits import FAULTY_LINES, FULL_WARNINGS
from stuart_bt.daemon.supervisor import Supervisor

FAKES = Path(__file__).parent / "fakes"


# -- the decoder -----------------------------------------------------------------------------------

@pytest.mark.parametrize("line", [
    b"[" * 300_000 + b"]" * 300_000,
    b'{"a": ' * 40 + b"1" + b"}" * 40,
    b'{"type": "heartbeat", "state": {"pose": {"x": NaN}}}',
    b'{"type": "heartbeat", "state": {"pose": {"x": Infinity}}}',
    b'{"type": "heartbeat", "state": {"pose": {"x": -Infinity}}}',
    b'{"type": "heartbeat", "state": {"pose": {"x": 1e999}}}',
    b"\xff\xfe not utf-8",
    b"[1, 2, 3]",
])
def test_a_line_that_is_deep_non_finite_or_not_an_object_is_a_protocol_error(line: bytes):
    with pytest.raises(p.ProtocolError):
        p.decode(line)


def test_brackets_inside_strings_do_not_count_as_nesting():
    message = p.decode(json.dumps({"type": "log", "message": "[" * 500 + "{" * 500}).encode())
    assert message["message"].startswith("[[[")


@settings(max_examples=300, deadline=None)
@given(st.binary(max_size=400) | st.text(max_size=400).map(lambda t: t.encode("utf-8", "surrogatepass")))
def test_arbitrary_bytes_are_decoded_or_refused_with_the_protocol_error_only(line: bytes):
    try:
        message = p.decode(line)
    except p.ProtocolError:
        return
    assert isinstance(message, dict)


JSON = st.recursive(st.none() | st.booleans() | st.floats() | st.integers() | st.text(max_size=8),
                    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=5), inner, max_size=4),
                    max_leaves=30)


def _finite_everywhere(value) -> bool:
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, dict):
        return all(_finite_everywhere(v) for v in value.values())
    if isinstance(value, list):
        return all(_finite_everywhere(v) for v in value)
    return True


@settings(max_examples=300, deadline=None)
@given(st.dictionaries(st.text(max_size=6), JSON, max_size=5))
def test_whatever_is_encoded_decodes_again_with_only_finite_numbers(message):
    line = p.encode(message)
    json.loads(line, parse_constant=lambda name: pytest.fail(f"{name} written"))  # strict JSON out
    try:
        back = p.decode(line)
    except p.ProtocolError as e:
        assert "nested deeper" in e.reason
        return
    assert _finite_everywhere(back)


@pytest.mark.parametrize("pose", [{"x": "abc", "y": 0}, {"x": float("nan"), "y": 0}, {"x": 1, "y": float("inf")},
                                  {"x": True, "y": 0}, "here", None, {"x": 1, "y": 2, "yaw": "north"}])
def test_a_pose_that_is_not_finite_numbers_is_not_a_pose(pose):
    with pytest.raises(PoseError):
        Pose.from_dict(pose)


def test_a_good_pose_is_a_pose_and_yaw_defaults_to_zero():
    assert Pose.from_dict({"x": 1, "y": 2.5}) == Pose(1.0, 2.5, 0.0)


# -- a hostile daemon, for real ------------------------------------------------------------------------

def test_a_hostile_daemon_is_refused_line_by_line_warned_about_at_a_bounded_rate_and_stays_up(tmp_path):
    assert FAULTY_LINES > 150  # the fake's junk stays under the flood bound: refused line by line, not restarted
    clock = ScaledClock(1.0)
    events = EventStream(clock)
    recorder = EventRecorder(events)
    sup = Supervisor("dry", clock, events, families=("loco",), run_dir=tmp_path,
                     programs={"loco": [sys.executable, str(FAKES / "hostile_daemon.py")]})
    try:
        sup.start()
        loco = sup.client("loco")
        started = time.monotonic()
        while loco.state.get("seq", 0) < 10 and time.monotonic() - started < 30:
            sup.poll()
            time.sleep(0.02)
        took = time.monotonic() - started
        assert loco.state.get("seq", 0) >= 10, "good heartbeats after the garbage were read"
        assert sup.phase("loco") == "ready"
        assert Pose.from_dict(loco.state["pose"]) == Pose(1.0, 2.0, 0.5)
        warnings = [e.data["message"] for e in recorder.of_kind("warning")]
        assert 1 <= len(warnings) <= FULL_WARNINGS + took + 2, len(warnings)  # a few in full, then a summary a second
        assert any("nested deeper" in w or "limit" in w for w in warnings)
    finally:
        sup.shutdown()


def _read_reply(proc: subprocess.Popen, request_id: str, timeout: float = 30.0) -> dict:
    deadline = time.monotonic() + timeout
    buffer = b""
    while time.monotonic() < deadline:
        ready, _, _ = select.select([proc.stdout], [], [], 0.5)
        if ready:
            chunk = proc.stdout.read1(65536)
            if not chunk:
                break
            buffer += chunk
            for line in buffer.split(b"\n")[:-1]:
                message = json.loads(line)
                if message.get("id") == request_id and message.get("type") in ("done", "error"):
                    return message
    raise AssertionError(f"no reply to {request_id} within {timeout} s; got {buffer[-300:]!r}")


@pytest.mark.parametrize("garbage", [
    b"[" * 300_000 + b"]" * 300_000,
    b'{"id": "g1", "cmd": "say", "args": {"text": NaN}}',
    b"x" * (p.MAX_LINE + 10),
    b"\xff\xfe\x00 binary",
])
def test_a_daemon_given_garbage_on_stdin_answers_and_goes_on(garbage: bytes):
    proc = subprocess.Popen([sys.executable, "-m", "stuart_bt.skills.tts", "--backend", "dry"],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        proc.stdin.write(garbage + b"\n" + p.encode(p.request("after", "ping")))
        proc.stdin.flush()
        assert _read_reply(proc, "after")["type"] == "done"
        assert proc.poll() is None
    finally:
        proc.kill()
        proc.communicate(timeout=10)
