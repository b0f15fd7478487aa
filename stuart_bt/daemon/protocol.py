"""The daemon wire protocol: one JSON object per line, both directions (see docs/protocol.md).

Both ends import this module, so the message shapes, error codes and line limits are defined
once. Every string travels JSON-encoded, so a newline inside an utterance stays inside its
string and can never start a second command.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from typing import Any

import orjson

from ..core.errors import StuartError
from ..core.jsonfile import compact_encoder, is_finite_number, nesting_depth

PROTOCOL_VERSION = 1
MAX_LINE = 1 << 20  # bytes of one line, newline excluded; longer lines are rejected unread
MAX_DEPTH = 32  # nesting of objects and arrays in one message; deeper lines are refused unparsed

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

# Error codes: one table for both line protocols that speak this shape, the daemons' (stdin and
# stdout) and the world server's (its socket). A daemon sends the first group; the framework sets
# the daemon_* group itself when a daemon cannot answer any more; the world server answers with
# WORLD_CODES (two of them only it uses); a client that cannot reach a server sets CLIENT_CODES.
ERROR_CODES: dict[str, str] = {
    "bad_request": "the line or its arguments are malformed; the reason says what",
    "unknown_command": "the daemon has no such command; the reason may suggest one",
    "preempted": "a newer command took the same resource (motion, voice, arms)",
    "stopped": "a stop command (or the daemon shutting down) ended the request",
    "cancelled": "a cancel command for this request ended it",
    "watchdog": "the daemon heard nothing from its framework while motion ran, so it stopped the robot itself",
    "unreachable": "the goal is out of reach; nothing moved",
    "not_found": "no such object, marker or target",
    "unknown_gesture": "the gesture name is not in the library",
    "blocked": "something stayed in the robot's way longer than allowed; the robot stopped",
    "not_holding": "release asked for, but the arm holds nothing",
    "already_holding": "pick asked for, but the robot already holds something",
    "backend_error": "the backend (simulator, vendor SDK) failed; vendor_code may say more",
    "daemon_died": "framework side: the daemon process exited with the request in flight",
    "daemon_hung": "framework side: the daemon stopped sending heartbeats or answering commands",
    "daemon_faulty": "framework side: the daemon flooded its output with lines that are not protocol",
    "daemon_down": "framework side: the daemon is not running (restarting or shut down)",
    "out_of_range": "the world server: a value is outside the robot's limits (a joint target); nothing moved",
    "busy": "the world server: an earlier request holds the resource (already recording to that file)",
    "disconnected": "client side: the server could not be reached, or closed the connection",
    "timeout": "client side: no reply came within the client's timeout",
    "start_failed": "client side: the server process exited before it was ready",
}
FRAMEWORK_CODES = ("daemon_died", "daemon_hung", "daemon_faulty", "daemon_down")
WORLD_CODES = ("bad_request", "unknown_command", "not_found", "out_of_range", "busy", "backend_error")
CLIENT_CODES = ("disconnected", "timeout", "start_failed")
LOG_LEVELS = ("debug", "info", "warning", "error")


class ProtocolError(StuartError, ValueError):
    """A line that is not a protocol message. ``request_id`` is set when the line had one."""

    def __init__(self, reason: str, request_id: str | None = None) -> None:
        super().__init__(reason)
        self.reason = reason
        self.request_id = request_id


_TO_LINE = compact_encoder(ensure_ascii=False)  # made once: json.dumps builds an encoder per call


def encode(message: dict[str, Any]) -> bytes:
    """One message as one line of UTF-8 JSON, newline included.

    Both encoders escape control characters inside strings, so the only raw newline in the
    output is the terminating one. orjson writes the usual message (plain dicts, lists, strings,
    numbers) several times faster than the stdlib; whatever it will not write (an integer past
    64 bits, a key that is not a string, a subclass such as a numpy float, a lone surrogate, a
    circular structure) goes to the stdlib encoder, whose output or refusal is the verdict. Both
    write a NaN or an infinity as ``null`` (:func:`~stuart_bt.core.jsonfile.to_json`).
    """
    try:
        return _FAST_LINE(message, option=_FAST_OPTIONS)
    except TypeError:
        return (_TO_LINE(message) + "\n").encode()


def decode(line: bytes | str) -> dict[str, Any]:
    """Parse one line (without or with its newline) into a message object.

    The one gate every line passes, both directions: anything a peer can send either comes back
    as a dict of finite numbers and valid strings or raises :class:`ProtocolError` (nothing
    else). Size and nesting are checked before the JSON parser runs, so its recursion can never
    be reached by a deep line; NaN, Infinity and numbers that overflow a float are refused.
    """
    return _decode(line)[0]


def decode_daemon_message(line: bytes | str) -> dict[str, Any]:
    """:func:`decode` then :func:`check_daemon_message`, the way the framework reads a daemon's
    line: the same verdict, but the walk for ``pose`` objects only runs when the line's text
    could hold such a key (every line of every daemon passes here, a pose is in few of them)."""
    message, text = _decode(line)
    # a key can only be one of POSE_KEYS if the text spells it, or spells anything with \u escapes
    poses = (b"pose" in text or b"\\u" in text) if isinstance(text, bytes) else ("pose" in text or "\\u" in text)
    return _check_daemon_message(message, poses=poses)


def _decode(line: bytes | str) -> tuple[dict[str, Any], bytes | str]:
    """The message and the text it was parsed from. Every line of every daemon and every
    request passes here, so the checks are written inline, and the walks over every value run
    only when the text shows they may find something."""
    if len(line) > MAX_LINE + 1:
        raise ProtocolError(f"line of {len(line)} bytes is longer than the {MAX_LINE}-byte limit")
    if type(line) is bytes and _fast_path_gives_the_same(line):
        try:
            message = _FAST_PARSE(line)
        except orjson.JSONDecodeError:
            pass  # refused: the stdlib path below gives the verdict, in its own words
        else:
            if type(message) is dict:
                return message, line
    return _decode_stdlib(line)


def _fast_path_gives_the_same(line: bytes) -> bool:
    """Whether orjson's reading of ``line`` is the stdlib reader's, checks included: orjson
    refuses every line the checks below refuse (invalid UTF-8, lone surrogates, NaN, Infinity,
    numbers that overflow a float) and reads the rest to the same values, except two things
    this rules out: nesting past :data:`MAX_DEPTH` (it allows 1024 levels) and integers of 19
    digits or more (past 64 bits it reads them as floats). Fuzzed against the stdlib path in
    tests/test_protocol.py."""
    return line.count(b"[") + line.count(b"{") <= MAX_DEPTH and _LONG_INTEGER.search(line) is None


def _decode_stdlib(line: bytes | str) -> tuple[dict[str, Any], str]:
    """:func:`_decode` with the stdlib parser and the protocol's own checks: every line orjson
    refuses, or may read differently, comes here, so the reason for a refusal is always this
    path's."""
    if isinstance(line, str):
        text, strings = line, True  # a str may hold lone surrogates: check every string
    else:
        try:
            text = bytes(line).decode("utf-8")
        except UnicodeDecodeError as e:
            raise ProtocolError(f"not JSON: not UTF-8 ({e.reason} at byte {e.start})") from None
        # valid UTF-8 decodes to no lone surrogate: only a \uD8xx escape can bring one in
        strings = "\\ud" in text or "\\uD" in text
    if nesting_depth(text, MAX_DEPTH) > MAX_DEPTH:
        raise ProtocolError(f"nested deeper than {MAX_DEPTH} levels")
    try:
        message = _PARSE(text)
    except (ValueError, RecursionError) as e:  # JSONDecodeError, and ints past Python's digit limit
        raise ProtocolError(f"not JSON: {e}") from None
    if not isinstance(message, dict):
        if isinstance(message, _NonFinite):
            raise ProtocolError(f"{message.text} is not a number the protocol carries (numbers must be finite)")
        raise ProtocolError(f"expected a JSON object, got {type(message).__name__}")
    if strings or _may_hold_non_finite(text):
        _check_values(message, strings)
    return message, text


