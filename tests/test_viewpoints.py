"""Where to stand to see something (stuart_bt.maps.viewpoints): the head camera's view from a
base pose, lines of sight on a map that has no heights, and the search for the spot nearest on
foot from which the camera sees a point. Maps here are drawn in the test (rooms, tables, walls),
so the rules are checked on layouts the lab does not have."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from stuart_bt.core.world import Pose
from stuart_bt.maps.astar import astar
from stuart_bt.maps.furniture import Furniture, Piece
from stuart_bt.maps.grid import Grid, OccupancyGrid
from stuart_bt.maps.nearest import nearest_goal
from stuart_bt.maps.viewpoints import NoViewpoint, StandingMap, find_viewpoint, line_of_sight
from stuart_bt.perception.frames import Intrinsics
from stuart_bt.perception.projection import CameraMount, head_camera_view, project, world_to_torso

RES = 0.05
CAMERA = head_camera_view()
TABLE_TOP = 0.79  # an apple's centre on the lab's kitchen table
Box = tuple[float, float, float, float]  # x0, x1, y0, y1


def room(boxes: dict[str, Box], size: tuple[float, float] = (6.0, 6.0), named: bool = True) -> StandingMap:
    """A walled room ``size`` metres from (0, 0) with the named boxes in it, planned as the sim
    loco daemon plans: the robot's 0.3 m radius to walk, 0.15 m to stand docked at furniture."""
    cols, rows = int(round(size[0] / RES)) + 2, int(round(size[1] / RES)) + 2
    occupied = np.zeros((rows, cols), dtype=bool)
    occupied[0, :] = occupied[-1, :] = occupied[:, 0] = occupied[:, -1] = True
    origin = (-RES, -RES)
    for x0, x1, y0, y1 in boxes.values():
        c0, c1 = int(math.floor((x0 - origin[0]) / RES)), int(math.ceil((x1 - origin[0]) / RES))
        r0, r1 = int(math.floor((y0 - origin[1]) / RES)), int(math.ceil((y1 - origin[1]) / RES))
        occupied[r0:r1, c0:c1] = True
    grid = OccupancyGrid.from_obstacles(occupied, RES, origin, 0.3, seeds=((0.5, 0.5),))
    pieces = tuple(Piece(name, (((x0, y0), (x1, y0), (x1, y1), (x0, y1)),)) for name, (x0, x1, y0, y1) in boxes.items())
    furniture = Furniture(pieces) if named else Furniture()
    return StandingMap(Grid(grid.occupied, RES, origin), grid.planning_grid(), grid.planning_grid(0.15),
                       furniture=furniture)


def sees(space: StandingMap, base: tuple[float, float, float], target: tuple[float, float, float]) -> bool:
    eye = CAMERA.eye(*base)
    return CAMERA.miss(base, target) is None and line_of_sight(space.obstacles, eye, target[:2]) is None


def walkable(space: StandingMap, here: tuple[float, float], spot: tuple[float, float]) -> bool:
    """The spot leaves the docking margin free and a path leads to it (as the loco daemon walks)."""
    if not space.tight.cell_is_free(*space.tight.world_to_cell(*spot)):
        return False
    docking = space.docking_cell(*spot)
    start = space.roomy.nearest_free(*space.roomy.world_to_cell(*here), 6)
    return docking is not None and start is not None and astar(space.roomy.occupied, start, docking[0]) is not None


# -- the camera ------------------------------------------------------------------------------------------
def test_the_camera_sees_exactly_what_the_perception_projection_puts_inside_the_picture():
    """The loco daemon's view of the camera and the vision pipeline's projection are two pieces of
    code; over random poses and points they must agree on what is in the picture (the search's
    margin shrinks the picture to its central 80 %; points within a pixel of that edge are left out)."""
    mount, k = CameraMount.sim(), Intrinsics.from_fov(640, 480, 42.0)
    rng = np.random.default_rng(16)
    agreed = seen = 0
    for _ in range(4000):
        base = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-math.pi, math.pi))
        target = np.array([rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5), rng.uniform(0.0, 1.2)])
        optical = mount.to_optical(world_to_torso(target, Pose(*base)))
        distance = float(np.linalg.norm(optical))
        if optical[2] <= 0.05:
            assert CAMERA.miss(base, tuple(target)) is not None
            agreed += 1
            continue
        u, v = project(optical, k)
        du, dv = abs(u - k.cx) - CAMERA.margin * k.width / 2, abs(v - k.cy) - CAMERA.margin * k.height / 2
        if -1.0 < du < 1.0 or -1.0 < dv < 1.0 or min(abs(distance - CAMERA.far), abs(distance - CAMERA.near)) < 0.01:
            continue
        inside = du < 0 and dv < 0 and CAMERA.near <= distance <= CAMERA.far
        assert (CAMERA.miss(base, tuple(target)) is None) == inside, (base, target, u, v, distance)
        agreed += 1
        seen += inside
    assert agreed > 3800 and seen > 100, f"the sample did not test both answers ({agreed}, {seen} in view)"


