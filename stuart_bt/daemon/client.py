"""The framework's end of one daemon's pipes: send requests, poll for replies, no threads.

The executor calls :meth:`DaemonClient.poll` once per tick (through the supervisor), which
reads whatever the daemon has written without blocking and updates the :class:`Request`
handles the leaves hold. Leaves never wait on a pipe, so one slow daemon cannot stall a tick.

A client outlives the daemon processes behind it: the supervisor :meth:`attach`-es each new
process, so a leaf that kept a client keeps working after a restart.
"""

from __future__ import annotations

import itertools
import os
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..core.events import EventStream
from . import protocol as p
from .limits import BadLineLimiter

SENT, ACCEPTED, DONE, ERROR = "sent", p.ACCEPTED, p.DONE, p.ERROR
READ_CHUNK = 1 << 16
_NOT_EVENT_FIELDS = ("id", "type", "family", "kind", "path")  # taken by the event itself


@dataclass(eq=False)
class Request:
    """One command sent to a daemon, updated in place as replies arrive.

    ``status`` goes ``sent`` -> ``accepted`` -> ``done`` | ``error`` (an immediate rejection skips
    ``accepted``). ``result`` is the done result, or the data an error carried (e.g. the pose
    where a stopped walk froze). ``progress`` is the last progress data. Times are
    ``time.monotonic()`` seconds.
    """

    id: str
    family: str
    cmd: str
    args: dict[str, Any]
    status: str = SENT
    result: dict[str, Any] | None = None
    error_code: str | None = None
    reason: str | None = None
    vendor_code: int | None = None
    progress: dict[str, Any] | None = None
    accepted_data: dict[str, Any] | None = None
    path: str | None = None  # the tree node that sent it, carried on its events
    sent_at: float = field(default_factory=time.monotonic)
    finished_at: float | None = None

    @property
    def finished(self) -> bool:
        return self.status in (DONE, ERROR)

    @property
    def ok(self) -> bool:
        return self.status == DONE

    def apply(self, message: dict[str, Any]) -> None:
        """Take in one reply line addressed to this request."""
        kind = message.get("type")
        if self.finished:
            return
        if kind == p.DONE:
            self.status, self.result, self.finished_at = DONE, message.get("result") or {}, time.monotonic()
        elif kind == p.ACCEPTED:
            self.status, self.accepted_data = ACCEPTED, message.get("data") or {}
        elif kind == p.PROGRESS:
            self.status, self.progress = ACCEPTED, message.get("data") or {}
        elif kind == p.ERROR:
            self.fail(message.get("code", "backend_error"), message.get("reason", ""), message.get("vendor_code"),
                      message.get("data"))

    def fail(self, code: str, reason: str, vendor_code: int | None = None, data: dict[str, Any] | None = None) -> None:
        self.status, self.error_code, self.reason, self.vendor_code = ERROR, code, reason, vendor_code
        self.result = data
        self.finished_at = time.monotonic()

    def __repr__(self) -> str:
        end = f" {self.error_code}: {self.reason}" if self.status == ERROR else ""
        return f"<Request {self.family}/{self.id} {self.cmd} {self.status}{end}>"


