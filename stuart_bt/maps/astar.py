"""A* search between two cells of a boolean grid, 8-connected.

Diagonal steps cost sqrt(2) and may not cut the corner between two blocked cells, so a path
never squeezes through a gap a robot's outline could not pass.
"""

from __future__ import annotations

import heapq
import math

import numpy as np

SQRT2 = math.sqrt(2.0)
NEIGHBOURS = [(1, 0, 1.0), (-1, 0, 1.0), (0, 1, 1.0), (0, -1, 1.0),
              (1, 1, SQRT2), (1, -1, SQRT2), (-1, 1, SQRT2), (-1, -1, SQRT2)]

Cell = tuple[int, int]


def astar(blocked: np.ndarray, start: Cell, goal: Cell) -> list[Cell] | None:
    """The cells of a shortest path from ``start`` to ``goal`` (both included), or None when
    the goal cannot be reached. ``blocked`` is True where the robot's centre may not be."""

    def h(cell: Cell) -> float:  # octile distance: admissible on an 8-connected grid
        dr, dc = abs(cell[0] - goal[0]), abs(cell[1] - goal[1])
        return (dr + dc) + (SQRT2 - 2.0) * min(dr, dc)

    rows, cols = blocked.shape
    g_cost = {start: 0.0}
    parent: dict[Cell, Cell] = {}
    frontier = [(h(start), 0.0, start)]
    closed: set[Cell] = set()
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
            if not (0 <= nr < rows and 0 <= nc < cols) or blocked[nr, nc]:
                continue
            if dr and dc and (blocked[r, nc] or blocked[nr, c]):
                continue  # no cutting corners between two occupied cells
            new = cost + step
            if new < g_cost.get((nr, nc), math.inf):
                g_cost[(nr, nc)] = new
                parent[(nr, nc)] = cell
                heapq.heappush(frontier, (new + h((nr, nc)), new, (nr, nc)))
    return None
