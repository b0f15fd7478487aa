"""The lab's occupancy grid, made from the scene's static geoms, and the map picture.

The planner (skills/loco/planner.py) reads a ROS map_server map: a PNG where black is occupied,
white free and grey unknown, plus a YAML with ``resolution`` and ``origin``. Deriving that map
from the very geoms the simulator uses means the map and the world cannot disagree; the
committed sim/maps/lab.png/.yaml are regenerated with::

    python -m stuart_bt.sim.world.occupancy --scene lab --out sim/maps/lab

and tests/test_world_occupancy.py checks that they still match the scene.

Only geoms that a robot could walk into count: static (welded to the world), collidable,
reaching between :data:`FLOOR_CLEAR` and :data:`ROBOT_HEIGHT` above the floor. Free objects,
the robot and the person move, so they are never in the map. Grid convention as ROS: rows along
y with row 0 at the lowest y, columns along x, ``origin`` the corner of cell (0, 0).
"""

from __future__ import annotations

import argparse
import math
from collections import deque
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

from stuart_bt.core.jsonfile import read_json

FLOOR_CLEAR = 0.03  # geoms entirely below this (rugs, mats) do not block
ROBOT_HEIGHT = 1.5  # geoms entirely above this (lintels, lamps) do not block
ROBOT_RADIUS = 0.3
MARGIN = 0.25  # metres of map beyond the outermost obstacle
FREE, UNKNOWN, OCCUPIED = 254, 205, 0  # PNG grey levels (map_server, negate 0)


@dataclass(frozen=True)
class Footprint:
    """A geom's outline on the floor: a circle (``radius``) or a convex polygon (CCW)."""

    name: str
    centre: tuple[float, float]
    radius: float | None = None
    polygon: tuple[tuple[float, float], ...] = ()
    z_low: float = 0.0  # the geom's lowest point: a table top leaves room for feet below it

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
        vertical = abs(mat[2, 2]) > 0.999
        if gtype in (int(mujoco.mjtGeom.mjGEOM_CYLINDER), int(mujoco.mjtGeom.mjGEOM_CAPSULE)) and vertical:
            half = size[1] + (size[0] if gtype == int(mujoco.mjtGeom.mjGEOM_CAPSULE) else 0.0)
            if _blocks(pos[2] - half, pos[2] + half):
                out.append(Footprint(name, (float(pos[0]), float(pos[1])), radius=float(size[0]),
                                     z_low=float(pos[2] - half)))
            continue
        if gtype == int(mujoco.mjtGeom.mjGEOM_SPHERE):
            if _blocks(pos[2] - size[0], pos[2] + size[0]):
                out.append(Footprint(name, (float(pos[0]), float(pos[1])), radius=float(size[0]),
                                     z_low=float(pos[2] - size[0])))
            continue
        # Anything else: the geom's own bounding box, turned into the world and projected.
        centre, half = model.geom_aabb[g, :3], model.geom_aabb[g, 3:]
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
        corners = pos + (centre + signs * half) @ mat.T
        if not _blocks(corners[:, 2].min(), corners[:, 2].max()):
            continue
        hull = _convex_hull([(float(c[0]), float(c[1])) for c in corners])
        out.append(Footprint(name, (float(pos[0]), float(pos[1])), polygon=tuple(hull),
                             z_low=float(corners[:, 2].min())))
    return out


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


def _disc_dilate(mask: np.ndarray, radius_cells: int) -> np.ndarray:
    out = mask.copy()
    rows, cols = mask.shape
    for dr in range(-radius_cells, radius_cells + 1):
        for dc in range(-radius_cells, radius_cells + 1):
            if (dr == 0 and dc == 0) or dr * dr + dc * dc > radius_cells * radius_cells:
                continue
            src = mask[max(0, -dr):rows - max(0, dr), max(0, -dc):cols - max(0, dc)]
            out[max(0, dr):rows - max(0, -dr), max(0, dc):cols - max(0, -dc)] |= src
    return out


