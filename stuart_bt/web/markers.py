"""The marker file as the map page edits it: validated edits, no lost updates, atomic writes.

Several browser tabs (or a person and a script) may edit markers at once. Each edit is a small
patch (add, update, rename, delete one marker) applied under a lock to the file *as it is on disk
now*, so edits to different markers never overwrite each other. An edit of an existing marker
carries the values the editor last saw (``expect``); when the marker changed since, the edit is
refused with :class:`MarkerConflict` and the current file, instead of silently undoing the other
edit. Writes go to a temporary file in the same folder and replace the old file in one step, so a
crash never leaves half a marker file. ``version`` is a hash of the file's bytes.

Units REP-103: metres and radians in the map frame; yaw is kept in (-pi, pi].
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
import tempfile
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..core.errors import StuartError
from ..core.jsonfile import to_json
from ..core.suggest import did_you_mean

NAME_RULE = re.compile(r"[a-z][a-z0-9_]{0,39}")  # used with fullmatch: "$" would let a trailing newline in
DISPLAY_MAX = 60
OPS = ("add", "update", "rename", "delete")


class MarkerEditError(StuartError, ValueError):
    """An edit that cannot be applied; the message says why (and the closest valid name)."""


class MarkerConflict(Exception):
    """The marker changed since the editor loaded it; ``current`` is the file now."""

    def __init__(self, message: str, current: dict[str, Any]) -> None:
        super().__init__(message)
        self.current = current


@dataclass(frozen=True)
class MapBounds:
    """Where markers may go: inside the map and not on an obstacle (``occupied(x, y)``)."""

    x_min: float
    y_min: float
    x_max: float
    y_max: float
    occupied: Callable[[float, float], bool] | None = None


class MarkerStore:
    """Reads and edits one marker file (``{"frame": "map", "markers": {name: {x, y, yaw, display_name}}}``)."""

    def __init__(self, path: str | Path, bounds: MapBounds | None = None) -> None:
        self.path = Path(path)
        self.bounds = bounds
        self._lock = threading.Lock()

    def load(self) -> dict[str, Any]:
        """The document plus its ``version``."""
        with self._lock:
            return self._read()

    def _read(self) -> dict[str, Any]:
        raw = self.path.read_bytes()
        try:
            doc = json.loads(raw.decode("utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError) as e:
            raise MarkerEditError(f"{self.path}: not a valid marker file: {e}") from None
        markers = doc.get("markers") if isinstance(doc, dict) else None
        if not isinstance(markers, dict):
            raise MarkerEditError(f"{self.path}: expected an object with a 'markers' mapping")
        return {"frame": doc.get("frame", "map"), "markers": markers, "version": _version(raw)}

    def edit(self, request: dict[str, Any]) -> dict[str, Any]:
        """Apply one edit (``op`` in OPS) and return the new document; nothing is written on error."""
        op = request.get("op")
        if op not in OPS:
            raise MarkerEditError(f"unknown edit {op!r}; choose one of {', '.join(OPS)}{did_you_mean(str(op), OPS)}")
        with self._lock:
            doc = self._read()
            markers: dict[str, Any] = dict(doc["markers"])
            name = _name(request.get("name"))
            if op == "add":
                if name in markers:
                    raise MarkerEditError(f"a marker named {name!r} exists already")
                markers[name] = self._values(request, None)
            else:
                if name not in markers:
                    raise MarkerEditError(f"no marker named {name!r}{did_you_mean(name, markers)}")
                self._check_expected(name, markers[name], request.get("expect"), doc)
                if op == "update":
                    markers[name] = self._values(request, markers[name])
                elif op == "rename":
                    new = _name(request.get("new_name"))
                    if new != name and new in markers:
                        raise MarkerEditError(f"a marker named {new!r} exists already")
                    markers = {(new if k == name else k): v for k, v in markers.items()}
                else:
                    del markers[name]
            self._write({"frame": doc["frame"], "markers": markers})
            return self._read()

    def _check_expected(self, name: str, current: dict[str, Any], expect: Any, doc: dict[str, Any]) -> None:
        if expect is None:
            return
        if not isinstance(expect, dict):
            raise MarkerEditError("'expect' must be the marker's values as last seen")
        for key in ("x", "y", "yaw", "display_name"):
            if key in expect and not _same(expect[key], current.get(key)):
                raise MarkerConflict(f"marker {name!r} was changed by someone else; reload and edit again", doc)

    def _values(self, request: dict[str, Any], old: dict[str, Any] | None) -> dict[str, Any]:
        old = old or {}
        x = _number(request.get("x", old.get("x")), "x")
        y = _number(request.get("y", old.get("y")), "y")
        yaw = math.remainder(_number(request.get("yaw", old.get("yaw", 0.0)), "yaw"), math.tau)
        display = request.get("display_name", old.get("display_name", ""))
        if not isinstance(display, str) or len(display) > DISPLAY_MAX:
            raise MarkerEditError(f"display_name must be text of at most {DISPLAY_MAX} characters")
        b = self.bounds
        if b is not None:
            if not (b.x_min <= x <= b.x_max and b.y_min <= y <= b.y_max):
                raise MarkerEditError(f"({x:.2f}, {y:.2f}) is outside the map "
                                      f"(x {b.x_min:.2f}..{b.x_max:.2f}, y {b.y_min:.2f}..{b.y_max:.2f} m)")
            if b.occupied is not None and b.occupied(x, y):
                raise MarkerEditError(f"({x:.2f}, {y:.2f}) is not free space on the map (an obstacle, or beyond "
                                      "the walls): the robot cannot stand there")
        return {"x": round(x, 4), "y": round(y, 4), "yaw": round(yaw, 4), "display_name": display.strip()}

    def _write(self, body: dict[str, Any]) -> None:
        text = to_json(body, indent=2) + "\n"
        fd, tmp = tempfile.mkstemp(prefix=f".{self.path.name}.", dir=self.path.parent)
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                f.write(text)
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, self.path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise


def _version(raw: bytes) -> str:
    return hashlib.sha256(raw).hexdigest()[:16]


def _name(value: Any) -> str:
    if not isinstance(value, str) or not NAME_RULE.fullmatch(value):
        raise MarkerEditError(f"marker name {value!r} must be lower-case letters, digits and '_', starting with "
                              "a letter, at most 40 characters (e.g. 'coffee_machine')")
    return value


def _number(value: Any, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise MarkerEditError(f"{what} must be a finite number, got {value!r}")
    return float(value)


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return abs(float(a) - float(b)) < 1e-3
    return a == b
