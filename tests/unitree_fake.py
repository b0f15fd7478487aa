"""The test side of the fake G1 (tests/fakes/unitree_services.py): start it on a private DDS
domain on loopback, read what it recorded, script its faults.

Nothing here imports the vendor SDK: the fake runs in its own process, like the robot would.
"""

from __future__ import annotations

import collections
import contextlib
import itertools
import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

FAKE = Path(__file__).parent / "fakes" / "unitree_services.py"
DOMAINS = range(160, 230)
SYNC_TIMEOUT = 30.0  # wall seconds for the fake to answer a ping behind the records it owes (a loaded machine)
START_TIMEOUT = 60.0  # wall seconds for the fake to answer on its own services (a loaded machine)
_start = itertools.count((os.getpid() * 7) % len(DOMAINS))


def private_domain() -> tuple[int, socket.socket]:
    """A DDS domain id no other fake on this machine holds (any test run, any checkout), and the
    claim on it: a Unix socket bound to a name in the abstract namespace, which only one process
    can hold and which vanishes with the process that holds it, so a killed run leaves neither a
    stale claim nor a file behind. Returns (domain, claim); close the claim to free the domain."""
    first = next(_start)
    for k in range(len(DOMAINS)):
        domain = DOMAINS[(first + k) % len(DOMAINS)]
        claim = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
        try:
            claim.bind(f"\0stuart_bt-dds-domain-{domain}")
            return domain, claim
        except OSError:
            claim.close()
    raise RuntimeError(f"every test DDS domain {DOMAINS.start}..{DOMAINS.stop - 1} is in use")


class FakeRobot:
    """A running fake robot; ``records`` grows as the fake reports requests and samples."""

    def __init__(self, domain: int | None = None, nav_speed: float = 4.0, silent: str = "") -> None:
        pytest.importorskip("unitree_sdk2py", reason="the unitree backend needs the 'robot' extra")
        self._domain_lock = None
        if domain is None:
            domain, self._domain_lock = private_domain()
        self.domain = domain
        self.records: list[dict[str, Any]] = []
        self._lock = threading.Lock()
        self._pings = 0
        self.stderr: collections.deque[str] = collections.deque(maxlen=20)  # its last words, for errors
        self.proc = subprocess.Popen(
            [sys.executable, str(FAKE), "--domain", str(self.domain), "--nav-speed", str(nav_speed),
             "--silent", silent],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
            start_new_session=True)  # its own process group: close() ends it and anything it started
        threading.Thread(target=self._read, daemon=True).start()
        threading.Thread(target=self._read_stderr, daemon=True).start()
        try:
            self.wait_for(lambda r: r["kind"] == "ready", timeout=START_TIMEOUT, what="the fake robot to start")
        except BaseException:  # noqa: BLE001 - whatever stopped the start, the fake is ended, then it goes on up
            self.close()
            raise AssertionError(f"the fake robot did not start on DDS domain {self.domain} within "
                                 f"{START_TIMEOUT:g} s; its stderr ends: {list(self.stderr)[-5:]}") from None

    @property
    def env(self) -> dict[str, str]:
        """Environment for a daemon or CLI process that should talk to this fake."""
        return {**os.environ, "STUART_UNITREE_INTERFACE": "lo", "STUART_UNITREE_DOMAIN": str(self.domain)}

    def options(self, **extra: Any) -> dict[str, Any]:
        return {"interface": "lo", "domain": self.domain, **extra}

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            record = json.loads(line)
            with self._lock:
                self.records.append(record)

    def _read_stderr(self) -> None:
        assert self.proc.stderr is not None
        for line in self.proc.stderr:
            self.stderr.append(line.decode("utf-8", "replace").rstrip())

    def sync(self) -> None:
        """Wait until every request the fake answered so far has been read here (its records
        are written before its answers, and a pong after them)."""
        self._pings += 1
        n, mark = self._pings, len(self.records)
        self.order(ping=n)
        self.wait_for(lambda r: r["kind"] == "pong" and r["n"] == n, timeout=SYNC_TIMEOUT, what="the fake's pong",
                      since=mark)

    def rpc(self, service: str | None = None, api: int | None = None) -> list[dict[str, Any]]:
        """Requests the fake answered (up to now: synced first)."""
        self.sync()
        with self._lock:
            return [r for r in self.records if r["kind"] == "rpc" and service in (None, r["service"])
                    and api in (None, r["api"])]

    def topic(self, name: str) -> list[dict[str, Any]]:
        """Samples the fake received on ``name`` (up to now: synced first)."""
        self.sync()
        with self._lock:
            return [r for r in self.records if r["kind"] == "topic" and r["topic"] == name]

    def order(self, **order: Any) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.write((json.dumps(order) + "\n").encode())
        self.proc.stdin.flush()

    def fault(self, service: str, api: int, code: int | None = None, times: int = 1) -> None:
        """The next ``times`` calls of ``api`` answer ``code`` (None: no answer at all)."""
        spec: dict[str, Any] = {"service": service, "api": api, "times": times}
        spec.update({"silent": True} if code is None else {"code": code})
        self.order(fault=spec)
        self.sync()  # the fake has taken it in before the test goes on: a request sent next meets the fault

    def wait_for(self, predicate: Callable[[dict[str, Any]], bool], timeout: float = 10.0,
                 what: str = "a record", since: int = 0) -> dict[str, Any]:
        """The first record from index ``since`` on that satisfies ``predicate``."""
        deadline = time.monotonic() + timeout
        seen = since
        while time.monotonic() < deadline:
            with self._lock:
                fresh = self.records[seen:]
                seen = len(self.records)
            for record in fresh:
                if predicate(record):
                    return record
            if self.proc.poll() is not None:
                break
            time.sleep(0.02)
        raise AssertionError(f"timed out waiting for {what}; last records: {self.records[-5:]}")

    def close(self) -> None:
        """End the fake: end of input first (it exits at once), then SIGKILL to its process group."""
        if self.proc.stdin:
            with contextlib.suppress(OSError):
                self.proc.stdin.close()
        with contextlib.suppress(subprocess.TimeoutExpired):
            self.proc.wait(timeout=5)
        with contextlib.suppress(ProcessLookupError, PermissionError):  # the fake, or anything left in its group
            os.killpg(self.proc.pid, signal.SIGKILL)
        self.proc.wait()
        if self._domain_lock is not None:
            self._domain_lock.close()  # the domain is free for the next fake

    def __enter__(self) -> FakeRobot:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