@pytest.mark.parametrize("height", [0.0, 0.4, TABLE_TOP, 1.0])
def test_a_point_straight_ahead_is_in_view_only_inside_the_band_for_its_height(height):
    near, far = CAMERA.band(height)
    for distance, in_view in ((near + 0.01, True), ((near + far) / 2, True), (far - 0.01, True),
                              (near - 0.02, False), (far + 0.02, False)):
        eye_x = CAMERA.ahead  # base at the origin facing +x: the eye is this far ahead
        assert (CAMERA.miss((0.0, -CAMERA.left, 0.0), (eye_x + distance, 0.0, height)) is None) == in_view, distance
    centred = CAMERA.centred(height)
    assert near <= centred <= far


def test_a_point_at_the_cameras_height_or_above_is_never_in_view_of_a_camera_looking_down():
    assert CAMERA.band(CAMERA.height + 0.2) is None
    assert CAMERA.band(CAMERA.height) is None
    assert CAMERA.centred(CAMERA.height + 0.2) is None


# -- lines of sight ----------------------------------------------------------------------------------
def test_what_a_point_stands_on_does_not_hide_it_but_other_furniture_does():
    space = room({"table": (2.0, 3.0, 2.0, 3.0), "crate": (1.0, 1.4, 2.3, 2.7)})
    on_table = (2.5, 2.5)
    assert line_of_sight(space.obstacles, (2.5, 3.6), on_table) is None, "the table under the point hid it"
    hidden_at = line_of_sight(space.obstacles, (0.5, 2.5), on_table)
    assert hidden_at is not None and 1.0 <= hidden_at[0] <= 1.45, f"the crate did not hide it: {hidden_at}"
    on_floor = (3.3, 2.5)
    assert line_of_sight(space.obstacles, (3.6, 2.5), on_floor) is None
    assert line_of_sight(space.obstacles, (1.7, 2.5), on_floor) is not None, \
        "the table did not hide the floor behind it"


# -- the search ----------------------------------------------------------------------------------------
def test_an_object_in_the_middle_of_a_table_is_looked_at_from_the_tables_edge_beyond_arms_reach():
    table = (2.6, 3.4, 2.4, 3.6)  # 0.8 x 1.2 m, like the lab's kitchen table
    space = room({"table": table})
    target, here = (3.0, 3.0, TABLE_TOP), (0.6, 0.6, 0.0)
    spot = find_viewpoint(space, CAMERA, target, here)

    assert sees(space, (spot.x, spot.y, spot.yaw), target)
    assert walkable(space, here[:2], (spot.x, spot.y))
    assert math.hypot(spot.x - target[0], spot.y - target[1]) > 0.39, "it could have reached it: no test"
    assert not (table[0] < spot.x < table[1] and table[2] < spot.y < table[3])
    assert spot.walk > 0


def test_the_viewpoint_chosen_is_the_nearest_on_foot():
    """A long table: the robot stands at its south end; the point is at its middle, seen from the
    east and the west side alike. It looks from the side it reaches first, not the far one."""
    space = room({"table": (2.6, 3.4, 1.0, 5.0)})
    target = (3.0, 3.0, TABLE_TOP)
    from_west = find_viewpoint(space, CAMERA, target, (1.0, 0.6, 0.0))
    from_east = find_viewpoint(space, CAMERA, target, (5.0, 0.6, math.pi))
    assert from_west.x < 2.6 and from_east.x > 3.4, (from_west, from_east)


def test_the_robot_stays_when_it_sees_the_point_and_only_turns_when_turning_is_enough():
    space = room({"table": (2.6, 3.4, 2.4, 3.6)})
    target = (3.0, 2.55, TABLE_TOP)
    base = (3.0, 2.55 - 0.45 - CAMERA.ahead, math.pi / 2)  # before the table's south edge, facing it
    stay = find_viewpoint(space, CAMERA, target, base)
    assert (stay.x, stay.y, stay.yaw, stay.walk) == (base[0], base[1], base[2], 0.0)
    turn = find_viewpoint(space, CAMERA, target, (base[0], base[1], -math.pi / 2))
    assert (turn.x, turn.y, turn.walk) == (base[0], base[1], 0.0)
    assert turn.yaw == pytest.approx(math.pi / 2, abs=1e-9)


