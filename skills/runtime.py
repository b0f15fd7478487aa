"""The loop every skill daemon runs: JSON lines in on stdin, JSON lines out on a private stdout.

One thread, one ``poll`` loop: read request lines, hand them to the backend, poll the
running activities, send heartbeats, and stop the robot when the framework goes away (stdin
EOF, broken pipe) or a signal arrives. Keeping it single-threaded means a stop is handled
between two polls, never racing a half-finished command.

Before anything else, fd 1 is pointed at stderr and the real stdout is kept as a private fd
for protocol lines only, so a library that prints (vendor SDKs do) cannot corrupt the stream.
"""

from __future__ import annotations

import argparse
import contextlib
import ctypes
import importlib
import json
import math
import os
import select
import signal
import stat
import sys
import time
import traceback
from collections.abc import Mapping
from typing import Any

from stuart_bt.core.clock import Clock, clock_from_spec
from stuart_bt.core.suggest import did_you_mean
from stuart_bt.daemon import protocol as p
from stuart_bt.daemon.backend import Activity, Backend, DaemonError, Done, Progress, StartupError

POLL_PERIOD = 0.01  # wall seconds between polls of activities that give no next_due()
READ_CHUNK = 1 << 16
EXIT_FLUSH_SECONDS = 0.5  # how long to try delivering the last replies before exiting
PR_SET_PDEATHSIG = 1



def _clock(spec: str | None) -> Clock:
    """The framework's clock from its spec: ``sim:PATH`` is the simulator's shared clock file
    (read only: the world drives it), anything else as :func:`clock_from_spec` reads it."""
    if spec and spec.startswith("sim:"):
        from stuart_bt.sim.world.clock import SimClock

        return SimClock(spec.removeprefix("sim:"), driver=False)
    return clock_from_spec(spec)


def main(family: str, backends: Mapping[str, str], argv: list[str] | None = None) -> int:
    """Run one daemon; ``backends`` maps names to ``"module:Class"`` (imported only when chosen,
    so the dry daemon never loads a vendor SDK). Returns the exit code."""
    out_fd = _claim_stdout()
    signals = _catch_signals()
    options = _parse_args(family, argv)
    _die_with_parent()
    try:
        backend_cls = _load_backend(family, backends, options.backend)
        clock = _clock(options.clock)
        backend_options = json.loads(options.options)
        if not isinstance(backend_options, dict):
            raise ValueError("--options must be a JSON object")
    except (LookupError, ValueError) as e:
        print(f"{family} daemon: {e}", file=sys.stderr)
        return 2
    try:
        backend = backend_cls(clock, backend_options)
    except StartupError as e:  # the operator's to fix: the reason alone, no traceback
        print(f"{family} daemon: {options.backend} backend failed to start: {e}", file=sys.stderr)
        return 1
    except Exception as e:  # noqa: BLE001 - any backend start-up failure ends the process before READY
        traceback.print_exc()
        print(f"{family} daemon: {options.backend} backend failed to start: {e}", file=sys.stderr)
        return 1
    print(f"{family} daemon: {options.backend} backend up, pid {os.getpid()}", file=sys.stderr)
    return Daemon(family, options.backend, backend, out_fd, signals, heartbeat_period=options.heartbeat,
                  watchdog=options.watchdog).run()


def _claim_stdout() -> int:
    """Keep the real stdout for protocol lines; everything else written to fd 1 goes to stderr."""
    sys.stdout.flush()
    out_fd = os.dup(1)
    os.dup2(2, 1)
    if stat.S_ISFIFO(os.fstat(out_fd).st_mode):  # a terminal is shared with the shell: leave it be
        os.set_blocking(out_fd, False)
    return out_fd


def _catch_signals() -> list[int]:
    """Record SIGTERM / SIGINT instead of dying, from the start: the loop then stops cleanly."""
    received: list[int] = []
    for signum in (signal.SIGTERM, signal.SIGINT):
        signal.signal(signum, lambda signum, _frame: received.append(signum))
    return received


def _parse_args(family: str, argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog=f"python -m stuart_bt.skills.{family}", description=f"{family} skill daemon")
    parser.add_argument("--backend", required=True, help="backend name, e.g. dry")
    parser.add_argument("--clock", default="wall", help="clock spec from Clock.spec() (default: wall)")
    parser.add_argument("--options", default="{}", help="backend options as a JSON object")
    parser.add_argument("--heartbeat", type=float, default=0.1, help="heartbeat period in wall seconds")
    parser.add_argument("--watchdog", type=float, default=0.0,
                        help="stop running motion when nothing came from the framework for this many wall "
                             "seconds (it sends keep-alives while it ticks); 0: off")
    return parser.parse_args(argv)