@dataclass
class OccupancyGrid:
    """Obstacles on a grid, plus which free cells are reachable (the rest is 'unknown')."""

    occupied: np.ndarray  # bool (rows along y, cols along x): an obstacle touches the cell
    resolution: float
    origin: tuple[float, float]  # map coordinates of cell (0, 0)'s lower-left corner
    inflation: float = ROBOT_RADIUS
    known: np.ndarray | None = None  # bool: free cells reachable from the seeds, and obstacles
    _inflated: np.ndarray | None = field(default=None, repr=False)

    @classmethod
    def from_model(cls, model: mujoco.MjModel, resolution: float = 0.05, inflation: float = ROBOT_RADIUS,
                   seeds: Iterable[tuple[float, float]] = ((0.0, 0.0),)) -> OccupancyGrid:
        """Rasterise :func:`static_footprints`. A cell is occupied when an outline comes within
        half a cell of its centre, so even a wall thinner than a cell shows."""
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
        grid = cls(occupied, resolution, (x0, y0), inflation)
        grid.known = grid._reachable(seeds)
        return grid

    # -- coordinates -------------------------------------------------------------------------

    @property
    def shape(self) -> tuple[int, int]:
        return self.occupied.shape

    def world_to_cell(self, x: float, y: float) -> tuple[int, int]:
        return (int(math.floor((y - self.origin[1]) / self.resolution)),
                int(math.floor((x - self.origin[0]) / self.resolution)))

    def cell_to_world(self, row: int, col: int) -> tuple[float, float]:
        """The centre of a cell."""
        return (self.origin[0] + (col + 0.5) * self.resolution, self.origin[1] + (row + 0.5) * self.resolution)

    def inside(self, row: int, col: int) -> bool:
        return 0 <= row < self.shape[0] and 0 <= col < self.shape[1]

    @property
    def inflated(self) -> np.ndarray:
        """Obstacles grown by ``inflation``: where the robot's centre must not go."""
        if self._inflated is None:
            self._inflated = _disc_dilate(self.occupied, int(math.ceil(self.inflation / self.resolution)))
        return self._inflated

    def dilated(self, radius: float) -> np.ndarray:
        """Obstacles grown by another ``radius`` (e.g. the base's own footprint)."""
        return _disc_dilate(self.occupied, int(math.ceil(radius / self.resolution)))

    def is_free(self, x: float, y: float) -> bool:
        """Whether the robot's centre may be at (x, y): on the map, clear of inflated obstacles."""
        row, col = self.world_to_cell(x, y)
        return self.inside(row, col) and not self.inflated[row, col]

    def is_occupied(self, x: float, y: float) -> bool:
        """Whether an obstacle touches the cell at (x, y) (not inflated); off the map counts."""
        row, col = self.world_to_cell(x, y)
        return not self.inside(row, col) or bool(self.occupied[row, col])

    def _reachable(self, seeds: Iterable[tuple[float, float]]) -> np.ndarray:
        """Flood fill of free cells from the seeds; obstacles are known too."""
        known = self.occupied.copy()
        queue: deque[tuple[int, int]] = deque()
        for x, y in seeds:
            cell = self.world_to_cell(x, y)
            if self.inside(*cell) and not self.occupied[cell]:
                known[cell] = True
                queue.append(cell)
        rows, cols = self.shape
        occupied = self.occupied
        while queue:
            r, c = queue.popleft()
            for nr, nc in ((r + 1, c), (r - 1, c), (r, c + 1), (r, c - 1)):
                if 0 <= nr < rows and 0 <= nc < cols and not known[nr, nc] and not occupied[nr, nc]:
                    known[nr, nc] = True
                    queue.append((nr, nc))
        return known

    # -- files -------------------------------------------------------------------------------

    def image(self) -> np.ndarray:
        """The map_server picture: row 0 at the top (highest y)."""
        pixels = np.full(self.shape, FREE, dtype=np.uint8)
        if self.known is not None:
            pixels[~self.known] = UNKNOWN
        pixels[self.occupied] = OCCUPIED
        return np.flipud(pixels)

    def save(self, stem: str | Path) -> tuple[Path, Path]:
        """Write ``stem.png`` and ``stem.yaml`` (map_server format, plus our ``inflation``)."""
        from PIL import Image

        stem = Path(stem)
        png, yaml_path = stem.with_suffix(".png"), stem.with_suffix(".yaml")
        png.parent.mkdir(parents=True, exist_ok=True)
        Image.fromarray(self.image()).save(png, optimize=True)
        yaml_path.write_text(
            f"image: {png.name}\n"
            "mode: trinary\n"
            f"resolution: {self.resolution:g}\n"
            f"origin: [{self.origin[0]:.4f}, {self.origin[1]:.4f}, 0.0]\n"
            "negate: 0\n"
            "occupied_thresh: 0.65\n"
            "free_thresh: 0.196\n"
            f"inflation: {self.inflation:g}  # robot radius the map is planned with (not a map_server key)\n",
            encoding="utf-8")
        return png, yaml_path

    @classmethod
    def load(cls, yaml_path: str | Path, inflation: float | None = None) -> OccupancyGrid:
        import yaml
        from PIL import Image

        yaml_path = Path(yaml_path)
        meta = yaml.safe_load(yaml_path.read_text(encoding="utf-8"))
        pixels = np.flipud(np.asarray(Image.open(yaml_path.parent / meta["image"]).convert("L")))
        occupancy = pixels / 255.0 if meta.get("negate", 0) else (255.0 - pixels) / 255.0
        occupied = occupancy > float(meta.get("occupied_thresh", 0.65))
        free = occupancy < float(meta.get("free_thresh", 0.196))
        radius = float(meta.get("inflation", ROBOT_RADIUS)) if inflation is None else inflation
        origin = (float(meta["origin"][0]), float(meta["origin"][1]))
        return cls(occupied.copy(), float(meta["resolution"]), origin, radius, known=(occupied | free).copy())


