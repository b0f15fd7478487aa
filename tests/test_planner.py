"""Global planner (stuart_bt.maps): A* on an occupancy grid with line-of-sight smoothing."""

from __future__ import annotations

from itertools import pairwise

import numpy as np
import pytest

from stuart_bt.maps.grid import Grid
from stuart_bt.maps.paths import PlanningError, path_length, plan


def room_with_wall() -> Grid:
    """6 x 4 m at 5 cm; a wall at x = 3 m with a 1 m doorway at y in [2.5, 3.5]."""
    occ = np.zeros((80, 120), dtype=bool)
    occ[:, 59:61] = True
    occ[50:70, 59:61] = False
    return Grid(occ, 0.05, (0.0, 0.0))


def test_straight_line_when_nothing_is_in_the_way():
    grid = Grid(np.zeros((40, 40), dtype=bool), 0.05, (0.0, 0.0))
    assert plan(grid, (0.2, 0.2), (1.8, 1.0)) == [(0.2, 0.2), (1.8, 1.0)]


def test_path_goes_through_the_doorway_and_every_segment_is_free():
    grid = room_with_wall()
    points = plan(grid, (1.0, 0.5), (5.0, 0.5))
    assert points[0] == (1.0, 0.5) and points[-1] == (5.0, 0.5)
    assert any(2.5 <= y <= 3.5 and 2.8 <= x <= 3.2 for x, y in points)  # a waypoint in the doorway
    assert all(grid.segment_free(a, b) for a, b in pairwise(points))
    assert len(points) <= 5  # smoothing removed the staircase
    assert path_length(points) < 4.0 + 2 * 2.7  # not much longer than via the door's corners


def test_goal_inside_a_wall_is_refused_with_a_reason():
    with pytest.raises(PlanningError, match="goal .* inside an obstacle"):
        plan(room_with_wall(), (1.0, 0.5), (3.0, 0.5), snap=0.0)


def test_goal_just_inside_the_margin_snaps_to_free_space():
    points = plan(room_with_wall(), (1.0, 0.5), (2.96, 3.0))
    assert points[-1] == (2.96, 3.0)


def test_no_route_when_the_doorway_is_closed():
    grid = room_with_wall()
    grid.occupied[:, 59:61] = True
    with pytest.raises(PlanningError, match="no path"):
        plan(grid, (1.0, 0.5), (5.0, 0.5))


def test_off_the_map_is_refused():
    with pytest.raises(PlanningError, match="off the map"):
        plan(room_with_wall(), (1.0, 0.5), (9.0, 0.5))


def test_a_start_docked_inside_the_margin_still_plans_with_an_exact_goal():
    grid = room_with_wall()
    docked = (2.96, 0.5)  # in the (uninflated) wall cells: as a robot docked inside a planning margin
    points = plan(grid, docked, (1.0, 0.5), snap=0.0)
    assert points[0] == docked and points[-1] == (1.0, 0.5)
