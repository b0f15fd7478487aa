"""Global path planning on an occupancy grid: 8-connected A*, then line-of-sight smoothing.

The grid is a 2-D array of booleans (True = occupied), already inflated by the robot's radius,
with ``resolution`` metres per cell and ``origin`` the map coordinates of cell (0, 0)'s corner,
rows along y and columns along x (the ROS map_server convention, row 0 at the bottom). The
result is a short list of map-frame waypoints whose straight segments are all collision-free,
which is what both the simulator's path follower and the robot's straight-line navigation
service want.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Sequence
from dataclasses import dataclass
from itertools import pairwise

import numpy as np

from stuart_bt.core.errors import StuartError

SQRT2 = math.sqrt(2.0)
NEIGHBOURS = [(1, 0, 1.0), (-1, 0, 1.0), (0, 1, 1.0), (0, -1, 1.0),
              (1, 1, SQRT2), (1, -1, SQRT2), (-1, 1, SQRT2), (-1, -1, SQRT2)]


class PlanningError(StuartError):
    """No path: the reason says why (goal in an obstacle, off the map, no route)."""


@dataclass
class Grid:
    occupied: np.ndarray  # bool, shape (rows along y, cols along x)
    resolution: float
    origin: tuple[float, float]

    def cell(self, x: float, y: float) -> tuple[int, int]:
        return (int(math.floor((y - self.origin[1]) / self.resolution)),
                int(math.floor((x - self.origin[0]) / self.resolution)))

    def centre(self, row: int, col: int) -> tuple[float, float]:
        return (self.origin[0] + (col + 0.5) * self.resolution, self.origin[1] + (row + 0.5) * self.resolution)

    def inside(self, row: int, col: int) -> bool:
        return 0 <= row < self.occupied.shape[0] and 0 <= col < self.occupied.shape[1]

    def free(self, row: int, col: int) -> bool:
        return self.inside(row, col) and not self.occupied[row, col]

    def nearest_free(self, row: int, col: int, max_cells: int) -> tuple[int, int] | None:
        """The closest free cell within ``max_cells`` (rings outward), for a start or goal that
        sits just inside the inflation margin."""
        if self.free(row, col):
            return row, col
        best: tuple[float, tuple[int, int]] | None = None
        for r in range(row - max_cells, row + max_cells + 1):
            for c in range(col - max_cells, col + max_cells + 1):
                if self.free(r, c):
                    d = math.hypot(r - row, c - col)
                    if d <= max_cells and (best is None or d < best[0]):
                        best = (d, (r, c))
        return best[1] if best else None

    def segment_free(self, a: tuple[float, float], b: tuple[float, float]) -> bool:
        """Every cell a straight segment passes is free (sampled at a quarter cell)."""
        steps = max(1, int(math.hypot(b[0] - a[0], b[1] - a[1]) / (self.resolution * 0.25)))
        for i in range(steps + 1):
            t = i / steps
            if not self.free(*self.cell(a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t)):
                return False
        return True


def plan(grid: Grid, start: tuple[float, float], goal: tuple[float, float], snap: float = 0.3,
         start_snap: float = 0.3) -> list[tuple[float, float]]:
    """Waypoints from ``start`` to ``goal`` (both included). A goal within ``snap`` metres of free
    space (a start within ``start_snap``: the robot may stand docked at a table) is moved onto it;
    farther inside an obstacle is a :class:`PlanningError`."""
    s = _endpoint(grid, start, int(start_snap / grid.resolution), "start")
    g = _endpoint(grid, goal, int(snap / grid.resolution), "goal")
    cells = _astar(grid, s, g)
    if cells is None:
        raise PlanningError(f"no path from ({start[0]:.2f}, {start[1]:.2f}) to ({goal[0]:.2f}, {goal[1]:.2f})")
    points = [start] + [grid.centre(r, c) for r, c in cells[1:-1]] + [goal]
    return smooth(grid, points)


def _endpoint(grid: Grid, xy: tuple[float, float], snap_cells: int, what: str) -> tuple[int, int]:
    row, col = grid.cell(*xy)
    if not grid.inside(row, col):
        raise PlanningError(f"{what} ({xy[0]:.2f}, {xy[1]:.2f}) is off the map")
    found = grid.nearest_free(row, col, snap_cells)
    if found is None:
        raise PlanningError(f"{what} ({xy[0]:.2f}, {xy[1]:.2f}) is inside an obstacle")
    return found


def _astar(grid: Grid, start: tuple[int, int], goal: tuple[int, int]) -> list[tuple[int, int]] | None:
    def h(cell: tuple[int, int]) -> float:  # octile distance: admissible on an 8-connected grid
        dr, dc = abs(cell[0] - goal[0]), abs(cell[1] - goal[1])
        return (dr + dc) + (SQRT2 - 2.0) * min(dr, dc)

    occupied = grid.occupied
    rows, cols = occupied.shape
    g_cost = {start: 0.0}
    parent: dict[tuple[int, int], tuple[int, int]] = {}
    frontier = [(h(start), 0.0, start)]
    closed: set[tuple[int, int]] = set()
    while frontier:
        _, cost, cell = heapq.heappop(frontier)
        if cell == goal:
            path = [cell]
            while cell in parent:
                cell = parent[cell]
                path.append(cell)
            return path[::-1]
        if cell in closed:
            continue
        closed.add(cell)
        r, c = cell
        for dr, dc, step in NEIGHBOURS:
            nr, nc = r + dr, c + dc
            if not (0 <= nr < rows and 0 <= nc < cols) or occupied[nr, nc]:
                continue
            if dr and dc and (occupied[r, nc] or occupied[nr, c]):
                continue  # no cutting corners between two occupied cells
            new = cost + step
            if new < g_cost.get((nr, nc), math.inf):
                g_cost[(nr, nc)] = new
                parent[(nr, nc)] = cell
                heapq.heappush(frontier, (new + h((nr, nc)), new, (nr, nc)))
    return None


def smooth(grid: Grid, points: Sequence[tuple[float, float]]) -> list[tuple[float, float]]:
    """Greedy line-of-sight shortcutting: from each kept point jump to the farthest visible one."""
    if len(points) <= 2:
        return list(points)
    out = [points[0]]
    i = 0
    while i < len(points) - 1:
        j = len(points) - 1
        while j > i + 1 and not grid.segment_free(points[i], points[j]):
            j -= 1
        out.append(points[j])
        i = j
    return out


def path_length(points: Sequence[tuple[float, float]]) -> float:
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in pairwise(points))


def inflate(occupied: np.ndarray, radius_cells: int) -> np.ndarray:
    """Grow obstacles by a disc of ``radius_cells`` (so a point robot plans for a round one)."""
    out = occupied.copy()
    rows, cols = occupied.shape
    for dr in range(-radius_cells, radius_cells + 1):
        for dc in range(-radius_cells, radius_cells + 1):
            if dr * dr + dc * dc > radius_cells * radius_cells or (dr == 0 and dc == 0):
                continue
            src = occupied[max(0, -dr):rows - max(0, dr), max(0, -dc):cols - max(0, dc)]
            out[max(0, dr):rows - max(0, -dr), max(0, dc):cols - max(0, -dc)] |= src
    return out


def load_map(yaml_path: str, robot_radius: float = 0.3) -> Grid:
    """A ROS map_server map (YAML + image): occupied where (255 - pixel) / 255 > occupied_thresh
    (``negate: 0``), image row 0 at the top; obstacles inflated by ``robot_radius``."""
    import os

    import yaml
    from PIL import Image

    with open(yaml_path, encoding="utf-8") as f:
        meta = yaml.safe_load(f)
    image_path = os.path.join(os.path.dirname(yaml_path), meta["image"])
    pixels = np.asarray(Image.open(image_path).convert("L"), dtype=np.float64)
    occupancy = pixels / 255.0 if meta.get("negate", 0) else (255.0 - pixels) / 255.0
    occupied = np.flipud(occupancy > float(meta.get("occupied_thresh", 0.65)))
    resolution = float(meta["resolution"])
    origin = (float(meta["origin"][0]), float(meta["origin"][1]))
    return Grid(inflate(occupied, int(math.ceil(robot_radius / resolution))), resolution, origin)