class _NonFinite:
    """Stands in for NaN, Infinity or an overflowing number while parsing, so the refusal can
    name the request the line belonged to (the parser's hooks cannot see the id)."""

    def __init__(self, text: str) -> None:
        self.text = text


def _refuse_constant(name: str) -> _NonFinite:
    return _NonFinite(name)


# Built once: json.loads given a hook builds a new decoder on every call, which costs more than
# parsing a short line.
_PARSE = json.JSONDecoder(parse_constant=_refuse_constant).decode
_FAST_PARSE = orjson.loads
_FAST_LINE = orjson.dumps
# orjson's own handling of subclasses, dataclasses and dates differs from the stdlib's: those go
# to the stdlib encoder as before; a newline is appended in C
_FAST_OPTIONS = (orjson.OPT_APPEND_NEWLINE | orjson.OPT_PASSTHROUGH_SUBCLASS | orjson.OPT_PASSTHROUGH_DATACLASS
                 | orjson.OPT_PASSTHROUGH_DATETIME)
_LONG_INTEGER = re.compile(rb"[0-9]{19}")
# A float literal that may overflow to infinity has a positive exponent of three digits or more,
# or a mantissa of more than 200 digits (under 10**200 times at most 10**99 is still finite).
# Digits inside strings may match too; that only costs the walk that then finds nothing. Two
# patterns, not one alternation: each alone is several times faster.
_LONG_EXPONENT = re.compile(r"[eE]\+?[0-9]{3}")
_LONG_MANTISSA = re.compile(r"[0-9]{200}")