def draw_map_png(grid: OccupancyGrid, markers: Mapping[str, Mapping[str, float]],
                 path_points: Sequence[tuple[float, float]], objects: Mapping[str, Mapping[str, float]],
                 out_path: str | Path, scale: int = 4, memory: Sequence[Mapping[str, Any]] = ()) -> Path:
    """The map with what happened on it: obstacles (and their inflation), named markers with
    their headings, the driven path (start green, end red), the objects where they are, and the
    spatial memory (``memory``: entries of a memory summary, drawn as rings sized by their
    confidence, so where the robot *believes* things are can be compared with where they are)."""
    from PIL import Image, ImageDraw, ImageFont

    rows, cols = grid.shape
    rgb = np.full((rows, cols, 3), 255, dtype=np.uint8)
    rgb[grid.inflated] = (225, 228, 235)
    if grid.known is not None:
        rgb[~grid.known] = (190, 190, 190)
    rgb[grid.occupied] = (60, 60, 70)
    big = np.repeat(np.repeat(rgb, scale, axis=0), scale, axis=1)
    free = (big == 255).all(axis=2)
    for k in range(math.ceil(grid.origin[0]), math.floor(grid.origin[0] + cols * grid.resolution) + 1):
        c = int(round((k - grid.origin[0]) / grid.resolution * scale))  # a light 1 m grid on free space
        if 0 <= c < big.shape[1]:
            big[free[:, c], c] = (232, 236, 242)
    for k in range(math.ceil(grid.origin[1]), math.floor(grid.origin[1] + rows * grid.resolution) + 1):
        row = int(round((k - grid.origin[1]) / grid.resolution * scale))
        if 0 <= row < big.shape[0]:
            big[row, free[row, :]] = (232, 236, 242)
    image = Image.fromarray(np.flipud(big).copy())
    draw = ImageDraw.Draw(image)
    try:
        font = ImageFont.load_default(size=max(10, 3 * scale))
    except TypeError:  # Pillow < 10.1
        font = ImageFont.load_default()

    def px(x: float, y: float) -> tuple[float, float]:
        return ((x - grid.origin[0]) / grid.resolution * scale, (rows - (y - grid.origin[1]) / grid.resolution) * scale)

    metre = scale / grid.resolution
    if len(path_points) >= 2:
        draw.line([px(x, y) for x, y in path_points], fill=(30, 110, 230), width=max(2, scale // 2))
    if path_points:
        for (x, y), colour in ((path_points[0], (40, 170, 60)), (path_points[-1], (220, 40, 40))):
            cx, cy = px(x, y)
            r = 0.08 * metre
            draw.ellipse([cx - r, cy - r, cx + r, cy + r], fill=colour)
    for name, m in markers.items():
        cx, cy = px(float(m["x"]), float(m["y"]))
        r = 0.1 * metre
        draw.ellipse([cx - r, cy - r, cx + r, cy + r], outline=(200, 120, 0), width=2)
        yaw = float(m.get("yaw", 0.0) or 0.0)
        tip = px(float(m["x"]) + 0.3 * math.cos(yaw), float(m["y"]) + 0.3 * math.sin(yaw))
        draw.line([(cx, cy), tip], fill=(200, 120, 0), width=2)
        draw.text((cx + r + 2, cy - r - 2), name, fill=(140, 80, 0), font=font, stroke_width=2,
                  stroke_fill=(255, 255, 255))
    for label, o in objects.items():
        cx, cy = px(float(o["x"]), float(o["y"]))
        r = 0.05 * metre
        draw.rectangle([cx - r, cy - r, cx + r, cy + r], fill=(200, 30, 120))
        draw.text((cx + r + 2, cy + 1), label, fill=(150, 20, 90), font=font, stroke_width=2,
                  stroke_fill=(255, 255, 255))
    for entry in memory:
        cx, cy = px(float(entry["x"]), float(entry["y"]))
        r = (0.06 + 0.08 * max(0.0, min(1.0, float(entry.get("confidence", 1.0))))) * metre
        draw.ellipse([cx - r, cy - r, cx + r, cy + r], outline=(0, 150, 170), width=max(2, scale // 2))
        draw.text((cx + r + 2, cy - r - 2 * scale), f"{entry.get('id', entry.get('label', '?'))} "
                  f"{float(entry.get('confidence', 1.0)):.2f}", fill=(0, 110, 130), font=font, stroke_width=2,
                  stroke_fill=(255, 255, 255))
    out_path = Path(out_path)
    out_path.parent.mkdir(parents=True, exist_ok=True)
    image.save(out_path)
    return out_path


def load_markers(path: str | Path | None = None) -> dict[str, dict[str, float]]:
    """The named markers (default: sim/maps/lab_markers.json); a regular file under the data
    file size limit only (stuart_bt.core.jsonfile.read_json)."""
    from stuart_bt.core.world import MarkerFileError

    from .scene import MAPS_DIR

    doc = read_json(path or MAPS_DIR / "lab_markers.json", MarkerFileError, "marker file")
    if not isinstance(doc, dict) or not isinstance(doc.get("markers"), dict):
        raise MarkerFileError(f"{path}: expected an object with a 'markers' mapping")
    return doc["markers"]


def scene_grid(scene: str = "lab", resolution: float = 0.05, inflation: float = ROBOT_RADIUS) -> OccupancyGrid:
    """The grid of a scene file alone (no robot needed: it is never part of the map)."""
    from .scene import scene_path

    model = mujoco.MjModel.from_xml_path(str(scene_path(scene)))
    return OccupancyGrid.from_model(model, resolution, inflation)


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
    png, yaml_path = grid.save(options.out or MAPS_DIR / options.scene)
    print(f"wrote {png} and {yaml_path} ({grid.shape[1]} x {grid.shape[0]} cells)")
    if options.picture:
        draw_map_png(grid, load_markers(), [], {}, options.picture)
        print(f"wrote {options.picture}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
