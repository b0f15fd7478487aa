"""The cheapest of many goals by walking distance: one Dijkstra search from the robot.

Choosing where to stand among a few hundred candidate spots by trying A* to each in turn costs
a search per spot, and a whole-map search for every spot in a pocket nothing reaches. One
search that grows from the robot and stops at the first goal it settles answers "which of these
is nearest on foot" at the price of one search. Steering it towards the goals (A*) matters: a
whole viewpoint search in the lab took 0.03-0.18 s with it and 0.07-0.26 s without (five goals,
a busy two-core machine), and the loco daemon must heartbeat within 1 s. A goal may carry an extra cost (a last straight
step onto it, a preference between spots); the search only ends once no cheaper goal can follow.
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Mapping, Sequence
from typing import TypeVar

import numpy as np

from .astar import NEIGHBOURS, Cell

T = TypeVar("T")


def nearest_goal(blocked: np.ndarray, start: Cell,
                 goals: Mapping[Cell, Sequence[tuple[float, T]]]) -> tuple[float, T] | None:
    """``(cost, payload)`` of the cheapest goal: walking cost in cells (8-connected, no cutting
    corners, as :func:`stuart_bt.maps.astar.astar`) to the goal's cell plus its extra cost (in
    cells too, never negative). ``goals`` maps a cell to its ``(extra, payload)`` entries. None
    when no goal cell can be reached from ``start``.

    The search is A* towards the goals' middle: no goal is nearer to a cell than the cell's
    distance to the middle less the goals' spread, a consistent estimate, so the first goal
    entry taken from the queue is the cheapest and the search stays in the goals' direction."""
    if not goals:
        return None
    cells = list(goals)
    mid = (sum(r for r, _ in cells) / len(cells), sum(c for _, c in cells) / len(cells))
    spread = max(_octile(cell, mid) for cell in cells)

    def h(cell: Cell) -> float:
        return max(0.0, _octile(cell, mid) - spread)

    rows, cols = blocked.shape
    order = itertools.count()  # ties keep insertion order; payloads are never compared
    best = {start: 0.0}
    frontier: list[tuple[float, int, float, Cell | None, T | None]] = [(h(start), next(order), 0.0, start, None)]
    settled: set[Cell] = set()
    while frontier:
        _, _, cost, cell, payload = heapq.heappop(frontier)
        if cell is None:  # a goal's entry: nothing cheaper is left in the queue
            return cost, payload  # type: ignore[return-value]
        if cell in settled:
            continue
        settled.add(cell)
        for extra, goal in goals.get(cell, ()):
            heapq.heappush(frontier, (cost + extra, next(order), cost + extra, None, goal))
        r, c = cell
        for dr, dc, step in NEIGHBOURS:
            nr, nc = r + dr, c + dc
            if not (0 <= nr < rows and 0 <= nc < cols) or blocked[nr, nc]:
                continue
            if dr and dc and (blocked[r, nc] or blocked[nr, c]):
                continue
            new = cost + step
            if new < best.get((nr, nc), math.inf):
                best[(nr, nc)] = new
                heapq.heappush(frontier, (new + h((nr, nc)), next(order), new, (nr, nc), None))
    return None


def _octile(cell: Cell, point: tuple[float, float]) -> float:
    """The shortest 8-connected distance between a cell and a point, on an empty grid."""
    dr, dc = abs(cell[0] - point[0]), abs(cell[1] - point[1])
    return (dr + dc) + (math.sqrt(2.0) - 2.0) * min(dr, dc)