def _may_hold_non_finite(text: str) -> bool:
    """Whether parsing ``text`` can have produced a NaN or an infinity: NaN and Infinity are bare
    words JSON cannot escape, and an overflowing number needs a long exponent or mantissa. When
    this says no, the walk over every value would find nothing, so it is skipped."""
    return ("NaN" in text or "Infinity" in text or _LONG_EXPONENT.search(text) is not None
            or _LONG_MANTISSA.search(text) is not None)


def _check_values(message: dict[str, Any], strings: bool) -> None:
    """Every number finite (NaN and Infinity arrive as :class:`_NonFinite`, an overflowing
    literal such as 1e400 as a float infinity) and, if ``strings``, every key and string
    encodable UTF-8 (JSON lets lone surrogates like \\ud800 in; they would break every later
    write of the event log). Iterative: no recursion."""
    stack: list[Any] = [message]
    while stack:
        value = stack.pop()
        if isinstance(value, dict):
            if strings:
                stack.extend(value.keys())
            stack.extend(value.values())
        elif isinstance(value, list):
            stack.extend(value)
        elif isinstance(value, float):
            if value - value != 0.0:  # inf - inf and nan - nan are nan: not finite
                raise ProtocolError("a number too large for a float is not a number the protocol carries "
                                    "(numbers must be finite)", _id_of(message))
        elif isinstance(value, _NonFinite):
            raise ProtocolError(f"{value.text} is not a number the protocol carries (numbers must be finite)",
                                _id_of(message))
        elif strings and isinstance(value, str):
            try:
                value.encode("utf-8")
            except UnicodeEncodeError:
                raise ProtocolError("a string holds a lone surrogate (not valid UTF-8)", _id_of(message)) from None


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


def check_daemon_message(message: dict[str, Any]) -> dict[str, Any]:
    """The schema of a daemon -> framework line (docs/protocol.md): its type, its fields' types,
    and every ``pose`` object in it (finite x, y, yaw), so nothing malformed reaches the leaves
    or the world state. Returns the message; raises :class:`ProtocolError`."""
    return _check_daemon_message(message, poses=True)


def _check_daemon_message(message: dict[str, Any], poses: bool) -> dict[str, Any]:
    kind = message.get("type")
    check = _SCHEMAS.get(kind) if isinstance(kind, str) else None
    if check is None:
        raise ProtocolError(f"message of unknown type {kind!r}", _id_of(message))
    try:
        check(message)
        if poses:
            _check_poses(message)
    except ProtocolError as e:
        raise ProtocolError(f"{kind}: {e.reason}", _id_of(message)) from None
    return message


def _id_of(message: dict[str, Any]) -> str | None:
    request_id = message.get("id")
    return request_id if isinstance(request_id, str) else None


