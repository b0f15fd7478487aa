"""The shared daemon loop: how a daemon ends (EOF, signals, shutdown), stray output, preemption."""

from __future__ import annotations

import json
import os
import select
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from stuart_bt.core.clock import ScaledClock
from stuart_bt.daemon import protocol as p

NOISY = Path(__file__).parent / "fakes" / "noisy_daemon.py"
LONG_WALK = {"pose": {"x": 40.0, "y": 0.0, "yaw": None}}  # 80 s of clock time: still walking when we act


class Daemon:
    """A daemon process on raw pipes (stderr kept apart, to check it for tracebacks)."""

    started: list[Daemon] = []  # reaped after each test by the autouse fixture

    def __init__(self, argv: list[str]) -> None:
        Daemon.started.append(self)
        self.proc = subprocess.Popen([*argv, "--clock", ScaledClock(20).spec(), "--heartbeat", "0.05"],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self._buffer = b""
        self.lines: list[bytes] = []
        self.ready = self.wait_for(lambda m: m.get("type") == "ready")

    @classmethod
    def dry(cls, family: str) -> Daemon:
        return cls([sys.executable, "-m", f"stuart_bt.skills.{family}", "--backend", "dry"])

    def send(self, message: dict[str, Any]) -> None:
        self.proc.stdin.write(p.encode(message))
        self.proc.stdin.flush()

    def messages(self) -> list[dict[str, Any]]:
        return [json.loads(line) for line in self.lines]

    def wait_for(self, match: Any, timeout: float = 3.0) -> dict[str, Any]:
        deadline = time.monotonic() + timeout
        while True:
            while b"\n" in self._buffer:
                raw, self._buffer = self._buffer.split(b"\n", 1)
                self.lines.append(raw)
                if match(json.loads(raw)):
                    return json.loads(raw)
            remaining = deadline - time.monotonic()
            assert remaining > 0, f"no matching line within {timeout} s; got {self.lines[-5:]}"
            if select.select([self.proc.stdout], [], [], remaining)[0]:
                chunk = os.read(self.proc.stdout.fileno(), 1 << 16)
                assert chunk, f"daemon closed its output; got {self.lines[-5:]}"
                self._buffer += chunk

    def reply(self, request_id: str, *types: str) -> dict[str, Any]:
        types = types or ("done", "error")
        return self.wait_for(lambda m: m.get("id") == request_id and m.get("type") in types)

    def finish(self, timeout: float = 3.0) -> tuple[int, list[dict[str, Any]], str]:
        """Exit code, every remaining protocol line, and all of stderr, once the process ended."""
        self.proc.wait(timeout)  # the little it still writes fits in the pipes
        out, err = self.proc.stdout.read(), self.proc.stderr.read()
        self.lines += [line for line in (self._buffer + out).split(b"\n") if line]
        return self.proc.returncode, self.messages(), err.decode()


@pytest.fixture(autouse=True)
def reap_daemons():
    yield
    for daemon in Daemon.started:
        if daemon.proc.returncode is None:
            daemon.proc.kill()
            daemon.proc.wait()
        for pipe in (daemon.proc.stdin, daemon.proc.stdout, daemon.proc.stderr):
            pipe.close()
    Daemon.started.clear()


def test_stdin_eof_stops_the_walk_and_exits_0_within_a_second():
    loco = Daemon.dry("loco")
    loco.send({"id": "w", "cmd": "navigate", "args": LONG_WALK})
    loco.reply("w", "accepted")
    started = time.monotonic()
    loco.proc.stdin.close()
    code, messages, _ = loco.finish()
    assert time.monotonic() - started < 1.0
    assert code == 0
    stopped = next(m for m in messages if m.get("id") == "w" and m["type"] == "error")
    assert stopped["code"] == "stopped" and "stdin closed" in stopped["reason"]
    assert 0.0 < stopped["data"]["pose"]["x"] < 40.0


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_stops_the_walk_and_exits_0_without_a_traceback(sig):
    loco = Daemon.dry("loco")
    loco.send({"id": "w", "cmd": "navigate", "args": LONG_WALK})
    loco.reply("w", "accepted")
    loco.proc.send_signal(sig)
    code, messages, stderr = loco.finish()
    assert code == 0
    assert "Traceback" not in stderr
    stopped = next(m for m in messages if m.get("id") == "w" and m["type"] == "error")
    assert stopped["code"] == "stopped" and sig.name in stopped["reason"]


def test_shutdown_stops_then_answers_then_exits_0():
    tts = Daemon.dry("tts")
    tts.send({"id": "s", "cmd": "say", "args": {"text": "a rather long sentence " * 20}})
    tts.send({"id": "bye", "cmd": "shutdown"})
    code, messages, _ = tts.finish()
    assert code == 0
    trace = [(m["id"], m["type"], m.get("code")) for m in messages if m.get("id") in ("s", "bye")]
    assert trace == [("s", "accepted", None), ("s", "error", "stopped"), ("bye", "done", None)]


def test_stray_prints_from_a_backend_go_to_stderr_not_the_protocol():
    noisy = Daemon([sys.executable, str(NOISY), "--backend", "noisy"])
    noisy.send({"id": "c1", "cmd": "chatter"})
    assert noisy.reply("c1")["result"] == {"printed": True}
    noisy.proc.stdin.close()
    code, messages, stderr = noisy.finish()
    assert code == 0
    assert all(line.startswith(b"{") for line in noisy.lines)  # every stdout line is protocol JSON
    assert [m for m in messages if m.get("id") == "fake"] == []
    for printed in ("SDK banner from Python print", "raw write to fd 1", "C puts to stdout",
                    "python print while polling", "chatter"):
        assert printed in stderr


def test_a_backend_exception_is_a_backend_error_and_the_daemon_survives():
    noisy = Daemon([sys.executable, str(NOISY), "--backend", "noisy"])
    noisy.send({"id": "b1", "cmd": "boom"})
    error = noisy.reply("b1")
    assert (error["code"], error["reason"]) == ("backend_error", "RuntimeError: simulated backend bug")
    log = next(m for m in noisy.messages() if m.get("type") == "log")
    assert log["level"] == "error" and "simulated backend bug" in log["message"]
    noisy.send({"id": "after", "cmd": "ping"})
    assert noisy.reply("after")["type"] == "done"
    noisy.proc.stdin.close()
    assert noisy.finish()[0] == 0


def test_an_unknown_backend_exits_2_before_ready_naming_the_valid_ones():
    result = subprocess.run([sys.executable, "-m", "stuart_bt.skills.pick", "--backend", "unitre"],
                            capture_output=True, timeout=10)
    assert result.returncode == 2
    assert result.stdout == b""
    assert "unknown backend 'unitre'" in result.stderr.decode() and "valid backends: dry" in result.stderr.decode()


def test_a_newer_walk_preempts_the_running_one_from_where_it_froze():
    loco = Daemon.dry("loco")
    loco.send({"id": "w1", "cmd": "navigate", "args": LONG_WALK})
    loco.reply("w1", "accepted")
    time.sleep(0.1)
    loco.send({"id": "w2", "cmd": "turn", "args": {"angle": 0.8}})
    preempted = loco.reply("w1")
    assert preempted["code"] == "preempted" and preempted["reason"] == "turn w2 took the motion"
    frozen = preempted["data"]["pose"]
    done = loco.reply("w2")
    assert done["result"]["pose"] == {"x": frozen["x"], "y": 0.0, "yaw": 0.8}


def test_a_rejected_command_leaves_the_running_one_alone():
    loco = Daemon.dry("loco")
    loco.send({"id": "w1", "cmd": "navigate", "args": LONG_WALK})
    loco.send({"id": "bad", "cmd": "navigate", "args": {"pose": {"x": "nowhere", "y": 0}}})
    assert loco.reply("bad")["code"] == "bad_request"
    loco.send({"id": "st", "cmd": "state"})
    assert loco.reply("st")["result"]["moving"] is True
    assert [m["type"] for m in loco.messages() if m.get("id") == "w1"][-1] in ("accepted", "progress")


def test_cancel_ends_only_its_target():
    tts = Daemon.dry("tts")
    tts.send({"id": "s1", "cmd": "say", "args": {"text": "one two three four five six seven eight"}})
    tts.send({"id": "c1", "cmd": "cancel", "args": {"target": "s1"}})
    cancelled = tts.reply("s1")
    assert (cancelled["code"], cancelled["reason"]) == ("cancelled", "cancelled by c1")
    assert tts.reply("c1")["result"] == {"target": "s1", "cancelled": True}
    tts.send({"id": "c2", "cmd": "cancel", "args": {"target": "s1"}})
    assert tts.reply("c2")["result"] == {"target": "s1", "cancelled": False}  # already over: no error


def test_a_request_id_already_running_is_refused():
    tts = Daemon.dry("tts")
    tts.send({"id": "s1", "cmd": "say", "args": {"text": "a long sentence to keep the voice busy for a while"}})
    tts.reply("s1", "accepted")
    tts.send({"id": "s1", "cmd": "ping"})
    assert tts.reply("s1")["reason"] == "request id 's1' is already running"
