"""The daemons' fault matrix (issue 12): each row is one fault in one direction, what the robot
does, how soon the framework knows, and what the user is told.

Daemon -> framework faults use the real dry daemons (kill -9, SIGSTOP) or a fake daemon that
misbehaves on its output (tests/fakes/faulty_daemon.py). Framework -> daemon faults write the bad
input straight into a real dry daemon's stdin. Detection times are printed (``-s``) for the
report; the assertions only hold generous bounds.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import time
from pathlib import Path

import pytest

from stuart_bt.core.catalogue import FAMILIES
from stuart_bt.core.clock import ScaledClock
from stuart_bt.core.events import EventRecorder, EventStream
from stuart_bt.daemon import limits
from stuart_bt.daemon import protocol as p
from stuart_bt.daemon.supervisor import Supervisor
from test_daemon_runtime import Daemon

FAULTY = Path(__file__).parent / "fakes" / "faulty_daemon.py"
CLOCK = ScaledClock(20)
BUSY = {  # a command per family that keeps the daemon busy for a while (seconds of clock time)
    "loco": ("navigate", {"pose": {"x": 40.0, "y": 0.0, "yaw": None}}),
    "tts": ("say", {"text": "a long sentence that keeps the voice busy for a good while " * 4}),
    "gesture": ("play", {"sequence": ["high wave", "face wave", "high wave", "face wave"]}),
    "pick": ("ping", {}),
    "vision": ("find", {"object": "bottle", "robot_pose": {"x": 3.5, "y": 1.5, "yaw": 0.0}, "held": None}),
}


@pytest.fixture(autouse=True)
def reap_raw_daemons():
    yield
    for daemon in Daemon.started:
        if daemon.proc.poll() is None:
            daemon.proc.kill()
            daemon.proc.wait()
    Daemon.started.clear()


@pytest.fixture
def supervised(tmp_path):
    made: list[Supervisor] = []

    def make(families: tuple[str, ...], **kwargs) -> tuple[Supervisor, EventRecorder]:
        stream = EventStream(CLOCK)
        recorder = EventRecorder(stream)
        kwargs.setdefault("heartbeat_timeout", 1.0)
        made.append(Supervisor("dry", CLOCK, stream, families=families, run_dir=tmp_path, **kwargs))
        made[-1].start()
        return made[-1], recorder

    yield make
    for sup in made:
        for family in sup.families:
            if sup.pid(family):
                with contextlib.suppress(ProcessLookupError):
                    os.kill(sup.pid(family), signal.SIGCONT)
        sup.shutdown()


def poll_until(sup: Supervisor, condition, timeout: float = 10.0) -> float:
    """Poll at 20 Hz like the executor until ``condition()``; the wall time it became true."""
    deadline = time.monotonic() + timeout
    while not condition():
        assert time.monotonic() < deadline, "condition not reached in time"
        time.sleep(0.05)
        sup.poll()
    return time.monotonic()


def state_events(recorder: EventRecorder, family: str) -> list[dict]:
    return [e.data for e in recorder.of_kind("daemon_state") if e.data["family"] == family]


def report(row: str, seconds: float) -> None:
    print(f"\nFAULT-MATRIX {row}: detected in {seconds * 1000:.0f} ms")


# -- daemon -> framework ----------------------------------------------------------------------

@pytest.mark.parametrize("family", FAMILIES)
def test_a_daemon_killed_with_sigkill_fails_its_request_at_the_next_poll_and_comes_back(supervised, family):
    sup, recorder = supervised((family,))
    client = sup.client(family)
    busy = client.request(*BUSY[family])
    poll_until(sup, lambda: busy.status != "sent")
    os.kill(sup.pid(family), signal.SIGKILL)
    killed = time.monotonic()
    detected = poll_until(sup, lambda: sup.phase(family) == "down")
    report(f"{family} kill -9", detected - killed)
    assert detected - killed < 5.0
    if not busy.finished or busy.error_code is not None:
        assert (busy.error_code, busy.reason) == ("daemon_died", f"{family} daemon exited with signal SIGKILL")
    assert state_events(recorder, family)[-1]["reason"] == f"{family} daemon exited with signal SIGKILL"
    poll_until(sup, lambda: sup.phase(family) == "ready")
    assert sup.wait(client.request("ping")).ok


@pytest.mark.parametrize("family", FAMILIES)
def test_a_daemon_frozen_with_sigstop_is_declared_hung_within_its_heartbeat_timeout(supervised, family):
    sup, recorder = supervised((family,))
    client = sup.client(family)
    os.kill(sup.pid(family), signal.SIGSTOP)
    frozen = time.monotonic()
    ping = client.request("ping")
    poll_until(sup, lambda: ping.finished)
    report(f"{family} SIGSTOP", ping.finished_at - frozen)
    assert ping.error_code == "daemon_hung" and ping.finished_at - frozen < 5.0
    assert state_events(recorder, family)[-1]["state"] == "hung"
    poll_until(sup, lambda: sup.phase(family) == "ready")
    assert sup.wait(client.request("ping")).ok


def test_a_daemon_that_heartbeats_but_never_answers_is_reported_hung_and_restarted(supervised):
    sup, recorder = supervised(("loco",), programs={"loco": [sys.executable, str(FAULTY), "mute"]})
    walk = sup.client("loco").request("navigate", {"pose": {"x": 1.0, "y": 0.0}}, path="tour/go")
    poll_until(sup, lambda: walk.finished)
    report("loco silence (mute)", walk.finished_at - walk.sent_at)
    assert walk.finished_at - walk.sent_at < 5.0
    assert walk.error_code == "daemon_hung"
    assert walk.reason == ("loco daemon did not answer r1 (navigate) within 1.0 s though it still heartbeats")
    hung = state_events(recorder, "loco")[-1]
    assert (hung["state"], hung["reason"], hung["failed"]) == ("hung", walk.reason, ["r1"])
    stops = [e.data for e in recorder.of_kind("command") if e.data["cmd"] == "stop"]
    assert stops, "the hung daemon was not told to stop before it was killed"
    poll_until(sup, lambda: sup.phase("loco") == "ready")


def test_a_garbage_flood_is_a_few_warnings_and_then_a_faulty_daemon(supervised):
    sup, recorder = supervised(("loco",), programs={"loco": [sys.executable, str(FAULTY), "flood"]})
    started = time.monotonic()
    faulty_at = poll_until(sup, lambda: any(s["state"] == "faulty" for s in state_events(recorder, "loco")))
    report("loco garbage flood", faulty_at - started)
    warnings = recorder.of_kind("warning")
    assert limits.FULL_WARNINGS <= len(warnings) <= limits.FULL_WARNINGS + 3 + (faulty_at - started)
    assert "not protocol" in warnings[0].data["message"]
    faulty = next(s for s in state_events(recorder, "loco") if s["state"] == "faulty")
    assert f"within {limits.FAULTY_WINDOW:g} s (limit {limits.FAULTY_LINES})" in faulty["reason"]


@pytest.mark.parametrize("fault, says", [
    ("huge", "+ bytes (limit 1048576); ignored"),
    ("deep", f"nested deeper than {p.MAX_DEPTH} levels"),
])
def test_a_huge_or_deep_line_from_a_daemon_is_one_warning_and_service_goes_on(supervised, fault, says):
    sup, recorder = supervised(("loco",), programs={"loco": [sys.executable, str(FAULTY), fault]})
    started = time.monotonic()
    poll_until(sup, lambda: recorder.of_kind("warning"))
    report(f"loco {fault} line out", time.monotonic() - started)
    ping = sup.wait(sup.client("loco").request("ping"))
    assert ping.ok and sup.phase("loco") == "ready"
    [warning] = recorder.of_kind("warning")
    assert says in warning.data["message"]


def test_bad_numbers_in_a_reply_fail_that_request_and_never_reach_the_world(supervised):
    sup, recorder = supervised(("loco",), programs={"loco": [sys.executable, str(FAULTY), "bad_numbers"]})
    loco = sup.client("loco")
    reasons = []
    for _ in range(4):  # a string, NaN, Infinity, 1e400 in turn
        reply = sup.wait(loco.request("turn", {"angle": 0.1}), timeout=5.0)
        assert reply.error_code == "backend_error" and "malformed reply" in reply.reason
        reasons.append(reply.reason)
    assert "'x' must be a finite number, got 'abc'" in reasons[0] or "x must be a finite number" in reasons[0]
    assert "NaN is not a number" in reasons[1]
    assert "Infinity is not a number" in reasons[2]
    assert "too large for a float" in reasons[3]
    assert sup.phase("loco") == "ready"


# -- framework -> daemon ----------------------------------------------------------------------

GARBAGE_IN = {
    "garbage": (b"hello daemon\x00\xff\n", None, "not JSON"),
    "10 MB line": (b'{"id": "big", "cmd": "ping", "args": {"x": "' + b"a" * 10_000_000 + b'"}}\n', None,
                   "exceeds the 1048576-byte limit"),
    "300k nested brackets": (b"[" * 300_000 + b"\n", None, f"nested deeper than {p.MAX_DEPTH} levels"),
    "NaN argument": (b'{"id": "n1", "cmd": "ping", "args": {"x": NaN}}\n', "n1", "NaN is not a number"),
}


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize("fault", GARBAGE_IN)
def test_a_daemon_answers_bad_input_with_bad_request_and_goes_on(family, fault):
    line, request_id, says = GARBAGE_IN[fault]
    daemon = Daemon.dry(family)
    started = time.monotonic()
    daemon.proc.stdin.write(line)
    daemon.proc.stdin.flush()
    error = daemon.wait_for(lambda m: m.get("type") == "error" and m.get("id") == request_id, timeout=10.0)
    report(f"{family} {fault} in", time.monotonic() - started)
    assert error["code"] == "bad_request" and says in error["reason"]
    daemon.send({"id": "after", "cmd": "ping"})
    assert daemon.reply("after")["type"] == "done"
    daemon.proc.stdin.close()
    code, _, stderr = daemon.finish()
    assert code == 0 and "Traceback" not in stderr


@pytest.mark.parametrize("family", ["loco", "tts", "gesture"])
def test_a_framework_that_falls_silent_mid_command_leaves_the_daemon_stopped(family):
    """Silence in the framework -> daemon direction: the watchdog ends the running command."""
    daemon = Daemon([sys.executable, "-m", f"stuart_bt.skills.{family}", "--backend", "dry", "--watchdog", "0.5"])
    cmd, args = BUSY[family]
    daemon.send({"id": "busy", "cmd": cmd, "args": args})
    accepted = daemon.reply("busy", "accepted")
    assert accepted["type"] == "accepted"
    silent_from = time.monotonic()
    stopped = daemon.wait_for(lambda m: m.get("id") == "busy" and m.get("type") == "error", timeout=10.0)
    report(f"{family} framework silence", time.monotonic() - silent_from)
    assert stopped["code"] == "watchdog" and "heard nothing from its framework" in stopped["reason"]
    daemon.proc.stdin.close()
    assert daemon.finish()[0] == 0
