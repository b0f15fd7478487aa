"""Reading a JSON data file (markers, states, objects) with errors that name the file and place,
and writing strict JSON (:func:`to_json`: what the project writes is readable by any JSON reader)."""

from __future__ import annotations

import json
import math
import os
import re
import stat
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, TypeGuard

_STRING = re.compile(r'"[^"\\]*(?:\\.[^"\\]*)*"', re.DOTALL)  # a JSON string, escapes included
_BRACKET = re.compile(r"[\[\]{}]")
MAX_DATA_FILE = 1 << 20  # bytes: markers, objects and trees are a few kilobytes


class NotARegularFile(OSError):
    """A path that names a device, a FIFO, a folder or a file over the size limit: not read."""


def read_limited(path: str | Path, limit: int = MAX_DATA_FILE) -> bytes:
    """The bytes of the regular file at ``path``, refusing anything else before reading: a FIFO
    would block forever, ``/dev/zero`` or ``/dev/urandom`` would fill memory, and a file that
    grows while it is read is cut at ``limit`` + 1 bytes and refused."""
    with open(path, "rb", opener=lambda name, flags: os.open(name, flags | os.O_NONBLOCK)) as handle:
        info = os.fstat(handle.fileno())
        if not stat.S_ISREG(info.st_mode):
            raise NotARegularFile("not a regular file (a device, FIFO or folder); refused")
        if info.st_size > limit:
            raise NotARegularFile(f"file is {info.st_size} bytes; the limit is {limit}")
        data = handle.read(limit + 1)
    if len(data) > limit:
        raise NotARegularFile(f"file is over {limit} bytes; refused")
    return data


def read_json(path: str | Path, error: type[Exception], what: str) -> Any:
    """The parsed document, or ``error("FILE:LINE:COL: ...")`` for a missing, unreadable or
    malformed file (``what`` names the kind of file in the message). Only a regular file under
    MAX_DATA_FILE bytes is read."""
    path = Path(path)
    try:
        return json.loads(read_limited(path).decode("utf-8"))
    except FileNotFoundError:
        raise error(f"{path}: {what} not found") from None
    except json.JSONDecodeError as e:
        raise error(f"{path}:{e.lineno}:{e.colno}: not valid JSON: {e.msg}") from None
    except NotARegularFile as e:
        raise error(f"{path}: {what} {e}") from None
    except (OSError, UnicodeDecodeError, RecursionError) as e:
        raise error(f"{path}: cannot read: {getattr(e, 'strerror', None) or e}") from None


def is_finite_number(value: object) -> TypeGuard[int | float]:
    """A JSON number that is a real quantity: an int or float (not a bool) that converts to a
    finite float. Python's JSON reader lets NaN, infinity and ints too big for a float through;
    daemon messages, poses and web requests are checked with this one rule."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    try:
        return math.isfinite(float(value))
    except OverflowError:
        return False


def _finite(value: Any) -> Any:
    """``value`` with every NaN or infinity replaced by None, however deep (JSON has neither)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {key: _finite(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(item) for item in value]
    return value


def to_json(value: Any, **options: Any) -> str:
    """``json.dumps`` that always writes strict JSON: a NaN or an infinity (a sim clock's
    unbounded speed, a failed measurement) is written as ``null``, never as the ``NaN`` or
    ``Infinity`` that Python writes and every other JSON reader refuses. ``options`` are
    ``json.dumps``'s; a ``default`` hook's output is made finite too. Costs nothing extra when
    every number is finite: the strict encoder runs first, the cleaning only when it refuses."""
    options["allow_nan"] = False
    default = options.get("default")
    if default is not None:
        options["default"] = lambda obj: _finite(default(obj))
    try:
        return json.dumps(value, **options)
    except ValueError:  # "Out of range float values are not JSON compliant"
        return json.dumps(_finite(value), **options)


def compact_encoder(ensure_ascii: bool = True) -> Callable[[Any], str]:
    """``to_json(value, separators=(",", ":"), ensure_ascii=...)`` for a hot path (a daemon's
    line). ``json.dumps`` given any option builds a new encoder on every call, and each
    ``JSONEncoder.encode`` builds a C encoder and a table of the containers it is inside: more
    work than encoding a short line. This makes the C encoder once, with no such table: a
    circular structure ends in RecursionError inside the encoder, raised here as the same
    ``ValueError`` json.dumps raises (as is a structure nested past the recursion limit). A NaN
    or an infinity takes :func:`to_json`'s path and is written as ``null``."""
    options: dict[str, Any] = {"separators": (",", ":"), "ensure_ascii": ensure_ascii}
    # the C encoder json.JSONEncoder makes for each call; None where the accelerator is missing
    make_c_encoder = getattr(json.encoder, "c_make_encoder", None)
    chunks: Callable[[Any, int], Sequence[str]]
    if make_c_encoder is None:
        python_encode = json.JSONEncoder(**options, allow_nan=False).encode

        def chunks(value: Any, _level: int) -> Sequence[str]:
            return [python_encode(value)]
    else:
        strings = json.encoder.encode_basestring_ascii if ensure_ascii else json.encoder.encode_basestring
        chunks = make_c_encoder(None, json.JSONEncoder().default, strings, None, ":", ",", False, False, False)

    def dumps(value: Any) -> str:
        try:
            return "".join(chunks(value, 0))
        except RecursionError:
            raise ValueError("Circular reference detected (or nested deeper than the recursion limit)") from None
        except ValueError:  # a NaN or an infinity somewhere: the cleaning path
            return to_json(value, **options)

    return dumps


def nesting_depth(text: str | bytes, limit: int = 0) -> int:
    """How deep objects and arrays nest in the JSON ``text``, brackets inside strings not
    counted: checked before parsing untrusted input, since Python's parser recurses (300,000
    brackets once killed a daemon). Regular expressions, not recursion. A text with no more
    than ``limit`` brackets in all cannot nest deeper and is answered from two counts."""
    if isinstance(text, bytes):
        text = text.decode("utf-8", "replace")
    brackets = text.count("[") + text.count("{")
    if brackets <= limit:
        return brackets
    depth = deepest = 0
    for bracket in _BRACKET.finditer(_STRING.sub("", text)):
        depth += 1 if bracket.group() in "[{" else -1
        deepest = max(deepest, depth)
    return deepest
