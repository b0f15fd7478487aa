"""The daemon wire protocol: one JSON object per line, both directions (see docs/protocol.md).

Both ends import this module, so the message shapes, error codes and line limits are defined
once. Every string travels JSON-encoded, so a newline inside an utterance stays inside its
string and can never start a second command.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from typing import Any

from ..jsonfile import nesting_depth, to_json

PROTOCOL_VERSION = 1
MAX_LINE = 1 << 20  # bytes of one line, newline excluded; longer lines are rejected unread
MAX_DEPTH = 32  # nesting of objects and arrays in one line; deeper lines are refused before parsing

# Message types (the "type" field of every daemon -> framework line).
READY = "ready"
ACCEPTED = "accepted"
PROGRESS = "progress"
DONE = "done"
ERROR = "error"
HEARTBEAT = "heartbeat"
ALIVE = "alive"  # framework -> daemon keep-alive line: {"type": "alive"} (no id, no reply)
LOG = "log"
REPLY_TYPES = (ACCEPTED, PROGRESS, DONE, ERROR)

# Commands every daemon understands, whatever its family.
PING = "ping"
STOP = "stop"
CANCEL = "cancel"
STATE = "state"
SHUTDOWN = "shutdown"
BUILTIN_COMMANDS = (PING, STOP, CANCEL, STATE, SHUTDOWN)

# Error codes. The daemon sends the first group; the framework sets the last group itself
# when a daemon cannot answer any more.
ERROR_CODES: dict[str, str] = {
    "bad_request": "the line or its arguments are malformed; the reason says what",
    "unknown_command": "the daemon has no such command; the reason may suggest one",
    "preempted": "a newer command took the same resource (motion, voice, arms)",
    "stopped": "a stop command (or the daemon shutting down) ended the request",
    "cancelled": "a cancel command for this request ended it",
    "unreachable": "the goal is out of reach; nothing moved",
    "not_found": "no such object, marker or target",
    "unknown_gesture": "the gesture name is not in the library",
    "blocked": "something stayed in the robot's way longer than allowed; the robot stopped",
    "not_holding": "release asked for, but the arm holds nothing",
    "already_holding": "pick asked for, but the robot already holds something",
    "backend_error": "the backend (simulator, vendor SDK) failed; vendor_code may say more",
    "daemon_died": "framework side: the daemon process exited with the request in flight",
    "daemon_hung": "framework side: the daemon stopped sending heartbeats",
    "daemon_down": "framework side: the daemon is not running (restarting or shut down)",
}
FRAMEWORK_CODES = ("daemon_died", "daemon_hung", "daemon_down")


class ProtocolError(ValueError):
    """A line that is not a protocol message. ``request_id`` is set when the line had one."""

    def __init__(self, reason: str, request_id: str | None = None) -> None:
        super().__init__(reason)
        self.reason = reason
        self.request_id = request_id


def encode(message: dict[str, Any]) -> bytes:
    """One message as one line of UTF-8 JSON, newline included.

    ``json.dumps`` escapes control characters inside strings, so the only raw newline in the
    output is the terminating one.
    """
    return (to_json(message, separators=(",", ":"), ensure_ascii=False) + "\n").encode()


def decode(line: bytes | str) -> dict[str, Any]:
    """Parse one line (without or with its newline) into a message object.

    Refused with :class:`ProtocolError`, never another exception: a line over MAX_LINE, nesting
    deeper than MAX_DEPTH (checked before parsing, since Python's parser recurses), anything that
    is not JSON, and NaN or infinite numbers (``NaN``, ``Infinity``, ``1e999``), which JSON does
    not have and which would poison the world state."""
    if len(line) > MAX_LINE + 1:
        raise ProtocolError(f"line of {len(line)} bytes is longer than the {MAX_LINE}-byte limit")
    raw = line.encode("utf-8", "surrogatepass") if isinstance(line, str) else line
    if nesting_depth(raw, MAX_DEPTH) > MAX_DEPTH:
        raise ProtocolError(f"nested deeper than {MAX_DEPTH} levels")
    try:
        message = json.loads(raw, parse_constant=_refuse_constant, parse_float=_finite_float)
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError) as e:
        raise ProtocolError(f"not JSON: {e}") from None
    if not isinstance(message, dict):
        raise ProtocolError(f"expected a JSON object, got {type(message).__name__}")
    return message


def _refuse_constant(name: str) -> float:
    raise ProtocolError(f"{name} is not a JSON number")


def _finite_float(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise ProtocolError(f"{text} is out of range for a number")
    return value


def parse_request(message: dict[str, Any]) -> tuple[str, str, dict[str, Any]]:
    """``(id, cmd, args)`` of a request, or :class:`ProtocolError` naming what is wrong."""
    request_id = message.get("id")
    if not isinstance(request_id, str) or not request_id:
        raise ProtocolError("request needs a non-empty string 'id'")
    cmd = message.get("cmd")
    if not isinstance(cmd, str) or not cmd:
        raise ProtocolError("request needs a string 'cmd'", request_id)
    args = message.get("args", {})
    if args is None:
        args = {}
    if not isinstance(args, dict):
        raise ProtocolError(f"'args' must be an object, got {type(args).__name__}", request_id)
    return request_id, cmd, args


def request(request_id: str, cmd: str, args: dict[str, Any] | None = None) -> dict[str, Any]:
    return {"id": request_id, "cmd": cmd, "args": args or {}}


def ready(family: str, backend: str, pid: int, commands: list[str]) -> dict[str, Any]:
    return {"type": READY, "family": family, "backend": backend, "pid": pid, "protocol": PROTOCOL_VERSION,
            "commands": commands}


def accepted(request_id: str, data: dict[str, Any] | None = None) -> dict[str, Any]:
    message: dict[str, Any] = {"id": request_id, "type": ACCEPTED}
    if data:
        message["data"] = data
    return message


def progress(request_id: str, data: dict[str, Any]) -> dict[str, Any]:
    return {"id": request_id, "type": PROGRESS, "data": data}


def done(request_id: str, result: dict[str, Any] | None = None) -> dict[str, Any]:
    return {"id": request_id, "type": DONE, "result": result or {}}


def error(
    request_id: str | None,
    code: str,
    reason: str,
    vendor_code: int | None = None,
    data: dict[str, Any] | None = None,
) -> dict[str, Any]:
    message: dict[str, Any] = {"id": request_id, "type": ERROR, "code": code, "reason": reason}
    if vendor_code is not None:
        message["vendor_code"] = vendor_code
    if data:
        message["data"] = data
    return message


def alive() -> dict[str, Any]:
    return {"type": ALIVE}


def is_alive(message: dict[str, Any]) -> bool:
    """The framework's keep-alive: it only proves the framework still runs (the daemon's watchdog)."""
    return message.get("type") == ALIVE and "id" not in message


def heartbeat(seq: int, t: float, state: dict[str, Any]) -> dict[str, Any]:
    return {"type": HEARTBEAT, "seq": seq, "t": round(t, 4), "state": state}


def log(level: str, message: str) -> dict[str, Any]:
    return {"type": LOG, "level": level, "message": message}


@dataclass(frozen=True)
class Oversize:
    """Stands in for a line that exceeded :data:`MAX_LINE`; its bytes were dropped."""

    size: int


class LineBuffer:
    """Splits a byte stream into lines, dropping (and reporting) lines over :data:`MAX_LINE`.

    Memory stays bounded whatever the peer sends: once a line is too long, its bytes are
    discarded up to the next newline and a single :class:`Oversize` takes its place.
    """

    def __init__(self, limit: int = MAX_LINE) -> None:
        self._limit = limit
        self._pending = bytearray()
        self._skipping = False  # inside an oversize line, waiting for its newline

    def feed(self, data: bytes) -> list[bytes | Oversize]:
        out: list[bytes | Oversize] = []
        start = 0
        while True:
            end = data.find(b"\n", start)
            if end < 0:
                self._keep(data[start:], out)
                return out
            if self._skipping:
                self._skipping = False
            else:
                self._pending += data[start:end]
                if len(self._pending) > self._limit:
                    out.append(Oversize(len(self._pending)))
                elif self._pending.strip():
                    out.append(bytes(self._pending))
                self._pending.clear()
            start = end + 1

    def _keep(self, tail: bytes, out: list[bytes | Oversize]) -> None:
        if self._skipping:
            return
        self._pending += tail
        if len(self._pending) > self._limit:
            out.append(Oversize(len(self._pending)))
            self._pending.clear()
            self._skipping = True
