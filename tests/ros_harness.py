"""Drive a ``stuart-bt ros`` bridge from other processes, for the ROS tests and bench/ros.py.

:func:`ros_env` confines DDS to this machine and to a domain of this test session;
:class:`BridgeProcess` runs the bridge command; :class:`RosClient` runs tests/ros_client.py (a
plain rclpy program that knows only topic names) and collects what it receives.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

CLIENT = Path(__file__).with_name("ros_client.py")
START_WAIT = 60.0  # wall seconds for a bridge (daemons, a sim world) to come up


def session_domain_id() -> int:
    """A ROS domain of this test session (1..100), so helpers testing at once do not meet."""
    return 1 + os.getpid() % 100


def ros_env(domain_id: int | None = None) -> dict[str, str]:
    env = dict(os.environ)
    env["ROS_DOMAIN_ID"] = str(domain_id if domain_id is not None else session_domain_id())
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"  # DDS discovery never leaves the machine
    env.pop("ROS_STATIC_PEERS", None)
    env["PYTHONUNBUFFERED"] = "1"
    return env


class Lines:
    """A process's stdout lines, read on a thread, kept in order."""

    def __init__(self, stream: Any) -> None:
        self.lines: list[str] = []
        self._cond = threading.Condition()
        threading.Thread(target=self._read, args=(stream,), daemon=True).start()

    def _read(self, stream: Any) -> None:
        for line in iter(stream.readline, ""):
            with self._cond:
                self.lines.append(line.rstrip("\n"))
                self._cond.notify_all()

    def wait_for(self, pred: Callable[[str], bool], timeout: float, since: int = 0) -> str | None:
        """The first line from index ``since`` on that ``pred`` accepts, waiting for it; each line
        is looked at once."""
        deadline = time.monotonic() + timeout
        index = since
        with self._cond:
            while True:
                while index < len(self.lines):
                    if pred(self.lines[index]):
                        return self.lines[index]
                    index += 1
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    return None
                self._cond.wait(remaining)


class BridgeProcess:
    """``stuart-bt ros ARGS`` in its own process; ``up()`` waits for its ready line."""

    def __init__(self, *args: str, env: dict[str, str] | None = None, stdin: int = subprocess.DEVNULL) -> None:
        """``stdin=subprocess.PIPE`` to feed it (``--hear -``: raw PCM, written with ``feed``)."""
        self.proc = subprocess.Popen([sys.executable, "-m", "stuart_bt.cli", "ros", *args], env=env or ros_env(),
                                     stdin=stdin, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.out = Lines(io.TextIOWrapper(self.proc.stdout, encoding="utf-8"))
        self.err = Lines(io.TextIOWrapper(self.proc.stderr, encoding="utf-8"))

    def feed(self, data: bytes) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.write(data)
        self.proc.stdin.flush()

    def up(self) -> str:
        line = self.out.wait_for(lambda x: x.startswith("ros bridge: node"), START_WAIT)
        if line is None:
            self.stop()
            raise RuntimeError(f"the bridge did not come up: {self.err.lines[-5:]}")
        return line

    def descendants(self) -> list[tuple[int, str]]:
        """(pid, start time) of every process below the bridge, now."""
        return descendants(self.proc.pid)

    def stop(self, sig: int = signal.SIGTERM, timeout: float = 60.0) -> int:
        if self.proc.stdin is not None and not self.proc.stdin.closed:
            with contextlib.suppress(OSError):
                self.proc.stdin.close()
        if self.proc.poll() is None:
            self.proc.send_signal(sig)
        try:
            return self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            return self.proc.wait()

    def __enter__(self) -> BridgeProcess:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()


class RosClient:
    """tests/ros_client.py in its own process."""

    def __init__(self, namespace: str = "/", env: dict[str, str] | None = None) -> None:
        self.proc = subprocess.Popen([sys.executable, str(CLIENT), namespace], env=env or ros_env(),
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True)
        self.out = Lines(self.proc.stdout)
        self.err = Lines(self.proc.stderr)
        if self.out.wait_for(lambda x: '"ready"' in x, START_WAIT) is None:
            raise RuntimeError("the ROS client did not start")

    @property
    def received(self) -> list[dict[str, Any]]:
        return [json.loads(x) for x in list(self.out.lines) if x.startswith("{")]

    def on(self, topic: str) -> list[dict[str, Any]]:
        return [m for m in self.received if m.get("topic") == topic]

    @property
    def mark(self) -> int:
        """The number of lines received so far: pass it as ``since`` to wait for later ones."""
        return len(self.out.lines)

    def publish(self, topic: str, data: Any, int32: bool = False) -> float:
        """Publish on ``topic`` (relative to the client's namespace); the client's send time."""
        since = self.mark
        self.proc.stdin.write(json.dumps({"pub_int" if int32 else "pub": topic, "data": data}) + "\n")
        self.proc.stdin.flush()
        line = self.out.wait_for(lambda x: x.startswith('{"sent"'), 30, since)
        if line is None:
            raise RuntimeError(f"the client did not publish on {topic}: {self.err.lines[-3:]}")
        return json.loads(line)["t"]

    def wait_for(self, pred: Callable[[dict[str, Any]], bool], timeout: float = 60.0,
                 since: int = 0) -> dict[str, Any] | None:
        """The first message (from line ``since`` on) that ``pred`` accepts, waiting for it."""
        def match(line: str) -> bool:
            try:
                return line.startswith("{") and pred(json.loads(line))
            except (ValueError, KeyError, TypeError):
                return False

        line = self.out.wait_for(match, timeout, since)
        return json.loads(line) if line else None

    def close(self) -> None:
        if self.proc.poll() is None:
            try:
                self.proc.stdin.write('{"quit": true}\n')
                self.proc.stdin.flush()
                self.proc.wait(10)
            except (OSError, subprocess.TimeoutExpired):
                self.proc.kill()
                self.proc.wait()

    def __enter__(self) -> RosClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def descendants(pid: int) -> list[tuple[int, str]]:
    """(pid, start time) of every live process below ``pid``, from /proc."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            stat = _stat(int(entry.name))
            if stat is not None:
                children.setdefault(int(stat[1]), []).append(int(entry.name))
    out: list[tuple[int, str]] = []
    stack = list(children.get(pid, []))
    while stack:
        child = stack.pop()
        stat = _stat(child)
        if stat is not None:
            out.append((child, stat[19]))
            stack += children.get(child, [])
    return out


def alive(proc: tuple[int, str]) -> bool:
    """Whether that process (same pid and start time) still runs (a zombie does not count)."""
    stat = _stat(proc[0])
    return stat is not None and stat[19] == proc[1] and stat[0] != "Z"


def _stat(pid: int) -> list[str] | None:
    """/proc/PID/stat fields after the command name: state, ppid, ... (index 19: start time)."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    return text[text.rindex(")") + 2:].split()