def test_a_wall_between_hides_the_point_and_the_robot_goes_round_through_the_door():
    walls = {"wall": (2.9, 3.1, 0.0, 4.6)}  # a wall across the room, a door north of y = 4.6
    space = room(walls)
    target = (3.8, 1.0, 0.0)  # on the floor just beyond the wall
    spot = find_viewpoint(space, CAMERA, target, (2.0, 1.0, 0.0))
    assert spot.x > 3.1, f"looked through the wall from {spot}"
    assert sees(space, (spot.x, spot.y, spot.yaw), target)
    assert spot.walk > 2 * (4.6 - 1.0), "the walk did not go round through the door"


def test_a_point_in_the_middle_of_a_wide_table_cannot_be_seen_and_the_table_is_named():
    space = room({"conference table": (1.5, 4.5, 1.5, 4.5)})
    with pytest.raises(NoViewpoint) as failed:
        find_viewpoint(space, CAMERA, (3.0, 3.0, TABLE_TOP), (0.6, 0.6, 0.0))
    assert failed.value.blocked_by == ["conference table"]
    assert failed.value.counts["inside"] > 0 and "(3.00, 3.00, 0.79)" in failed.value.reason


def test_a_map_without_names_fails_the_same_and_names_nothing():
    space = room({"conference table": (1.5, 4.5, 1.5, 4.5)}, named=False)
    with pytest.raises(NoViewpoint) as failed:
        find_viewpoint(space, CAMERA, (3.0, 3.0, TABLE_TOP), (0.6, 0.6, 0.0))
    assert failed.value.blocked_by == []


def test_a_point_no_reachable_spot_sees_says_so():
    """A closed cupboard-like room: the spots that see the point are all in a part of the map the
    robot cannot walk to."""
    space = room({"north wall": (0.0, 6.0, 2.9, 3.1)})
    with pytest.raises(NoViewpoint) as failed:
        find_viewpoint(space, CAMERA, (3.0, 4.5, 0.0), (1.0, 1.0, 0.0))
    assert failed.value.counts["unreachable"] > 0 and "no path from here" in failed.value.reason


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(boxes=st.lists(st.tuples(st.floats(0.3, 5.0), st.floats(0.3, 5.0), st.floats(0.3, 1.5), st.floats(0.3, 1.5)),
                      min_size=1, max_size=5),
       target=st.tuples(st.floats(0.2, 5.8), st.floats(0.2, 5.8), st.sampled_from([0.0, 0.45, TABLE_TOP])))
def test_every_viewpoint_found_on_any_layout_sees_the_point_and_can_be_walked_to(boxes, target):
    layout = {f"box {i}": (x, min(x + w, 5.9), y, min(y + h, 5.9)) for i, (x, y, w, h) in enumerate(boxes)}
    space = room(layout)
    here = (0.5, 0.5, 0.0)
    if not space.roomy.cell_is_free(*space.roomy.world_to_cell(*here[:2])):
        return  # the robot itself would stand in a box
    try:
        spot = find_viewpoint(space, CAMERA, target, here)
    except NoViewpoint as e:
        assert set(e.blocked_by) <= set(layout), e.blocked_by
        return
    assert sees(space, (spot.x, spot.y, spot.yaw), target), spot
    assert spot.walk == 0.0 or walkable(space, here[:2], (spot.x, spot.y)), spot


# -- nearest on foot -----------------------------------------------------------------------------------
def test_the_nearest_goal_is_the_one_nearest_on_foot_with_its_extra_cost():
    blocked = np.zeros((20, 20), dtype=bool)
    blocked[0:18, 10] = True  # a wall with a gap at its top
    goals = {(2, 12): [(0.0, "behind the wall")], (2, 1): [(0.0, "far but open")]}
    cost, which = nearest_goal(blocked, (2, 8), goals)
    assert which == "far but open" and cost == pytest.approx(7.0)
    cost, which = nearest_goal(blocked, (2, 8), {**goals, (2, 1): [(40.0, "far but open")]})
    assert which == "behind the wall", "the extra cost was not counted"
    walled_off = np.zeros((3, 3), dtype=bool)
    walled_off[:, 1] = True
    assert nearest_goal(walled_off, (0, 0), {(0, 2): [(0.0, "beyond")]}) is None
