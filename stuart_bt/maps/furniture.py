"""What the obstacles on a map are called: named outlines, so a robot can say what is in its way.

An occupancy grid knows where obstacles are, not what they are. A furniture file adds names:
each piece is a name people use ("kitchen table") and one or more convex outlines on the floor
(metres, map frame, counter-clockwise). The map YAML names the file under its ``furniture`` key
(our addition to the map_server keys, as ``inflation`` is); a map without one simply knows no
names, and every question here then answers with none. The simulator writes the file from its
scene (:mod:`stuart_bt.sim.world.occupancy`); on the robot it can be drawn by hand.

File format (strict JSON)::

    {"frame": "map", "furniture": [{"name": "kitchen table", "outlines": [[[3.91, 0.9], [4.71, 0.9], ...]]}]}
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..core.errors import StuartError
from ..core.jsonfile import read_json, to_json
from .grid import Grid

Point = tuple[float, float]
Outline = tuple[Point, ...]


class FurnitureFileError(StuartError):
    """A furniture file that cannot be read: the reason names the file and what is wrong."""


@dataclass(frozen=True)
class Piece:
    """One named obstacle: its spoken name and the convex outlines it covers on the floor."""

    name: str
    outlines: tuple[Outline, ...]

    def distance(self, x: float, y: float) -> float:
        """Metres from (x, y) to the nearest of the outlines (0 inside one)."""
        return min((outline_distance(o, x, y) for o in self.outlines), default=math.inf)


@dataclass(frozen=True)
class Furniture:
    """Every named piece of a map. Empty when the map knows no names."""

    pieces: tuple[Piece, ...] = ()

    def __bool__(self) -> bool:
        return bool(self.pieces)

    def at(self, x: float, y: float, within: float = 0.0) -> str | None:
        """The name of the piece at (x, y), or the closest within ``within`` metres of it."""
        best = min(((p.distance(x, y), p.name) for p in self.pieces), default=None)
        return best[1] if best is not None and best[0] <= within else None


class FurnitureCells:
    """The furniture laid on a grid once, so naming what is at a point costs a look-up: for each
    cell, the nearest piece within ``reach`` metres of the cell's centre and its distance. A
    search that asks hundreds of times what blocked a spot or a line of sight stays fast."""

    def __init__(self, furniture: Furniture, grid: Grid, reach: float = 0.5) -> None:
        self.grid = grid
        self.names = [p.name for p in furniture.pieces]
        rows, cols = grid.shape
        self.distance = np.full((rows, cols), np.inf)
        self.piece = np.full((rows, cols), -1, dtype=np.int32)
        res, (x0, y0) = grid.resolution, grid.origin
        for index, piece in enumerate(furniture.pieces):
            for outline in piece.outlines:
                xs, ys = [p[0] for p in outline], [p[1] for p in outline]
                c0, c1 = max(0, int((min(xs) - reach - x0) / res)), min(cols, int((max(xs) + reach - x0) / res) + 1)
                r0, r1 = max(0, int((min(ys) - reach - y0) / res)), min(rows, int((max(ys) + reach - y0) / res) + 1)
                if c0 >= c1 or r0 >= r1:
                    continue
                gx, gy = np.meshgrid(x0 + (np.arange(c0, c1) + 0.5) * res, y0 + (np.arange(r0, r1) + 0.5) * res)
                d = outline_distances(outline, gx, gy)
                window, owner = self.distance[r0:r1, c0:c1], self.piece[r0:r1, c0:c1]
                closer = (d < window) & (d <= reach)
                window[closer], owner[closer] = d[closer], index

    def at(self, x: float, y: float, within: float) -> str | None:
        """The name of the piece nearest to the cell at (x, y), if it is within ``within`` metres."""
        row, col = self.grid.world_to_cell(x, y)
        if not self.grid.inside(row, col) or self.piece[row, col] < 0 or self.distance[row, col] > within:
            return None
        return self.names[int(self.piece[row, col])]


def outline_distances(outline: Outline, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """:func:`outline_distance` for arrays of points at once."""
    if len(outline) == 1:
        return np.hypot(x - outline[0][0], y - outline[0][1])
    inside = np.full(np.shape(x), len(outline) >= 3)
    best = np.full(np.shape(x), np.inf)
    for (ax, ay), (bx, by) in zip(outline, outline[1:] + outline[:1], strict=True):
        ex, ey = bx - ax, by - ay
        inside &= (ex * (y - ay) - ey * (x - ax)) >= 0.0
        seg2 = ex * ex + ey * ey
        t = np.zeros(np.shape(x)) if seg2 == 0 else np.clip(((x - ax) * ex + (y - ay) * ey) / seg2, 0.0, 1.0)
        best = np.minimum(best, np.hypot(x - (ax + t * ex), y - (ay + t * ey)))
    return np.where(inside, 0.0, best)


def ranked(names: Iterable[str | None]) -> list[str]:
    """Names counted over many observations (what each blocked look or spot ran into), the most
    often seen first, ties in first-seen order; None (an obstacle with no name) is left out."""
    counts: dict[str, int] = {}
    for name in names:
        if name is not None:
            counts[name] = counts.get(name, 0) + 1
    return sorted(counts, key=lambda n: -counts[n])


def outline_distance(outline: Outline, x: float, y: float) -> float:
    """Distance from a point to a convex counter-clockwise polygon (0 inside or on it)."""
    if len(outline) == 1:
        return math.hypot(x - outline[0][0], y - outline[0][1])
    inside = len(outline) >= 3
    best = math.inf
    for (ax, ay), (bx, by) in zip(outline, outline[1:] + outline[:1], strict=True):
        ex, ey = bx - ax, by - ay
        if ex * (y - ay) - ey * (x - ax) < 0.0:
            inside = False
        seg2 = ex * ex + ey * ey
        t = 0.0 if seg2 == 0 else min(1.0, max(0.0, ((x - ax) * ex + (y - ay) * ey) / seg2))
        best = min(best, math.hypot(x - (ax + t * ex), y - (ay + t * ey)))
    return 0.0 if inside else best


def circle_outline(cx: float, cy: float, radius: float, sides: int = 16) -> Outline:
    """A round footprint as a polygon whose edges stay outside the circle (a margin never shrinks)."""
    r = radius / math.cos(math.pi / sides)
    return tuple((round(cx + r * math.cos(2 * math.pi * k / sides), 4),
                  round(cy + r * math.sin(2 * math.pi * k / sides), 4)) for k in range(sides))


def write_furniture(pieces: Sequence[Piece], path: str | Path) -> Path:
    """One piece a line, so a change to the scene shows as a readable diff."""
    path = Path(path)
    lines = [to_json({"name": p.name, "outlines": [[[round(x, 4), round(y, 4)] for x, y in o] for o in p.outlines]})
             for p in pieces]
    path.write_text('{"frame": "map", "furniture": [\n  ' + ",\n  ".join(lines) + "\n]}\n", encoding="utf-8")
    return path


def read_furniture(path: str | Path) -> Furniture:
    """A furniture file; a :class:`FurnitureFileError` saying what is wrong when it is not one."""
    path = Path(path)
    data = read_json(path, FurnitureFileError, "furniture file")
    entries = data.get("furniture") if isinstance(data, dict) else None
    if not isinstance(entries, list):
        raise FurnitureFileError(f"{path}: expected an object with a 'furniture' list")
    return Furniture(tuple(_piece(entry, f"{path}: furniture[{i}]") for i, entry in enumerate(entries)))


def furniture_for_map(yaml_path: str | Path) -> Furniture:
    """The furniture file a map YAML names under ``furniture`` (relative to the YAML), or no names."""
    import yaml

    yaml_path = Path(yaml_path)
    meta = yaml.safe_load(yaml_path.read_text(encoding="utf-8")) or {}
    name = meta.get("furniture") if isinstance(meta, dict) else None
    if not name:
        return Furniture()
    return read_furniture(yaml_path.parent / str(name))


def _piece(entry: Any, where: str) -> Piece:
    if not isinstance(entry, dict) or not isinstance(entry.get("name"), str) or not entry["name"].strip():
        raise FurnitureFileError(f"{where}: needs a 'name' (text) and 'outlines'")
    outlines = entry.get("outlines")
    if not isinstance(outlines, list) or not outlines:
        raise FurnitureFileError(f"{where} ({entry['name']}): 'outlines' must be a non-empty list of polygons")
    try:
        polygons = tuple(tuple((float(p[0]), float(p[1])) for p in outline) for outline in outlines)
    except (TypeError, ValueError, IndexError, KeyError):
        raise FurnitureFileError(f"{where} ({entry['name']}): an outline is not a list of [x, y] points") from None
    if any(not polygon for polygon in polygons):
        raise FurnitureFileError(f"{where} ({entry['name']}): an outline has no points")
    return Piece(entry["name"].strip(), polygons)
