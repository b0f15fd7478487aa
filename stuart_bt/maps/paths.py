"""Global paths on a planning grid: endpoints snapped onto free space, A*, line-of-sight smoothing.

The grid is already inflated by the robot's radius (``OccupancyGrid.planning_grid`` in
:mod:`stuart_bt.maps.grid`). The result is a short list of map-frame waypoints whose straight segments are
all collision-free, which is what both the simulator's path follower and the robot's
straight-line navigation service want.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from itertools import pairwise

from ..core.errors import StuartError
from .astar import astar
from .grid import Grid

Point = tuple[float, float]


class PlanningError(StuartError):
    """No path: the reason says why (goal in an obstacle, off the map, no route)."""


def plan(grid: Grid, start: Point, goal: Point, snap: float = 0.3, start_snap: float = 0.3) -> list[Point]:
    """Waypoints from ``start`` to ``goal`` (both included). A goal within ``snap`` metres of free
    space (a start within ``start_snap``: the robot may stand docked at a table) is moved onto it;
    farther inside an obstacle is a :class:`PlanningError`."""
    s = _endpoint(grid, start, int(start_snap / grid.resolution), "start")
    g = _endpoint(grid, goal, int(snap / grid.resolution), "goal")
    cells = astar(grid.occupied, s, g)
    if cells is None:
        raise PlanningError(f"no path from ({start[0]:.2f}, {start[1]:.2f}) to ({goal[0]:.2f}, {goal[1]:.2f})")
    points = [start] + [grid.cell_to_world(r, c) for r, c in cells[1:-1]] + [goal]
    return smooth(grid, points)


def _endpoint(grid: Grid, xy: Point, snap_cells: int, what: str) -> tuple[int, int]:
    row, col = grid.world_to_cell(*xy)
    if not grid.inside(row, col):
        raise PlanningError(f"{what} ({xy[0]:.2f}, {xy[1]:.2f}) is off the map")
    found = grid.nearest_free(row, col, snap_cells)
    if found is None:
        raise PlanningError(f"{what} ({xy[0]:.2f}, {xy[1]:.2f}) is inside an obstacle")
    return found


def smooth(grid: Grid, points: Sequence[Point]) -> list[Point]:
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


def path_length(points: Sequence[Point]) -> float:
    """Metres along the waypoints."""
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in pairwise(points))
