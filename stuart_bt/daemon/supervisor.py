"""Starts one daemon process per skill family, watches them, restarts them, stops them.

The executor calls :meth:`Supervisor.poll` once per tick: one ``select`` with timeout 0 over
every daemon's output, a read of what is there, then cheap checks for a crash (EOF or exit) or
a hang (no heartbeat). A lost daemon's in-flight requests fail at once with ``daemon_died`` or
``daemon_hung`` so the tree can react, and the daemon is restarted with exponential backoff
without blocking the tick.

Daemons run in their own session, so a Ctrl-C in the terminal reaches only the tree process,
which then stops them itself. If the tree process dies anyway, each daemon sees stdin EOF (and
on Linux a PR_SET_PDEATHSIG SIGTERM) and stops the robot. Linux sends that signal when the
*thread* that spawned the daemon exits, so use a supervisor from one long-lived thread.

Not thread-safe: one thread (the executor's) owns a supervisor.
"""

from __future__ import annotations

import atexit
import contextlib
import json
import math
import os
import select
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..core.catalogue import FAMILIES
from ..core.clock import Clock
from ..core.errors import StuartError
from ..core.events import EventStream
from ..core.suggest import did_you_mean
from .client import DaemonClient, Request

EXIT_WAIT = 0.2  # seconds to wait for the exit status after a daemon closed its output
KILL_WAIT = 0.5  # seconds between SIGTERM and SIGKILL at shutdown
STDERR_TAIL_LINES = 8


class DaemonStartError(StuartError, RuntimeError):
    """A daemon did not come up; the message names it and quotes the end of its stderr."""


@dataclass(eq=False)
class _Daemon:
    """Book-keeping for one family: its client, current process and restart schedule."""

    family: str
    client: DaemonClient
    log_path: Path
    proc: subprocess.Popen[bytes] | None = None
    phase: str = "down"  # starting | ready | down | stopped
    spawned_at: float = 0.0
    ready_at: float = 0.0
    log_offset: int = 0  # where this process's stderr starts in the log file
    failures: int = 0  # consecutive losses, for the backoff
    restart_at: float | None = None

    @property
    def process(self) -> subprocess.Popen[bytes]:
        """The current process; only asked for once one was spawned."""
        assert self.proc is not None, f"{self.family} daemon was never started"
        return self.proc


class _Outputs:
    """The daemons' output pipes, waited on with ``select.poll`` itself: the selectors module's
    wrapper around it was a measurable share of a round trip (docs/protocol.md)."""

    def __init__(self) -> None:
        self._poller = select.poll()
        self._daemons: dict[int, _Daemon] = {}

    def add(self, fd: int, daemon: _Daemon) -> None:
        self._poller.register(fd, select.POLLIN)
        self._daemons[fd] = daemon

    def remove(self, fd: int) -> None:
        """Stop watching ``fd`` (nothing happens if it is not watched)."""
        if self._daemons.pop(fd, None) is not None:
            self._poller.unregister(fd)

    def ready(self, timeout: float) -> list[_Daemon]:
        """The daemons with output (or an end of output) to read, waiting up to ``timeout`` s."""
        daemons = self._daemons
        ready = []
        for fd, events in self._poller.poll(timeout * 1000.0):
            d = daemons[fd]
            d.client.hung_up = bool(events & _HANG_UP)  # the daemon closed its end: read to the end now
            ready.append(d)
        return ready


_HANG_UP = select.POLLHUP | select.POLLERR


