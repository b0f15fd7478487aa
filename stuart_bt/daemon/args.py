"""Checks for command arguments, raising ``bad_request`` errors that say exactly what is wrong.

Every family interface validates its arguments with these before a backend sees them, so the
dry, sim and unitree backends all reject the same bad input with the same words.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

from ..core.suggest import did_you_mean
from ..core.world import Pose
from .backend import DaemonError

_MISSING: Any = object()


def bad(cmd: str, reason: str) -> DaemonError:
    return DaemonError("bad_request", f"{cmd}: {reason}")


def only_known(args: dict[str, Any], allowed: Iterable[str], cmd: str) -> None:
    """Reject argument names the command does not take (typos would otherwise be ignored)."""
    allowed = list(allowed)
    for key in args:
        if key not in allowed:
            raise bad(cmd, f"unknown argument {key!r}{did_you_mean(key, allowed)}; takes {', '.join(allowed)}")


def number(args: dict[str, Any], key: str, cmd: str, default: Any = _MISSING, minimum: float | None = None) -> float:
    value = args.get(key, default)
    if value is _MISSING:
        raise bad(cmd, f"missing argument {key!r}")
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise bad(cmd, f"{key!r} must be a finite number, got {value!r}")
    if minimum is not None and value < minimum:
        raise bad(cmd, f"{key!r} must be >= {minimum}, got {value!r}")
    return float(value)


def optional_number(args: dict[str, Any], key: str, cmd: str) -> float | None:
    return None if args.get(key) is None else number(args, key, cmd)


def string(args: dict[str, Any], key: str, cmd: str, default: Any = _MISSING, choices: tuple[str, ...] = ()) -> str:
    value = args.get(key, default)
    if value is _MISSING:
        raise bad(cmd, f"missing argument {key!r}")
    if not isinstance(value, str):
        raise bad(cmd, f"{key!r} must be a string, got {value!r}")
    if choices and value not in choices:
        raise bad(cmd, f"{key!r} must be one of {', '.join(choices)}, got {value!r}{did_you_mean(value, choices)}")
    return value


def mapping(args: dict[str, Any], key: str, cmd: str) -> dict[str, Any]:
    value = args.get(key)
    if not isinstance(value, dict):
        raise bad(cmd, f"{key!r} must be an object, got {value!r}")
    return value


def one_of(args: dict[str, Any], keys: tuple[str, ...], cmd: str) -> str:
    """The single key of ``keys`` present in ``args``."""
    given = [k for k in keys if args.get(k) is not None]
    if len(given) != 1:
        raise bad(cmd, f"give exactly one of {', '.join(keys)} (got {', '.join(given) or 'none'})")
    return given[0]


def pose(args: dict[str, Any], key: str, cmd: str) -> Pose:
    """A map pose ``{"x", "y", "yaw"}`` (yaw defaults to 0)."""
    value = mapping(args, key, cmd)
    only_known(value, ("x", "y", "yaw"), f"{cmd} {key}")
    return Pose(number(value, "x", f"{cmd} {key}"), number(value, "y", f"{cmd} {key}"),
                number(value, "yaw", f"{cmd} {key}", default=0.0))
