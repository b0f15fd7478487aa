"""Reading a JSON data file (markers, states, objects) with errors that name the file and place,
and writing strict JSON (:func:`to_json`: what the project writes is readable by any JSON reader)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any


def read_json(path: str | Path, error: type[Exception], what: str) -> Any:
    """The parsed document, or ``error("FILE:LINE:COL: ...")`` for a missing, unreadable or
    malformed file (``what`` names the kind of file in the message)."""
    path = Path(path)
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise error(f"{path}: {what} not found") from None
    except json.JSONDecodeError as e:
        raise error(f"{path}:{e.lineno}:{e.colno}: not valid JSON: {e.msg}") from None
    except (OSError, UnicodeDecodeError) as e:
        raise error(f"{path}: cannot read: {e}") from None


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