class Supervisor:
    """The daemons of one run: ``backend`` (dry, sim, unitree) for every family."""

    def __init__(
        self,
        backend: str,
        clock: Clock,
        events: EventStream,
        families: Iterable[str] = FAMILIES,
        options: Mapping[str, dict[str, Any]] | None = None,
        handshake_timeout: float = 10.0,
        heartbeat_timeout: float = 1.0,
        restart_backoff: tuple[float, float] = (0.2, 5.0),
        *,
        heartbeat_period: float = 0.1,
        watchdog: float = 0.0,
        programs: Mapping[str, Sequence[str]] | None = None,
        run_dir: str | Path | None = None,
        stalled: Callable[[], bool] | None = None,
    ) -> None:
        """``programs`` replaces ``python -m stuart_bt.skills.<family>`` for some families (tests,
        out-of-tree daemons); ``run_dir`` receives ``<family>.stderr.log`` (default: a temp dir).
        ``watchdog`` (wall seconds, 0: off): each daemon stops running motion when :meth:`poll`
        has sent it nothing for that long (poll sends a keep-alive every quarter of it), so a
        frozen framework leaves a stopped robot; poll at the tick rate, as the executor does.
        ``stalled`` says whether something every daemon may be waiting on stands still (the
        simulator's world, frozen or starved): time while it does, and ``heartbeat_timeout``
        after, does not count towards a hang, since restarting a daemon cannot help then."""
        self.backend = backend
        self.clock = clock
        self.events = events
        self.options = dict(options or {})
        self.handshake_timeout = handshake_timeout
        self.heartbeat_timeout = heartbeat_timeout
        self.restart_backoff = restart_backoff
        self.heartbeat_period = heartbeat_period
        self.watchdog = watchdog
        self._next_keep_alive = 0.0
        self._next_check = 0.0  # wall time the health checks are next due in wait()
        self.programs = dict(programs or {})
        self.run_dir = Path(run_dir) if run_dir else Path(tempfile.mkdtemp(prefix="stuart_bt-daemons-"))
        self.run_dir.mkdir(parents=True, exist_ok=True)
        self._daemons = {
            f: _Daemon(f, DaemonClient(f, events), self.run_dir / f"{f}.stderr.log") for f in families
        }
        self._outputs = _Outputs()
        self._stalled = stalled
        self._stood_still_at = -math.inf  # wall time the thing daemons wait on was last seen standing still
        self._zombies: list[subprocess.Popen[bytes]] = []  # killed, not yet reaped
        self._started = False
        self._closed = False

    # -- public API ---------------------------------------------------------------------------

    def start(self) -> None:
        """Spawn every daemon at once and wait until all sent READY (or raise DaemonStartError)."""
        if self._started:
            return
        self._started = True
        atexit.register(self.shutdown)
        try:
            for d in self._daemons.values():
                self._spawn(d)
            self._await_handshakes()
        except BaseException:
            self.shutdown()
            raise

    def client(self, family: str) -> DaemonClient:
        if family not in self._daemons:
            raise KeyError(f"no {family!r} daemon{did_you_mean(family, self._daemons)}; "
                           f"families: {', '.join(self._daemons)}")
        return self._daemons[family].client

    @property
    def families(self) -> list[str]:
        return list(self._daemons)

    def phase(self, family: str) -> str:
        """``starting``, ``ready``, ``down`` (restart pending) or ``stopped``."""
        return self._daemons[family].phase

    def pid(self, family: str) -> int | None:
        proc = self._daemons[family].proc
        return proc.pid if proc else None

    def poll(self) -> None:
        """Read what the daemons sent, then check for crashes, hangs and due restarts (no blocking)."""
        if not self._closed:
            self._poll(self._outputs.ready(0))

    def wait(self, request: Request, timeout: float | None = 10.0) -> Request:
        """Block until ``request`` finishes or ``timeout`` wall seconds pass (then it comes back
        unfinished: check ``.finished``), polling every daemon meanwhile.

        A daemon's death or flood is acted on as soon as its output shows it; the checks that
        only time can trigger (a hang, a due restart) run at least every :attr:`check_period`.
        Running them on every wake-up instead cost as much as the round trip's own work."""
        deadline = time.monotonic() + (timeout if timeout is not None else float("inf"))
        block = 0.0 if request.finished else self.check_period  # a finished request: one look
        # No look before blocking: select returns as soon as a reply is there, and a look at
        # once (the reply is never there yet) cost a second select and a second round of checks.
        while not self._closed:
            ready = self._outputs.ready(max(0.0, min(deadline - time.monotonic(), block)))
            now = self._poll(ready) if time.monotonic() >= self._next_check else self._read(ready)
            if request.finished or now >= deadline:
                break
        return request

    @property
    def check_period(self) -> float:
        """Wall seconds between two health checks while :meth:`wait` blocks."""
        return min(0.05, self.heartbeat_timeout / 4)

    def stop_all(self) -> list[Request]:
        """Send ``stop`` to every live daemon at once; the handles finish as they acknowledge."""
        return [d.client.stop() for d in self._daemons.values() if d.client.connected]

    def shutdown(self, timeout: float = 2.0) -> None:
        """Stop the robot, end every daemon and reap it: shutdown command and stdin EOF first,
        then SIGTERM, then SIGKILL. Safe to call twice; also runs at interpreter exit."""
        if self._closed:
            return
        self._closed = True
        atexit.unregister(self.shutdown)
        live = [d for d in self._daemons.values() if d.client.connected]
        self.stop_all()
        for d in live:
            d.client.request("shutdown")
            d.client.close_input()
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline and any(d.proc and d.proc.poll() is None for d in live):
            for d in self._outputs.ready(0.02):
                d.client.poll()
                if d.client.eof:
                    self._outputs.remove(d.client.fileno())
        for d in live:  # replies that arrived with the exit
            d.client.poll()
        for sig, wait in ((signal.SIGTERM, KILL_WAIT), (signal.SIGKILL, None)):
            alive = [d.proc for d in live if d.proc and d.proc.poll() is None]
            for proc in alive:
                _signal_group(proc, sig)
            for proc in alive:
                with contextlib.suppress(subprocess.TimeoutExpired):
                    proc.wait(wait)
        for d in self._daemons.values():
            if d.client.connected:
                self._disconnect(d, "daemon_down", f"{d.family} daemon was shut down")
            if d.phase != "stopped":
                d.phase = "stopped"
                self.events.publish("daemon_state", family=d.family, state="stopped", reason="shutdown")
        for proc in self._zombies:
            proc.wait()
        self._zombies.clear()

    def __enter__(self) -> Supervisor:
        self.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.shutdown()

    # -- processes ----------------------------------------------------------------------------

    def _argv(self, family: str) -> list[str]:
        program = self.programs.get(family) or [sys.executable, "-m", f"stuart_bt.skills.{family}"]
        return [*program, "--backend", self.backend, "--clock", self.clock.spec(),
                "--options", json.dumps(self.options.get(family, {})), "--heartbeat", str(self.heartbeat_period),
                *(["--watchdog", str(self.watchdog)] if self.watchdog > 0 else [])]

    def _spawn(self, d: _Daemon) -> None:
        argv = self._argv(d.family)
        with open(d.log_path, "ab") as log:
            log.write(f"--- {time.strftime('%Y-%m-%d %H:%M:%S')} {' '.join(argv)}\n".encode())
            log.flush()
            d.log_offset = log.tell()
            to_child, to_daemon = os.pipe()
            from_daemon, from_child = os.pipe()
            try:
                d.proc = subprocess.Popen(argv, stdin=to_child, stdout=from_child, stderr=log,
                                          start_new_session=True, env={**os.environ, "PYTHONUNBUFFERED": "1"})
            except OSError as e:
                for fd in (to_daemon, from_daemon):
                    os.close(fd)
                raise DaemonStartError(f"{d.family} daemon could not be started ({argv[0]}): {e}") from None
            finally:
                os.close(to_child)
                os.close(from_child)
        os.set_blocking(to_daemon, False)
        os.set_blocking(from_daemon, False)
        d.client.attach(to_daemon, from_daemon)
        self._outputs.add(from_daemon, d)
        d.phase, d.spawned_at, d.restart_at = "starting", time.monotonic(), None
        restart = f", restart after {d.failures} loss(es)" if d.failures else ""
        self.events.publish("daemon_state", family=d.family, state="starting", reason=f"pid {d.proc.pid}{restart}",
                            pid=d.proc.pid)

    def _await_handshakes(self) -> None:
        deadline = time.monotonic() + self.handshake_timeout
        problems: list[str] = []
        waiting = list(self._daemons.values())
        while waiting:
            for d in self._outputs.ready(max(0.0, min(0.05, deadline - time.monotonic()))):
                d.client.poll()
            for d in list(waiting):
                if d.client.ready:
                    self._mark_ready(d, time.monotonic())
                    waiting.remove(d)
                elif d.client.eof or d.process.poll() is not None:
                    problems.append(f"{d.family} daemon failed to start: {self._exit_reason(d)} before READY"
                                    f"{self._stderr_tail(d)}")
                    waiting.remove(d)
            if waiting and time.monotonic() >= deadline:
                problems += [f"{d.family} daemon failed to start: no READY within {self.handshake_timeout} s"
                             f"{self._stderr_tail(d)}" for d in waiting]
                break
        if problems:
            raise DaemonStartError("; ".join(problems))

    def _poll(self, ready: list[_Daemon]) -> float:
        """Read, then check every daemon's health (and reap the killed ones); returns the time
        the checks ran at."""
        now = self._read(ready)
        self._next_check = now + self.check_period
        for d in self._daemons.values():
            self._check(d, now)
        if self._zombies:
            self._zombies = [z for z in self._zombies if z.poll() is None]
        return now

    def _read(self, ready: list[_Daemon]) -> float:
        """Take in what the ready daemons wrote and act at once on what their output shows (an
        end of output, a flood of bad lines, READY); keep the watchdog fed. Returns the time
        after reading."""
        for d in ready:
            d.client.poll()
            if d.client.eof or d.client.faulty or (d.phase == "starting" and d.client.ready):
                self._check(d, time.monotonic())
        now = time.monotonic()
        if self.watchdog > 0 and now >= self._next_keep_alive:
            self._next_keep_alive = now + self.watchdog / 4
            for d in self._daemons.values():
                if d.phase == "ready":
                    d.client.keep_alive()
        return now

    def _check(self, d: _Daemon, now: float) -> None:
        if d.phase == "down":
            self._restart_if_due(d, now)
            return
        if d.phase not in ("starting", "ready"):
            return
        d.client.tick(now)
        if d.phase == "starting" and d.client.ready and not d.client.eof:
            self._mark_ready(d, now)
        loss = self._loss(d, now)
        if loss is not None:
            self._lose(d, *loss, now)
        elif d.phase == "ready" and d.failures and now - d.ready_at > self.restart_backoff[1]:
            d.failures = 0  # up long enough: the next loss starts the backoff afresh

    def _restart_if_due(self, d: _Daemon, now: float) -> None:
        if d.restart_at is None or now < d.restart_at:
            return
        try:
            self._spawn(d)
        except DaemonStartError as e:
            delay = self._schedule_restart(d, now)
            self.events.publish("daemon_state", family=d.family, state="died", reason=str(e), failed=[],
                                restart_in=delay)

    def _loss(self, d: _Daemon, now: float) -> tuple[str, str, str] | None:
        """``(error code, state, reason)`` if the daemon is lost: exited, never ready, flooding,
        silent, or not answering its commands; None while it is healthy."""
        if d.client.eof or d.process.poll() is not None:
            return "daemon_died", "died", f"{d.family} daemon {self._exit_reason(d)}"
        if d.client.faulty and d.phase != "starting":
            return "daemon_faulty", "faulty", d.client.faulty
        waited_from = self._last_stall(now)  # silence while the world stood still is not counted
        if d.phase == "starting":
            if now - max(d.spawned_at, waited_from) > self.handshake_timeout:
                return "daemon_hung", "hung", f"{d.family} daemon sent no READY within {self.handshake_timeout} s"
            return None
        if now - max(d.client.last_heartbeat or d.ready_at, waited_from) > self.heartbeat_timeout:
            return "daemon_hung", "hung", f"{d.family} daemon sent no heartbeat for {self.heartbeat_timeout} s"
        unanswered = self._unanswered(d, now, waited_from)
        return ("daemon_hung", "hung", unanswered) if unanswered is not None else None

    def _last_stall(self, now: float) -> float:
        """The wall time the thing the daemons wait on (``stalled``) was last seen standing
        still; ``-inf`` when it never did, or nothing was given to ask."""
        if self._stalled is not None and self._stalled():
            self._stood_still_at = now
        return self._stood_still_at

    def _unanswered(self, d: _Daemon, now: float, waited_from: float = -math.inf) -> str | None:
        """The rule for a daemon that heartbeats but does not take its commands: every request
        gets its first reply (accepted, done or error) within ``heartbeat_timeout`` of being sent
        (or of READY, for one sent while the daemon started). Commands validate and start inside
        the loop that heartbeats, so a healthy daemon never needs longer."""
        oldest = d.client.oldest_unanswered()
        if oldest is None or now - max(oldest.sent_at, d.ready_at, waited_from) <= self.heartbeat_timeout:
            return None
        return (f"{d.family} daemon did not answer {oldest.id} ({oldest.cmd}) within {self.heartbeat_timeout} s "
                f"though it still heartbeats")

    def _mark_ready(self, d: _Daemon, now: float) -> None:
        d.phase, d.ready_at = "ready", now
        ready = d.client.ready or {}
        self.events.publish("daemon_state", family=d.family, state="ready", reason=f"pid {ready.get('pid')}",
                            pid=ready.get("pid"), backend=ready.get("backend"), commands=ready.get("commands"))

    def _lose(self, d: _Daemon, code: str, state: str, reason: str, now: float) -> None:
        """The daemon crashed or hung: fail its requests, kill what is left, schedule a restart.
        A live one is first told to stop (best effort: one line into its stdin, never blocking),
        so a daemon that still reads stops the robot before it is killed."""
        if d.process.poll() is None:
            d.client.tell_stop()
            _signal_group(d.process, signal.SIGKILL)
            self._zombies.append(d.process)
        failed = self._disconnect(d, code, reason)
        d.phase = "down"
        delay = self._schedule_restart(d, now)
        self.events.publish("daemon_state", family=d.family, state=state, reason=reason,
                            failed=[r.id for r in failed], restart_in=delay)

    def _schedule_restart(self, d: _Daemon, now: float) -> float:
        """Count one more consecutive loss and set the restart time; returns the delay."""
        d.failures += 1
        low, high = self.restart_backoff
        delay = min(high, low * 2 ** (d.failures - 1))
        d.restart_at = now + delay
        return delay

    def _disconnect(self, d: _Daemon, code: str, reason: str) -> list[Request]:
        self._outputs.remove(d.client.fileno())
        return d.client.detach(code, reason)

    def _exit_reason(self, d: _Daemon) -> str:
        """``exited with signal SIGKILL`` / ``exited with code 2`` / ``closed its output``."""
        try:
            code = d.process.wait(EXIT_WAIT)
        except subprocess.TimeoutExpired:
            return "closed its output"
        if code < 0:
            try:
                return f"exited with signal {signal.Signals(-code).name}"
            except ValueError:
                return f"exited with signal {-code}"
        return f"exited with code {code}"

    def _stderr_tail(self, d: _Daemon) -> str:
        """`` (stderr: last | lines)`` of the current process, or nothing."""
        try:
            with open(d.log_path, "rb") as log:
                log.seek(max(d.log_offset, log.seek(0, os.SEEK_END) - 8192))
                text = log.read().decode(errors="replace")
        except OSError:
            return ""
        lines = [line.strip() for line in text.splitlines() if line.strip()][-STDERR_TAIL_LINES:]
        return f" (stderr: {' | '.join(lines)})" if lines else f" (stderr: empty; log {d.log_path})"


def _signal_group(proc: subprocess.Popen[bytes], sig: int) -> None:
    """Signal the daemon's whole session (it leads it), so helpers it spawned go too."""
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(proc.pid, sig)
