"""Growing obstacles by the robot's radius, so a robot planned as a point stays clear of them.

Both the world server (its map, and its footprint check) and the loco planner inflate the same
way; a disc of whole cells is what ROS map_server based planners do too.
"""

from __future__ import annotations

import math

import numpy as np


def radius_in_cells(radius: float, resolution: float) -> int:
    """A radius in metres as whole cells, rounded up: a margin may grow, never shrink."""
    return int(math.ceil(radius / resolution))


def inflate(occupied: np.ndarray, radius_cells: int) -> np.ndarray:
    """Grow obstacles by a disc of ``radius_cells`` (so a point robot plans for a round one).

    Shifted copies of the mask, one per cell offset inside the disc, are OR-ed together: exact
    for the disc, no SciPy needed, and fast enough for a lab map (a few hundred cells a side).
    """
    out = occupied.copy()
    rows, cols = occupied.shape
    for dr in range(-radius_cells, radius_cells + 1):
        for dc in range(-radius_cells, radius_cells + 1):
            if (dr == 0 and dc == 0) or dr * dr + dc * dc > radius_cells * radius_cells:
                continue
            src = occupied[max(0, -dr):rows - max(0, dr), max(0, -dc):cols - max(0, dc)]
            out[max(0, dr):rows - max(0, -dr), max(0, dc):cols - max(0, -dc)] |= src
    return out