class DaemonClient:
    """Requests to, and replies from, one skill family's daemon process."""

    def __init__(self, family: str, events: EventStream, id_prefix: str = "r") -> None:
        self.family = family
        self.events = events
        self.ready: dict[str, Any] | None = None  # the current process's READY line
        self.state: dict[str, Any] = {}  # backend state from the last heartbeat
        self.last_heartbeat: float | None = None  # time.monotonic() of the last heartbeat or READY
        # called with each heartbeat's state, in line order with the replies (which go to events)
        self.state_listeners: list[Callable[[dict[str, Any]], None]] = []
        self.eof = False  # the current process closed its output (it died or is dying)
        self.hung_up = False  # the last poll of the pipe said the writer closed it (set by the supervisor)
        self._prefix = id_prefix
        self._ids = itertools.count(1)
        self._read_fd: int | None = None
        self._write_fd: int | None = None
        self._lines = p.LineBuffer()
        self._out = bytearray()
        self._pending: dict[str, Request] = {}
        self._down_reason = f"{family} daemon is not started"
        self._bad_lines = BadLineLimiter(family, self._publish_warning)

    # -- connection (the supervisor's side) ---------------------------------------------------

    @property
    def connected(self) -> bool:
        return self._read_fd is not None

    def attach(self, write_fd: int, read_fd: int) -> None:
        """Talk to a new daemon process through these (non-blocking) pipe ends, now owned here."""
        self._read_fd, self._write_fd = read_fd, write_fd
        self._lines = p.LineBuffer()
        self._out.clear()
        self.ready, self.state, self.last_heartbeat, self.eof = None, {}, None, False
        self._bad_lines = BadLineLimiter(self.family, self._publish_warning)

    def detach(self, code: str, reason: str) -> list[Request]:
        """The process is gone: close its pipes and fail every request still in flight."""
        for fd in (self._read_fd, self._write_fd):
            if fd is not None:
                os.close(fd)
        self._read_fd = self._write_fd = None
        self._down_reason = reason
        self.ready = None
        failed = list(self._pending.values())
        self._pending.clear()
        for request in failed:
            self._fail(request, code, reason)
        return failed

    def close_input(self) -> None:
        """Flush what is queued, then close the daemon's stdin (it stops and exits on EOF)."""
        self.flush()
        if self._write_fd is not None:
            os.close(self._write_fd)
            self._write_fd = None

    def fileno(self) -> int:
        """The daemon's output fd, for ``select``; ``ValueError`` while no process is attached."""
        if self._read_fd is None:
            raise ValueError(f"{self.family} daemon is not running")
        return self._read_fd

    # -- requests -----------------------------------------------------------------------------

    def request(self, cmd: str, args: dict[str, Any] | None = None, path: str | None = None) -> Request:
        """Send a command without waiting; the returned handle fills in as replies arrive.
        ``path`` (the sending tree node) goes on the command's events."""
        args = args or {}
        request = Request(f"{self._prefix}{next(self._ids)}", self.family, cmd, args, path=path)
        self.events.publish("command", path, family=self.family, id=request.id, cmd=cmd, args=args)
        if self._write_fd is None:
            self._fail(request, "daemon_down", self._down_reason)
            return request
        self._pending[request.id] = request
        self._out += p.encode(p.request(request.id, cmd, args))
        self.flush()  # last: the caller then waits at once, while the daemon works
        return request

    def keep_alive(self) -> None:
        """Tell the daemon the framework still runs (its watchdog); no reply, no event."""
        if self._write_fd is not None:
            self._out += p.encode(p.alive())
            self.flush()

    def cancel(self, request: Request) -> Request | None:
        """Ask the daemon to cancel ``request`` (it ends with ``cancelled``); None if already over."""
        if request.finished or request.id not in self._pending:
            return None
        return self.request(p.CANCEL, {"target": request.id}, request.path)

    def stop(self) -> Request:
        """Stop everything this daemon is doing; each running request ends with ``stopped``."""
        return self.request(p.STOP)

    def tell_stop(self) -> None:
        """A last ``stop`` to a daemon about to be killed: written if the pipe takes it, never
        waited for (nobody will read the answer), published as a command like any other."""
        if self._write_fd is None:
            return
        request_id = f"{self._prefix}{next(self._ids)}"
        self.events.publish("command", None, family=self.family, id=request_id, cmd=p.STOP, args={})
        self._out += p.encode(p.request(request_id, p.STOP))
        self.flush()

    @property
    def in_flight(self) -> list[Request]:
        return list(self._pending.values())

    def oldest_unanswered(self) -> Request | None:
        """The earliest request the daemon has not answered at all (no accepted, done or error):
        a daemon that heartbeats but never takes its commands is found through this."""
        waiting = [r for r in self._pending.values() if r.status == SENT]
        return min(waiting, key=lambda r: r.sent_at) if waiting else None

    @property
    def faulty(self) -> str | None:
        """Why this daemon's output is beyond saving (a flood of bad lines), else None."""
        return self._bad_lines.faulty

    def tick(self, now: float) -> None:
        """Time passes: publish the summary of bad lines whose warnings were held back."""
        self._bad_lines.tick(now)

    # -- I/O ----------------------------------------------------------------------------------

    def flush(self) -> None:
        """Write queued request bytes the pipe accepts now (a hung daemon must not block us)."""
        while self._out and self._write_fd is not None:
            try:
                written = os.write(self._write_fd, self._out)
            except BlockingIOError:
                return
            except BrokenPipeError:
                self._out.clear()
                self.eof = True
                return
            del self._out[:written]

    def poll(self) -> None:
        """Read every byte available now and dispatch the complete lines."""
        if self._out:
            self.flush()
        while self._read_fd is not None and not self.eof:
            try:
                data = os.read(self._read_fd, READ_CHUNK)
            except BlockingIOError:
                return
            if not data:
                self.eof = True
                return
            for line in self._lines.feed(data):
                self._handle(line)
            if len(data) < READ_CHUNK and not self.hung_up:
                # A pipe returns less than asked only when it is empty: reading again would only
                # raise EAGAIN. Whatever comes next makes the fd readable again. When the daemon
                # has closed its end (hung_up), read on to the end of output, so its death is seen
                # in this very poll, not the next one.
                return

    def _handle(self, line: bytes | p.Oversize) -> None:
        if isinstance(line, p.Oversize):
            self._bad_line(f"{self.family} daemon sent a line of {line.size}+ bytes (limit {p.MAX_LINE}); ignored")
            return
        try:
            message = p.decode_daemon_message(line)
        except p.ProtocolError as e:
            request = self._pending.get(e.request_id) if e.request_id is not None else None
            if request is not None:  # a malformed reply still ends its request, with the reason
                self._end_malformed(request, e.reason)
            self._bad_line(f"{self.family} daemon sent a line that is not protocol ({e.reason}): {line[:120]!r}")
            return
        kind = message["type"]
        if kind in p.REPLY_TYPES:
            self._reply(message)
        elif kind == p.HEARTBEAT:
            self.state = message["state"]
            self.last_heartbeat = time.monotonic()
            for listener in self.state_listeners:
                listener(self.state)
        elif kind == p.READY:
            self.ready = message
            self.last_heartbeat = time.monotonic()
        elif kind == p.LOG:
            self.events.publish("log", family=self.family, level=message["level"], message=message["message"])

    def _reply(self, message: dict[str, Any]) -> None:
        request_id = message.get("id")
        request = self._pending.get(request_id) if isinstance(request_id, str) else None
        if request is None:  # not ours (any more): counted like a bad line, so a flood stays cheap
            what = (f"rejected a line: {message.get('code')}: {message.get('reason')}" if message["type"] == p.ERROR
                    else f"sent a {message['type']} for no running request ({request_id!r})")
            self._bad_line(f"{self.family} daemon {what}")
            return
        fields = {k: v for k, v in message.items() if k not in _NOT_EVENT_FIELDS}
        self.events.publish("daemon", request.path, family=self.family, type=message["type"], id=request_id,
                            **fields)
        request.apply(message)
        if request.finished:
            del self._pending[request.id]

    def _end_malformed(self, request: Request, reason: str) -> None:
        """A reply to ``request`` that breaks the protocol (a bad number, a wrong type): the
        request fails ``backend_error`` at once, rather than waiting out a timeout."""
        del self._pending[request.id]
        self._fail(request, "backend_error", f"{self.family} daemon sent a malformed reply to {request.id}: {reason}")

    def _fail(self, request: Request, code: str, reason: str) -> None:
        """End a request on the framework's side, published like a daemon error reply."""
        request.fail(code, reason)
        self.events.publish("daemon", request.path, family=self.family, type=p.ERROR, id=request.id, code=code,
                            reason=reason)

    def _bad_line(self, message: str) -> None:
        self._bad_lines.report(message, time.monotonic())

    def _publish_warning(self, message: str, fields: dict[str, Any]) -> None:
        self.events.publish("warning", family=self.family, message=message, **fields)
