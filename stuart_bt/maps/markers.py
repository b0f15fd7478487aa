"""Marker files: the named places of a map (``{"frame": "map", "markers": {name: {x, y, yaw,
display_name}}}``), read in one place for the tree loader, the resolver, the planner's start
state, the session, the web view and the map picture.

:class:`stuart_bt.core.world.Marker` stays in core: it is part of the world state every layer shares.
"""

from __future__ import annotations

from pathlib import Path

from ..core.errors import StuartError
from ..core.jsonfile import read_json, to_json
from ..core.world import Marker


class MarkerFileError(StuartError, ValueError):
    """A marker file that is missing, unreadable, not JSON, or not shaped as a marker file."""


def load_markers(path: str | Path) -> dict[str, Marker]:
    """Read a marker file: ``{"frame": "map", "markers": {name: {x, y, yaw, display_name}}}``;
    a regular file under the data file size limit only (:func:`stuart_bt.core.jsonfile.read_json`)."""
    path = Path(path)
    doc = read_json(path, MarkerFileError, "marker file")
    entries = doc.get("markers") if isinstance(doc, dict) else None
    if not isinstance(entries, dict):
        raise MarkerFileError(f"{path}: expected an object with a 'markers' mapping")
    markers: dict[str, Marker] = {}
    for name, m in entries.items():
        try:
            markers[name] = Marker(
                name, float(m["x"]), float(m["y"]), float(m.get("yaw", 0.0)), str(m.get("display_name", ""))
            )
        except (KeyError, TypeError, ValueError):
            raise MarkerFileError(f"{path}: marker {name!r} needs numeric x and y (and optional yaw)") from None
    return markers


def save_markers(path: str | Path, markers: dict[str, Marker], frame: str = "map") -> None:
    """Write a marker file :func:`load_markers` reads back (strict JSON, two-space indent)."""
    body = {
        "frame": frame,
        "markers": {
            m.name: {"x": m.x, "y": m.y, "yaw": m.yaw, "display_name": m.display_name} for m in markers.values()
        },
    }
    Path(path).write_text(to_json(body, indent=2) + "\n", encoding="utf-8")
