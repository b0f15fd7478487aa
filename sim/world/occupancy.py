"""The lab's occupancy grid, made from the scene's static geoms.

The grid itself, its files and the map picture are :mod:`stuart_bt.maps` (shared with the loco
daemon, which reads the saved map and plans on it); this module only turns MuJoCo geoms into
floor outlines and rasterises them. Deriving the map from the very geoms the simulator uses
means the map and the world cannot disagree; the committed sim/maps/lab.png/.yaml are
regenerated with::

    python -m stuart_bt.sim.world.occupancy --scene lab --out sim/maps/lab

which also writes ``lab_furniture.json``: every static geom's outline under the name of the
body it belongs to, as people say it ("kitchen_table" -> "kitchen table"), so the robot can say
what is in its way (:mod:`stuart_bt.maps.furniture`). tests/test_world_occupancy.py checks that
they still match the scene.

Only geoms that a robot could walk into count: static (welded to the world), collidable,
reaching between :data:`FLOOR_CLEAR` and :data:`ROBOT_HEIGHT` above the floor. Free objects,
the robot and the person move, so they are never in the map.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

from stuart_bt.maps.files import write_map
from stuart_bt.maps.furniture import Piece, circle_outline, write_furniture
from stuart_bt.maps.grid import ROBOT_RADIUS, OccupancyGrid
from stuart_bt.maps.markers import load_markers
from stuart_bt.maps.picture import draw_map_png

FLOOR_CLEAR = 0.03  # geoms entirely below this (rugs, mats) do not block
ROBOT_HEIGHT = 1.5  # geoms entirely above this (lintels, lamps) do not block
MARGIN = 0.25  # metres of map beyond the outermost obstacle


@dataclass(frozen=True)
class Footprint:
    """A geom's outline on the floor: a circle (``radius``) or a convex polygon (CCW)."""

    name: str
    centre: tuple[float, float]
    radius: float | None = None
    polygon: tuple[tuple[float, float], ...] = ()
    z_low: float = 0.0  # the geom's lowest point: a table top leaves room for feet below it
    group: str = ""  # the body it belongs to (the geom's own name for one placed in the world body)

    def distance(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Distance from points to the outline (0 inside)."""
        if self.radius is not None:
            return np.maximum(np.hypot(x - self.centre[0], y - self.centre[1]) - self.radius, 0.0)
        pts = self.polygon
        inside = np.ones(np.shape(x), dtype=bool)
        best = np.full(np.shape(x), np.inf)
        for (ax, ay), (bx, by) in zip(pts, pts[1:] + pts[:1], strict=True):
            ex, ey = bx - ax, by - ay
            inside &= (ex * (y - ay) - ey * (x - ax)) >= 0.0
            seg2 = ex * ex + ey * ey
            t = np.clip(((x - ax) * ex + (y - ay) * ey) / seg2, 0.0, 1.0) if seg2 > 0 else np.zeros(np.shape(x))
            best = np.minimum(best, np.hypot(x - (ax + t * ex), y - (ay + t * ey)))
        return np.where(inside, 0.0, best)

    def bounds(self) -> tuple[float, float, float, float]:
        if self.radius is not None:
            cx, cy = self.centre
            return cx - self.radius, cy - self.radius, cx + self.radius, cy + self.radius
        xs = [p[0] for p in self.polygon]
        ys = [p[1] for p in self.polygon]
        return min(xs), min(ys), max(xs), max(ys)


def static_footprints(model: mujoco.MjModel) -> list[Footprint]:
    """Floor outlines of every static, collidable geom between the floor and the robot's height."""
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    out: list[Footprint] = []
    for g in range(model.ngeom):
        if model.body_weldid[model.geom_bodyid[g]] != 0:
            continue  # moves: robot, free objects, the person
        if model.geom_contype[g] == 0 and model.geom_conaffinity[g] == 0:
            continue  # decoration
        gtype = model.geom_type[g]
        if gtype == int(mujoco.mjtGeom.mjGEOM_PLANE):
            continue
        pos = data.geom_xpos[g]
        mat = data.geom_xmat[g].reshape(3, 3)
        size = model.geom_size[g]
        name = model.geom(g).name or f"geom{g}"
        body = int(model.geom_bodyid[g])
        group = (model.body(body).name if body != 0 else "") or name
        vertical = abs(mat[2, 2]) > 0.999
        if gtype in (int(mujoco.mjtGeom.mjGEOM_CYLINDER), int(mujoco.mjtGeom.mjGEOM_CAPSULE)) and vertical:
            half = size[1] + (size[0] if gtype == int(mujoco.mjtGeom.mjGEOM_CAPSULE) else 0.0)
            if _blocks(pos[2] - half, pos[2] + half):
                out.append(Footprint(name, (float(pos[0]), float(pos[1])), radius=float(size[0]),
                                     z_low=float(pos[2] - half), group=group))
            continue
        if gtype == int(mujoco.mjtGeom.mjGEOM_SPHERE):
            if _blocks(pos[2] - size[0], pos[2] + size[0]):
                out.append(Footprint(name, (float(pos[0]), float(pos[1])), radius=float(size[0]),
                                     z_low=float(pos[2] - size[0]), group=group))
            continue
        # Anything else: the geom's own bounding box, turned into the world and projected.
        centre, half = model.geom_aabb[g, :3], model.geom_aabb[g, 3:]
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
        corners = pos + (centre + signs * half) @ mat.T
        if not _blocks(corners[:, 2].min(), corners[:, 2].max()):
            continue
        hull = _convex_hull([(float(c[0]), float(c[1])) for c in corners])
        out.append(Footprint(name, (float(pos[0]), float(pos[1])), polygon=tuple(hull),
                             z_low=float(corners[:, 2].min()), group=group))
    return out


def furniture_pieces(footprints: Sequence[Footprint]) -> list[Piece]:
    """The map's named furniture: the outlines of each body's geoms under the body's name, as
    people say it (underscores read as spaces), in the order the scene lists them."""
    outlines: dict[str, list[tuple[tuple[float, float], ...]]] = {}
    for fp in footprints:
        outline = circle_outline(*fp.centre, fp.radius) if fp.radius is not None else fp.polygon
        outlines.setdefault(fp.group or fp.name, []).append(tuple(outline))
    return [Piece(group.replace("_", " ").strip(), tuple(shapes)) for group, shapes in outlines.items()]


def _blocks(z_low: float, z_high: float) -> bool:
    return z_high >= FLOOR_CLEAR and z_low <= ROBOT_HEIGHT


def _convex_hull(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Counter-clockwise hull (monotone chain)."""
    pts = sorted(set((round(x, 9), round(y, 9)) for x, y in points))
    if len(pts) <= 2:
        return pts

    def cross(o: tuple[float, float], a: tuple[float, float], b: tuple[float, float]) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[tuple[float, float]] = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    upper: list[tuple[float, float]] = []
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def clearance(footprints: Sequence[Footprint], x: float, y: float) -> float:
    """Distance from a point to the nearest obstacle outline (exact, not gridded)."""
    px, py = np.array([x]), np.array([y])
    return float(min((fp.distance(px, py)[0] for fp in footprints), default=math.inf))


def footprint_hits(footprints: Sequence[Footprint], x: float, y: float, radius: float,
                   raised: tuple[float, float] | None = None) -> list[str]:
    """Names of the obstacles a round footprint of ``radius`` at (x, y) overlaps. With ``raised``
    = (height, radius), an obstacle whose lowest point is above ``height`` (a table top: the feet
    go under it) is checked against that smaller radius (the body at that height) instead."""
    px, py = np.array([x]), np.array([y])
    hits = []
    for fp in footprints:
        r = raised[1] if raised is not None and fp.z_low > raised[0] else radius
        if fp.distance(px, py)[0] < r:
            hits.append(fp.name)
    return hits


def grid_from_model(model: mujoco.MjModel, resolution: float = 0.05, inflation: float = ROBOT_RADIUS,
                    seeds: Iterable[tuple[float, float]] = ((0.0, 0.0),)) -> OccupancyGrid:
    """Rasterise :func:`static_footprints`. A cell is occupied when an outline comes within
    half a cell of its centre, so even a wall thinner than a cell shows; free space the seeds
    cannot reach is unknown."""
    footprints = static_footprints(model)
    if not footprints:
        raise ValueError("the model has no static obstacles to map")
    bounds = np.array([fp.bounds() for fp in footprints])
    x0 = math.floor((bounds[:, 0].min() - MARGIN) / resolution) * resolution
    y0 = math.floor((bounds[:, 1].min() - MARGIN) / resolution) * resolution
    cols = int(math.ceil((bounds[:, 2].max() + MARGIN - x0) / resolution))
    rows = int(math.ceil((bounds[:, 3].max() + MARGIN - y0) / resolution))
    occupied = np.zeros((rows, cols), dtype=bool)
    for fp in footprints:
        bx0, by0, bx1, by1 = fp.bounds()
        c0, c1 = max(0, int((bx0 - x0) / resolution) - 1), min(cols, int((bx1 - x0) / resolution) + 2)
        r0, r1 = max(0, int((by0 - y0) / resolution) - 1), min(rows, int((by1 - y0) / resolution) + 2)
        xs = x0 + (np.arange(c0, c1) + 0.5) * resolution
        ys = y0 + (np.arange(r0, r1) + 0.5) * resolution
        gx, gy = np.meshgrid(xs, ys)
        occupied[r0:r1, c0:c1] |= fp.distance(gx, gy) <= 0.5 * resolution
    return OccupancyGrid.from_obstacles(occupied, resolution, (x0, y0), inflation, seeds)


def scene_grid(scene: str = "lab", resolution: float = 0.05, inflation: float = ROBOT_RADIUS) -> OccupancyGrid:
    """The grid of a scene file alone (no robot needed: it is never part of the map)."""
    from .scene import scene_path

    model = mujoco.MjModel.from_xml_path(str(scene_path(scene)))
    return grid_from_model(model, resolution, inflation)


def scene_furniture(scene: str = "lab") -> list[Piece]:
    """The named furniture of a scene file (what ``main`` writes next to the map)."""
    from .scene import scene_path

    return furniture_pieces(static_footprints(mujoco.MjModel.from_xml_path(str(scene_path(scene)))))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m stuart_bt.sim.world.occupancy",
                                     description="Write a scene's occupancy map (map_server PNG + YAML).")
    parser.add_argument("--scene", default="lab")
    parser.add_argument("--out", default=None, help="file stem (default sim/maps/<scene>)")
    parser.add_argument("--resolution", type=float, default=0.05)
    parser.add_argument("--inflation", type=float, default=ROBOT_RADIUS)
    parser.add_argument("--picture", default=None, help="also draw the map with markers to this PNG")
    options = parser.parse_args(argv)
    from .scene import MAPS_DIR

    grid = scene_grid(options.scene, options.resolution, options.inflation)
    stem = Path(options.out or MAPS_DIR / options.scene)
    furniture = write_furniture(scene_furniture(options.scene), stem.parent / f"{stem.name}_furniture.json")
    png, yaml_path = write_map(grid, stem, furniture=furniture.name)
    print(f"wrote {png}, {yaml_path} and {furniture} ({grid.shape[1]} x {grid.shape[0]} cells)")
    if options.picture:
        draw_map_png(grid, load_markers(MAPS_DIR / "lab_markers.json"), [], {}, options.picture)
        print(f"wrote {options.picture}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