# -- fixtures the unitree test files import --------------------------------------------------------

@pytest.fixture(scope="module")
def robot_of_this_file():
    """One fake robot per test file (starting one takes a few seconds), or the reason it could
    not start: kept, so the file reports that once instead of once per test."""
    try:
        fake = FakeRobot(nav_speed=8.0)
    except AssertionError as failure:
        yield failure
        return
    with fake:
        yield fake


@pytest.fixture
def robot(robot_of_this_file, request):
    """The test file's fake robot. If it failed to start, the first test that asks for it fails
    with the reason and the others in the file are skipped, naming that failure."""
    if isinstance(robot_of_this_file, AssertionError):
        if getattr(request.module, "_fake_robot_failure_reported", False):
            pytest.skip(f"the fake robot of this file did not start (reported above): {robot_of_this_file}")
        request.module._fake_robot_failure_reported = True
        raise robot_of_this_file
    return robot_of_this_file


def supervisor(backend: str, family: str, options: dict[str, Any], run_dir: Path, factor: float = 1.0) -> Any:
    """A supervisor of one ``family`` daemon with ``backend`` and ``options``, an event recorder on
    its events, not started yet (the caller starts it and shuts it down)."""
    from stuart_bt.core.clock import ScaledClock
    from stuart_bt.core.events import EventRecorder, EventStream
    from stuart_bt.daemon.supervisor import Supervisor

    clock = ScaledClock(factor)
    sup = Supervisor(backend, clock, EventStream(clock), families=(family,), options={family: options},
                     run_dir=run_dir, handshake_timeout=30.0)
    sup.recorder = EventRecorder(sup.events)
    return sup


@pytest.fixture
def unitree_daemon(robot, tmp_path):
    """``unitree_daemon(family, factor=1.0, **options)``: a started unitree daemon talking to
    ``robot``; shut down after the test."""
    made: list[Any] = []

    def start(family: str, factor: float = 1.0, **options: Any) -> Any:
        sup = supervisor("unitree", family, robot.options(**options), tmp_path, factor)
        made.append(sup)
        sup.start()
        return sup

    yield start
    for sup in made:
        sup.shutdown()


def start_failure(family: str, options: dict[str, Any], run_dir: Path, backend: str = "unitree") -> str:
    """The message of the DaemonStartError a ``backend`` daemon with ``options`` gives."""
    from stuart_bt.daemon.supervisor import DaemonStartError

    sup = supervisor(backend, family, options, run_dir)
    try:
        with pytest.raises(DaemonStartError) as err:
            sup.start()
    finally:
        sup.shutdown()
    return str(err.value)
