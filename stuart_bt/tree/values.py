"""Checking one parameter value against its catalogue type, at load time.

Each problem comes back with the exact place (a list element, the column inside an expression)
so messages point where the user must edit. Blackboard references (``$key``) pass for every
type because their value is only known at run time; text with ``${key}`` templates passes for
the text-like types for the same reason. Marker names are only checked for being text here:
the loader checks them against the marker file once it knows which file applies.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from yaml.nodes import Node, ScalarNode, SequenceNode

from ..core import expr, gestures
from ..core.blackboard import is_reference, template_names
from ..core.suggest import did_you_mean
from .spec import Location
from .yaml_source import location

Problem = tuple[Location, str]

TEXT_TYPES = ("string", "marker", "gesture", "path", "choice", "expression")
EXPECTED = {
    "string": "text",
    "number": "a number",
    "integer": "an integer",
    "boolean": "true or false",
    "seconds": "a number of seconds >= 0",
    "angle": "an angle in radians (a number)",
    "marker": "a marker name",
    "gesture": "a gesture name",
    "gestures": "a list of gesture names",
    "path": "a file path",
    "expression": "an expression",
}


def describe(value: Any) -> str:
    """A value as the user wrote it in YAML, with its kind where that helps."""
    if value is None:
        return "null"
    if isinstance(value, bool):
        return f"{str(value).lower()} (a boolean)"
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, list):
        return "a list"
    if isinstance(value, dict):
        return "a mapping"
    return repr(value)


def is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def check_value(
    type_: str,
    value: Any,
    node: Node,
    file: str,
    base_dir: Path,
    choices: Sequence[str] = (),
) -> list[Problem]:
    """Problems with ``value`` (written at ``node`` in ``file``) for a parameter of type ``type_``."""
    here = location(file, node)
    if type_ == "any" or is_reference(value):
        return []
    if type_ in TEXT_TYPES and isinstance(value, str) and template_names(value):
        return []
    if type_ == "choice":
        if isinstance(value, str) and value in choices:
            return []
        got = f"{value!r}{did_you_mean(value, choices)}" if isinstance(value, str) else describe(value)
        return [(here, f"expected one of {', '.join(choices)}, got {got}")]
    if type_ == "gestures":
        return _check_gestures(value, node, file)
    if type_ in TEXT_TYPES:
        if not isinstance(value, str):
            hint = " (quote it to make it text)" if isinstance(value, (bool, int, float)) or value is None else ""
            return [(here, f"expected {EXPECTED[type_]}, got {describe(value)}{hint}")]
        if not value.strip():
            return [(here, f"expected {EXPECTED[type_]}, got an empty text")] if type_ != "string" else []
        return _check_text(type_, value, node, file, base_dir)
    return _check_scalar(type_, value, here)


def _check_scalar(type_: str, value: Any, here: Location) -> list[Problem]:
    ok = {
        "number": is_number(value) and not _is_nan(value),
        "angle": is_number(value) and math.isfinite(value),
        "integer": isinstance(value, int) and not isinstance(value, bool),
        "boolean": isinstance(value, bool),
        "seconds": is_number(value) and not _is_nan(value) and value >= 0,
    }[type_]
    return [] if ok else [(here, f"expected {EXPECTED[type_]}, got {describe(value)}")]


def _is_nan(value: float) -> bool:
    return isinstance(value, float) and math.isnan(value)


def _check_text(type_: str, value: str, node: Node, file: str, base_dir: Path) -> list[Problem]:
    here = location(file, node)
    if type_ == "gesture" and gestures.lookup(value) is None:
        return [(here, f"unknown gesture {value!r}{did_you_mean(value, gestures.names())}")]
    if type_ == "path":
        target = base_dir / value
        if not is_file(target):
            return [(here, (f"file {value!r} not found (relative to {base_dir.as_posix()})"
                           f"{did_you_mean(target.name, names_in(target.parent))}"))]
    if type_ == "expression":
        try:
            expr.parse(value)
        except expr.ExprError as e:
            return [(_column_in(node, file, value, e.column), e.message)]
    return []


def is_file(path: Path) -> bool:
    try:
        return path.is_file()
    except (OSError, ValueError):  # unreadable directory, NUL byte in the name
        return False


def names_in(folder: Path) -> list[str]:
    """File names in ``folder`` for a suggestion; none when it cannot be listed."""
    try:
        return [p.name for p in folder.iterdir()]
    except (OSError, ValueError):
        return []


def _column_in(node: Node, file: str, text: str, column: int) -> Location:
    """Where column ``column`` (1-based, of the stripped expression) sits in the file."""
    start = location(file, node)
    if not isinstance(node, ScalarNode) or node.style in ("|", ">") or "\n" in text:
        return start
    quote = 1 if node.style in ('"', "'") else 0
    leading = len(text) - len(text.lstrip())
    return Location(file, start.line, start.column + quote + leading + column - 1)


def _check_gestures(value: Any, node: Node, file: str) -> list[Problem]:
    here = location(file, node)
    if not isinstance(value, list):
        return [(here, f"expected {EXPECTED['gestures']}, got {describe(value)}")]
    if not value:
        return [(here, "expected at least one gesture name")]
    items = node.value if isinstance(node, SequenceNode) and len(node.value) == len(value) else [node] * len(value)
    problems: list[Problem] = []
    for item, item_node in zip(value, items, strict=True):
        problems += check_value("gesture", item, item_node, file, Path("."))
    return problems