def _die_with_parent() -> None:
    """Ask Linux to SIGTERM us when the parent dies (stdin EOF covers every other case)."""
    if not sys.platform.startswith("linux"):
        return
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)


def _load_backend(family: str, backends: Mapping[str, str], name: str) -> type[Backend]:
    if name not in backends:
        valid = ", ".join(sorted(backends))
        raise LookupError(f"unknown backend {name!r}{did_you_mean(name, backends)}; valid backends: {valid}")
    module_name, _, class_name = backends[name].partition(":")
    return getattr(importlib.import_module(module_name), class_name)


class Daemon:
    """The protocol loop around one backend."""

    def __init__(self, family: str, backend_name: str, backend: Backend, out_fd: int, signals: list[int],
                 in_fd: int = 0, heartbeat_period: float = 0.1, watchdog: float = 0.0) -> None:
        self.family = family
        self.backend_name = backend_name
        self.backend = backend
        self._commands = backend.commands()
        self._out_fd = out_fd
        self._in_fd = in_fd
        self._heartbeat_period = heartbeat_period
        self._next_heartbeat = time.monotonic()
        self._watchdog = watchdog  # wall seconds of framework silence that stop running motion; 0: off
        self._last_heard = time.monotonic()
        self._seq = 0
        self._activities: dict[str, Activity] = {}
        self._lines = p.LineBuffer()
        self._out = bytearray()
        self._broken = False  # nobody reads our output any more
        self._exiting = False
        self._signals = signals  # filled by the handlers _catch_signals installed
        self._builtins = {p.PING: self._ping, p.STATE: self._state, p.CANCEL: self._cancel, p.STOP: self._stop,
                          p.SHUTDOWN: self._shutdown}
        # select.poll itself, not the selectors module: its wrapper was a measurable share of a
        # round trip (docs/protocol.md, "Round trip cost")
        self._poller = select.poll()
        self._poller.register(in_fd, select.POLLIN)
        self._waiting_to_write = False  # out_fd is registered for POLLOUT (a backlog the pipe refused)
        self._behind = False  # the last flush left bytes the pipe would not take
        self._wait = 0.0  # wall seconds the next poll may block
        self._wake_r, wake_w = os.pipe()
        os.set_blocking(wake_w, False)
        self._poller.register(self._wake_r, select.POLLIN)
        signal.set_wakeup_fd(wake_w)  # a signal also wakes the poll at once

    def run(self) -> int:
        self._send(p.ready(self.family, self.backend_name, os.getpid(), [*p.BUILTIN_COMMANDS, *self._commands]))
        while not self._exiting:
            self._step()
        self._close()
        return 0

    # -- one turn of the loop ---------------------------------------------------------------

    def _step(self) -> None:
        """Wait for input or for the next thing due, handle it, then write. The write comes last
        and the wait right after it: the framework, woken by the reply, finds this process asleep
        rather than still at its bookkeeping beside it (a few µs of every round trip on a 2-vCPU
        VM, docs/protocol.md "Round trip cost")."""
        for fd, _events in self._poller.poll(self._wait * 1000.0):
            if fd == self._in_fd:
                self._read_input()
            elif fd == self._wake_r:
                os.read(self._wake_r, 512)
        if self._signals and not self._exiting:
            name = signal.Signals(self._signals[0]).name
            self._stop_everything("stopped", f"{self.family} daemon received {name}")
            self._exiting = True
        if not self._exiting:
            if self._activities:  # both are about running activities (a ping or a state is none)
                self._check_watchdog()
                self._poll_activities()
            for level, message in self.backend.take_logs():
                self._send(p.log(level, message))
            if time.monotonic() >= self._next_heartbeat:
                self._heartbeat()
        self._wait = self._timeout()
        self._flush()

    def _check_watchdog(self) -> None:
        """A framework that went silent while motion runs (hung, frozen, its machine gone) leaves
        the robot stopped: the running activities end ``stopped`` and the backend stops. Idle, the
        daemon waits: stopping would also let go of a held object or a held gesture."""
        if self._watchdog <= 0 or not self._activities:
            return
        silent = time.monotonic() - self._last_heard
        if silent > self._watchdog:
            self._stop_everything("watchdog", f"{self.family} daemon heard nothing from its framework for "
                                             f"{silent:.2f} s (watchdog {self._watchdog:g} s)")
            self._last_heard = time.monotonic()

    def _timeout(self) -> float:
        """Wall seconds until the next heartbeat, the next activity poll or the watchdog is due."""
        timeout = self._next_heartbeat - time.monotonic()
        if self._watchdog > 0 and self._activities:
            timeout = min(timeout, self._last_heard + self._watchdog - time.monotonic() + 0.001)
        if self._activities:
            dues = [activity.next_due() for activity in self._activities.values()]
            known = [due for due in dues if due is not None]
            if len(known) < len(dues):
                timeout = min(timeout, POLL_PERIOD)
            else:
                clock = self.backend.clock
                timeout = min(timeout, (min(known) - clock.now()) / clock.factor,
                              getattr(clock, "poll_interval", math.inf))
        return max(0.0, timeout)

    def _read_input(self) -> None:
        data = os.read(self._in_fd, READ_CHUNK)
        self._last_heard = time.monotonic()
        if not data:
            self._stop_everything("stopped", f"{self.family} daemon lost its framework (stdin closed)")
            self._exiting = True
            return
        for line in self._lines.feed(data):
            if self._exiting:
                return
            try:
                self._handle_line(line)
            except Exception as e:  # noqa: BLE001 - a bug in the loop itself must not take the robot's daemon down
                self._log_exception("handling an input line failed", e)
                self._send(p.error(None, "bad_request", f"the line could not be handled: {type(e).__name__}: {e}"))

    # -- requests ---------------------------------------------------------------------------

    def _handle_line(self, line: bytes | p.Oversize) -> None:
        if isinstance(line, p.Oversize):
            self._send(p.error(None, "bad_request", f"line of {line.size}+ bytes exceeds the {p.MAX_LINE}-byte limit"))
            return
        try:
            message = p.decode(line)
            if p.is_alive(message):  # the framework's keep-alive: reading it was the point
                return
            request_id, cmd, args = p.parse_request(message)
        except p.ProtocolError as e:
            self._send(p.error(e.request_id, "bad_request", e.reason))
            return
        if request_id in self._activities:
            self._send(p.error(request_id, "bad_request", f"request id {request_id!r} is already running"))
            return
        builtin = self._builtins.get(cmd)
        if builtin is not None:
            builtin(request_id, args)
        elif cmd in self._commands:
            self._start(request_id, cmd, args)
        else:
            known = [*p.BUILTIN_COMMANDS, *self._commands]
            self._send(p.error(request_id, "unknown_command",
                               f"{self.family} daemon has no command {cmd!r}{did_you_mean(cmd, known)}"))

    def _start(self, request_id: str, cmd: str, args: dict[str, Any]) -> None:
        now = self.backend.clock.now()
        try:
            activity = self._commands[cmd](args)
            self._preempt(activity.resource, request_id, cmd, now)
            data = activity.start(now)
        except DaemonError as e:
            self._send(p.error(request_id, e.code, e.reason, e.vendor_code, e.data))
        except Exception as e:  # noqa: BLE001 - a backend bug must not take the daemon down
            self._backend_failed(request_id, e)
        else:
            self._activities[request_id] = activity
            self._send(p.accepted(request_id, data))

    def _preempt(self, resource: str | None, by_id: str, by_cmd: str, now: float) -> None:
        if resource is None:
            return
        for request_id, activity in list(self._activities.items()):
            if activity.resource == resource:
                self._end(request_id, "preempted", f"{by_cmd} {by_id} took the {resource}", now)

    def _ping(self, request_id: str, _args: dict[str, Any]) -> None:
        self._send(p.done(request_id, {"t": round(self.backend.clock.now(), 6)}))

    def _state(self, request_id: str, _args: dict[str, Any]) -> None:
        try:
            self._send(p.done(request_id, self.backend.state()))
        except Exception as e:  # noqa: BLE001 - a backend bug must not take the daemon down
            self._backend_failed(request_id, e)

    def _cancel(self, request_id: str, args: dict[str, Any]) -> None:
        target = args.get("target")
        if not isinstance(target, str):
            self._send(p.error(request_id, "bad_request", f"cancel: 'target' must be a request id, got {target!r}"))
            return
        running = target in self._activities
        if running:
            self._end(target, "cancelled", f"cancelled by {request_id}", self.backend.clock.now())
        self._send(p.done(request_id, {"target": target, "cancelled": running}))

    def _stop(self, request_id: str, _args: dict[str, Any]) -> None:
        stopped = self._stop_everything("stopped", f"stopped by {request_id}")
        self._send(p.done(request_id, {"stopped": stopped}))

    def _shutdown(self, request_id: str, _args: dict[str, Any]) -> None:
        self._stop_everything("stopped", f"{self.family} daemon shutting down ({request_id})")
        self._send(p.done(request_id, {}))
        self._exiting = True

    def _stop_everything(self, code: str, reason: str) -> list[str]:
        now = self.backend.clock.now()
        ended = list(self._activities)
        for request_id in ended:
            self._end(request_id, code, reason, now)
        try:
            self.backend.stop()
        except Exception as e:  # noqa: BLE001 - stop must reach every activity even if the backend fails
            self._log_exception("backend stop failed", e)
        return ended

    def _end(self, request_id: str, code: str, reason: str, now: float) -> None:
        """Cancel one activity and report it ended with ``code``."""
        activity = self._activities.pop(request_id)
        try:
            data = activity.cancel(now)
        except Exception as e:  # noqa: BLE001 - a backend bug must not take the daemon down
            self._log_exception(f"cancelling {request_id} failed", e)
            data = None
        self._send(p.error(request_id, code, reason, data=data))

    # -- activities and heartbeats ----------------------------------------------------------

    def _poll_activities(self) -> None:
        if not self._activities:
            return
        now = self.backend.clock.now()
        for request_id, activity in list(self._activities.items()):
            try:
                outcome = activity.poll(now)
            except DaemonError as e:
                del self._activities[request_id]
                self._send(p.error(request_id, e.code, e.reason, e.vendor_code, e.data))
                continue
            except Exception as e:  # noqa: BLE001 - a backend bug ends that activity only
                del self._activities[request_id]
                self._backend_failed(request_id, e)
                continue
            if isinstance(outcome, Progress):
                self._send(p.progress(request_id, outcome.data))
            elif isinstance(outcome, Done):
                del self._activities[request_id]
                self._send(p.done(request_id, outcome.result))

    def _heartbeat(self) -> None:
        """One heartbeat, now due: the backend's state, unless the framework is behind."""
        self._next_heartbeat = time.monotonic() + self._heartbeat_period
        if self._behind:  # the framework is behind: do not pile heartbeats on top
            return
        try:
            state = self.backend.state()
        except Exception as e:  # noqa: BLE001 - the heartbeat goes out without the state
            self._log_exception("backend state failed", e)
            state = {}
        self._seq += 1
        self._send(p.heartbeat(self._seq, self.backend.clock.now(), state))

    def _backend_failed(self, request_id: str, e: Exception) -> None:
        self._log_exception(f"request {request_id} failed inside the backend", e)
        self._send(p.error(request_id, "backend_error", f"{type(e).__name__}: {e}"))

    def _log_exception(self, what: str, e: Exception) -> None:
        text = "".join(traceback.format_exception(e))
        print(f"{self.family} daemon: {what}\n{text}", file=sys.stderr)
        self._send(p.log("error", f"{what}: {type(e).__name__}: {e}"))

    # -- output -----------------------------------------------------------------------------

    def _send(self, message: dict[str, Any]) -> None:
        if self._broken:
            return
        try:
            self._out += p.encode(message)
        except (TypeError, ValueError) as e:  # a backend returned something JSON cannot carry
            print(f"{self.family} daemon: cannot encode {message!r}: {e}", file=sys.stderr)
            request_id = message.get("id")
            if request_id is not None and message.get("type") in (p.DONE, p.ERROR):
                self._out += p.encode(p.error(request_id, "backend_error", f"reply could not be encoded: {e}"))
            else:
                self._out += p.encode(p.log("error", f"could not encode a {message.get('type')} message: {e}"))

    def _flush(self) -> None:
        """Write what the pipe takes now; the rest waits for the next turn (never block)."""
        while self._out and not self._broken:
            try:
                written = os.write(self._out_fd, self._out)
            except BlockingIOError:
                break
            except BrokenPipeError:
                self._out.clear()
                self._broken = True
                if not self._exiting:
                    self._stop_everything("stopped", f"{self.family} daemon lost its framework (broken pipe)")
                    self._exiting = True
                return
            del self._out[:written]
        # kept in flags: the heartbeat asks whether the framework is behind, the poll what to watch
        want_write = self._behind = bool(self._out) and not self._broken
        if want_write and not self._waiting_to_write:
            self._poller.register(self._out_fd, select.POLLOUT)
        elif self._waiting_to_write and not want_write:
            self._poller.unregister(self._out_fd)
        self._waiting_to_write = want_write

    def _close(self) -> None:
        try:
            self.backend.close()
        except Exception as e:  # noqa: BLE001 - the daemon is exiting anyway: say why and go
            self._log_exception("backend close failed", e)
        for fd in (self._in_fd, self._wake_r):
            self._poller.unregister(fd)
        deadline = time.monotonic() + EXIT_FLUSH_SECONDS
        while self._out and not self._broken and time.monotonic() < deadline:
            self._flush()
            if self._out:
                self._poller.poll(max(0.0, deadline - time.monotonic()) * 1000.0)
        signal.set_wakeup_fd(-1)