def _field(message: dict[str, Any], name: str, types: type | tuple[type, ...], optional: bool = False) -> None:
    if name not in message:
        if optional:
            return
        raise ProtocolError(f"missing {name!r}")
    value = message[name]
    if isinstance(value, bool) and bool not in (types if isinstance(types, tuple) else (types,)):
        raise ProtocolError(f"{name!r} must be {_names(types)}, got bool")
    if not isinstance(value, types):
        raise ProtocolError(f"{name!r} must be {_names(types)}, got {type(value).__name__}")


def _names(types: type | tuple[type, ...]) -> str:
    names = {dict: "an object", str: "a string", int: "an integer", float: "a number", list: "a list",
             type(None): "null"}
    return " or ".join(dict.fromkeys(names[t] for t in (types if isinstance(types, tuple) else (types,))))


def _check_ready(m: dict[str, Any]) -> None:
    for name, types in (("family", str), ("backend", str), ("pid", int), ("protocol", int), ("commands", list)):
        _field(m, name, types)
    if not all(isinstance(c, str) for c in m["commands"]):
        raise ProtocolError("'commands' must be a list of strings")


_REPLY_BODY = {ACCEPTED: "data", PROGRESS: "data", DONE: "result"}  # an optional object in each


def _check_reply(m: dict[str, Any]) -> None:
    body = _REPLY_BODY[m["type"]]
    if type(m.get("id")) is str and type(m.get(body, {})) is dict:
        return  # the usual reply, as the parser builds it; anything else is looked at closely
    _field(m, "id", str)
    _field(m, body, dict, optional=True)


def _check_error(m: dict[str, Any]) -> None:
    _field(m, "id", (str, type(None)))
    _field(m, "code", str)
    _field(m, "reason", str)
    _field(m, "vendor_code", (int, type(None)), optional=True)
    _field(m, "data", (dict, type(None)), optional=True)


def _check_heartbeat(m: dict[str, Any]) -> None:
    _field(m, "seq", int)
    _field(m, "t", (int, float), optional=True)
    _field(m, "state", dict)


def _check_log(m: dict[str, Any]) -> None:
    _field(m, "level", str)
    _field(m, "message", str)
    if m["level"] not in LOG_LEVELS:
        raise ProtocolError(f"level {m['level']!r} is not one of {', '.join(LOG_LEVELS)}")


_SCHEMAS = {
    READY: _check_ready,
    ACCEPTED: _check_reply,
    PROGRESS: _check_reply,
    DONE: _check_reply,
    ERROR: _check_error,
    HEARTBEAT: _check_heartbeat,
    LOG: _check_log,
}
POSE_KEYS = ("pose", "robot_pose")  # objects under these keys are map poses wherever they appear


def _check_poses(message: dict[str, Any]) -> None:
    """Every ``pose``/``robot_pose`` in a daemon message is ``{x, y, yaw}`` of finite numbers
    (iterative walk; depth is already bounded by :func:`decode`)."""
    stack: list[Any] = [message]
    while stack:
        value = stack.pop()
        if isinstance(value, dict):
            for key, inner in value.items():
                if key in POSE_KEYS and inner is not None:
                    check_pose(inner, key)
            stack.extend(value.values())
        elif isinstance(value, list):
            stack.extend(value)


def check_pose(value: Any, what: str = "pose") -> dict[str, Any]:
    """``value`` as a map pose: an object whose x and y (and yaw, if given and not null) are
    finite numbers. Raises :class:`ProtocolError` naming the bad field."""
    if not isinstance(value, dict):
        raise ProtocolError(f"{what} must be an object, got {type(value).__name__}")
    for axis in ("x", "y", "yaw"):
        if axis == "yaw" and value.get("yaw") is None:
            continue
        if axis not in value:
            raise ProtocolError(f"{what} has no {axis!r}")
        if not is_finite_number(value[axis]):
            raise ProtocolError(f"{what}.{axis} must be a finite number, got {value[axis]!r:.40}")
    return value


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
        if not self._pending and not self._skipping and len(data) <= self._limit and data.endswith(b"\n"):
            # the usual read: whole lines, none of them too long (the whole read is not)
            return [line for line in bytes(data).split(b"\n")[:-1] if line.strip()]
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
