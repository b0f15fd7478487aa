"""Occupancy grids in the map frame: where cells are, which are free, and the robot's margin.

Convention as ROS map_server: rows along y with row 0 at the lowest y, columns along x,
``origin`` the map coordinates of cell (0, 0)'s lower-left corner. :class:`Grid` is any boolean
grid (the planner's, already inflated); :class:`OccupancyGrid` is the map itself: the raw
obstacles, which free cells are known (reachable), and the robot radius it is inflated by.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

from .inflation import inflate, radius_in_cells

ROBOT_RADIUS = 0.3  # metres: the G1's footprint, what maps are inflated by unless told otherwise


@dataclass
class Grid:
    """A boolean grid placed in the map frame; True cells are blocked."""

    occupied: np.ndarray  # bool, shape (rows along y, cols along x)
    resolution: float  # metres per cell
    origin: tuple[float, float]  # map coordinates of cell (0, 0)'s lower-left corner

    @property
    def shape(self) -> tuple[int, int]:
        return self.occupied.shape

    def world_to_cell(self, x: float, y: float) -> tuple[int, int]:
        """The (row, col) of the cell holding a map point (possibly off the grid)."""
        return (int(math.floor((y - self.origin[1]) / self.resolution)),
                int(math.floor((x - self.origin[0]) / self.resolution)))

    def cell_to_world(self, row: int, col: int) -> tuple[float, float]:
        """The centre of a cell."""
        return (self.origin[0] + (col + 0.5) * self.resolution, self.origin[1] + (row + 0.5) * self.resolution)

    def inside(self, row: int, col: int) -> bool:
        return 0 <= row < self.occupied.shape[0] and 0 <= col < self.occupied.shape[1]

    def cell_is_free(self, row: int, col: int) -> bool:
        """On the grid and not blocked (off the grid counts as blocked)."""
        return self.inside(row, col) and not self.occupied[row, col]

    def nearest_free(self, row: int, col: int, max_cells: int) -> tuple[int, int] | None:
        """The closest free cell within ``max_cells`` (rings outward), for a start or goal that
        sits just inside the inflation margin."""
        if self.cell_is_free(row, col):
            return row, col
        best: tuple[float, tuple[int, int]] | None = None
        for r in range(row - max_cells, row + max_cells + 1):
            for c in range(col - max_cells, col + max_cells + 1):
                if self.cell_is_free(r, c):
                    d = math.hypot(r - row, c - col)
                    if d <= max_cells and (best is None or d < best[0]):
                        best = (d, (r, c))
        return best[1] if best else None

    def segment_free(self, a: tuple[float, float], b: tuple[float, float]) -> bool:
        """Every cell a straight segment passes is free (sampled at a quarter cell)."""
        return self.first_blocked(a, b) is None

    def first_blocked(self, a: tuple[float, float], b: tuple[float, float]) -> tuple[float, float] | None:
        """The first point from ``a`` towards ``b`` in a blocked cell (sampled at a quarter
        cell), or None when the whole segment is free: where a straight move would hit."""
        steps = max(1, int(math.hypot(b[0] - a[0], b[1] - a[1]) / (self.resolution * 0.25)))
        for i in range(steps + 1):
            t = i / steps
            x, y = a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t
            if not self.cell_is_free(*self.world_to_cell(x, y)):
                return x, y
        return None


@dataclass
class OccupancyGrid(Grid):
    """The map: obstacles (``occupied``, not inflated), which cells are known, and the robot
    radius it is planned with. The world server checks the base against it; the loco daemon
    plans on :meth:`planning_grid`."""

    inflation: float = ROBOT_RADIUS  # metres obstacles grow by for the robot's centre
    known: np.ndarray | None = None  # bool: free cells reachable from the seeds, and obstacles
    _inflated: np.ndarray | None = field(default=None, repr=False)

    @classmethod
    def from_obstacles(cls, occupied: np.ndarray, resolution: float, origin: tuple[float, float],
                       inflation: float = ROBOT_RADIUS,
                       seeds: Iterable[tuple[float, float]] = ((0.0, 0.0),)) -> OccupancyGrid:
        """A map of raw obstacles; free space not reachable from the seeds (the far side of a
        wall) is marked unknown, as a robot exploring from the seeds would have it."""
        grid = cls(occupied, resolution, origin, inflation)
        grid.known = grid.reachable(seeds)
        return grid

    @property
    def inflated(self) -> np.ndarray:
        """Obstacles grown by ``inflation``: where the robot's centre must not go."""
        if self._inflated is None:
            self._inflated = inflate(self.occupied, radius_in_cells(self.inflation, self.resolution))
        return self._inflated

    def dilated(self, radius: float) -> np.ndarray:
        """Obstacles grown by another ``radius`` (e.g. the base's own footprint)."""
        return inflate(self.occupied, radius_in_cells(radius, self.resolution))

    def planning_grid(self, radius: float | None = None) -> Grid:
        """The cells the robot's centre may not enter, for :func:`stuart_bt.maps.paths.plan`:
        obstacles grown by ``radius`` (default the map's own ``inflation``)."""
        blocked = self.inflated if radius is None else self.dilated(radius)
        return Grid(blocked, self.resolution, self.origin)

    def is_free(self, x: float, y: float) -> bool:
        """Whether the robot's centre may be at (x, y): on the map, clear of inflated obstacles."""
        row, col = self.world_to_cell(x, y)
        return self.inside(row, col) and not self.inflated[row, col]

    def is_occupied(self, x: float, y: float) -> bool:
        """Whether an obstacle touches the cell at (x, y) (not inflated); off the map counts."""
        row, col = self.world_to_cell(x, y)
        return not self.inside(row, col) or bool(self.occupied[row, col])

    def reachable(self, seeds: Iterable[tuple[float, float]]) -> np.ndarray:
        """Flood fill (4-connected) of free cells from the seeds; obstacles are known too."""
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
