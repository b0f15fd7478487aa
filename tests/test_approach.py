"""The ``approach`` leaf: stand with a point (or a remembered object) ahead and to one side, facing
it, on a spot the backend chooses. Dry: on the side facing the robot. Sim: free of furniture on the
lab map, going round the object when the near side is blocked. And the ``view`` leaf: stand where
the head camera sees the point, which needs no arm's reach.

Lab (docs/sim.md): the robot starts at 'entrance' (0, 0) facing +x; the kitchen table's top spans
x 3.91 .. 4.71 and y 0.90 .. 2.10."""

from __future__ import annotations

import math

import pytest

from stuart_bt.perception.projection import head_camera_view

TABLE = (3.91, 4.71, 0.90, 2.10)
CAMERA = head_camera_view()  # what the head camera sees from a base pose (stuart_bt.maps.viewpoints)


def in_body_frame(pose: dict[str, float], x: float, y: float) -> tuple[float, float]:
    """(ahead, left) of the point (x, y) as the robot at ``pose`` sees it (REP-103)."""
    dx, dy, yaw = x - pose["x"], y - pose["y"], pose["yaw"]
    return dx * math.cos(yaw) + dy * math.sin(yaw), -dx * math.sin(yaw) + dy * math.cos(yaw)


def test_dry_approach_stands_on_the_near_side_with_the_point_before_the_right_shoulder(stuart_dry):
    result = stuart_dry(text="root: {approach: {x: 2.0, y: 1.0, standoff: 0.3, lateral: -0.1}}")

    result.assert_success()
    pose = result.report["final_pose"]
    ahead, left = in_body_frame(pose, 2.0, 1.0)
    assert ahead == pytest.approx(0.3, abs=0.02) and left == pytest.approx(-0.1, abs=0.02)
    assert pose["x"] < 2.0, "it walked round to the far side"


def test_approaching_an_object_nobody_found_fails_with_the_closest_known_name(stuart_dry):
    result = stuart_dry(text="""
root:
  sequence:
    - find: bottle
    - approach: {name: go, object: botle}
""")

    assert result.status == "FAILURE"
    reason = result.failure("root/go") or ""
    assert reason.startswith("unknown_object: no remembered position for 'botle'") and "'bottle'" in reason
    assert not [c for c in result.commands("navigate")], "the base was sent somewhere"


def test_sim_approach_goes_round_the_table_when_the_near_side_is_blocked(stuart_sim):
    """A point 10 cm in from the table's south edge, looked at from the entrance: straight on, the
    stand-off is inside the table, so the robot must go round to the south edge."""
    px, py = 4.31, 1.00
    result = stuart_sim(text=f"root: {{approach: {{x: {px}, y: {py}, standoff: 0.3, lateral: 0.0}}}}")

    result.assert_success()
    result.assert_no_collisions()
    pose = result.final_world["base"]
    ahead, left = in_body_frame(pose, px, py)
    assert math.hypot(ahead, left) <= 0.3 + 0.10 + 0.1, "stood further than stand-off plus slack"
    assert ahead > 0.25 and abs(left) < 0.1, "not facing the point"
    x0, x1, y0, y1 = TABLE
    inside = x0 - 0.1 < pose["x"] < x1 + 0.1 and y0 - 0.1 < pose["y"] < y1 + 0.1
    assert not inside, f"the base stands in the table at {pose}"


def test_sim_approach_to_a_point_inside_a_wall_of_furniture_fails_before_moving(stuart_sim):
    # the middle of the kitchen table: no spot 0.29 .. 0.39 m from it leaves the docking clearance
    result = stuart_sim(text="root: {approach: {name: go, x: 4.31, y: 1.5}}")

    assert result.status == "FAILURE"
    assert (result.failure("go") or "").startswith("unreachable: no free spot to stand within 0.39 m of (4.31, 1.50)")
    failed = next(e for e in result.events("leaf") if e["path"] == "go")
    assert failed["detail"]["goal"] == "reach" and failed["detail"]["blocked_by"] == ["kitchen table"], \
        "the furniture in the way was not named"
    start, end = result.initial_world["base"], result.final_world["base"]
    assert math.hypot(end["x"] - start["x"], end["y"] - start["y"]) < 0.01


def sees(pose: dict[str, float], point: tuple[float, float, float]) -> bool:
    return CAMERA.miss((pose["x"], pose["y"], pose["yaw"]), point) is None


def test_dry_view_walks_straight_towards_the_point_until_the_camera_has_it_in_the_middle(stuart_dry):
    point = (3.0, 1.0, 0.8)
    result = stuart_dry(text=f"root: {{view: {{x: {point[0]}, y: {point[1]}, z: {point[2]}}}}}")

    result.assert_success()
    pose = result.report["final_pose"]
    assert sees(pose, point)
    ahead, left = in_body_frame(pose, point[0], point[1])
    assert ahead == pytest.approx(CAMERA.ahead + CAMERA.centred(point[2]), abs=0.02)
    assert left == pytest.approx(CAMERA.left, abs=0.02)


def test_dry_view_does_not_walk_when_the_camera_sees_the_point_from_where_the_robot_stands(stuart_dry):
    """The robot starts at the entrance (0, 0) facing +x: a point on the floor 1.2 m ahead is in view."""
    result = stuart_dry(text="root: {view: {x: 1.2, y: 0.0, z: 0.0}}")

    result.assert_success()
    assert result.report["final_pose"] == {"x": 0.0, "y": 0.0, "yaw": 0.0}
    assert result.leaf_results("view")[0]["result"]["distance"] == 0.0


def test_sim_view_looks_at_the_middle_of_the_table_from_its_edge(stuart_sim):
    """No spot within arm's reach of the table's middle is free (the approach test above), but the
    camera sees it from the table's edge: the robot walks there, round nothing, touching nothing."""
    point = (4.31, 1.5, 0.79)
    result = stuart_sim(text=f"root: {{view: {{x: {point[0]}, y: {point[1]}, z: {point[2]}}}}}")

    result.assert_success()
    result.assert_no_collisions()
    base = result.final_world["base"]
    assert sees(base, point), f"the camera does not see {point} from {base}"
    assert math.hypot(base["x"] - point[0], base["y"] - point[1]) > 0.39
    x0, x1, y0, y1 = TABLE
    assert not (x0 < base["x"] < x1 and y0 < base["y"] < y1), f"the base stands in the table at {base}"


def test_sim_view_of_something_on_top_of_the_tall_shelf_fails_before_moving(stuart_sim):
    """The storage shelf is 1.8 m tall; the head camera, 1.27 m up and looking down, sees nothing on
    top of it from any distance, so the walk fails at once and says why."""
    result = stuart_sim(text="root: {view: {name: look, x: 4.4, y: -3.4, z: 1.85}}")

    assert result.status == "FAILURE"
    failed = next(e for e in result.events("leaf") if e["path"] == "look")
    assert failed["reason"] == "unreachable: the camera sees no point at height 1.85 m from any distance"
    assert failed["detail"]["goal"] == "view" and failed["detail"]["blocked_by"] == []
    result.assert_robot_did_not_move()
