"""The ``approach`` leaf: stand with a point (or a remembered object) ahead and to one side, facing
it, on a spot the backend chooses. Dry: on the side facing the robot. Sim: free of furniture on the
lab map, going round the object when the near side is blocked.

Lab (docs/sim.md): the robot starts at 'entrance' (0, 0) facing +x; the kitchen table's top spans
x 3.91 .. 4.71 and y 0.90 .. 2.10."""

from __future__ import annotations

import math

import pytest

TABLE = (3.91, 4.71, 0.90, 2.10)


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
    start, end = result.initial_world["base"], result.final_world["base"]
    assert math.hypot(end["x"] - start["x"], end["y"] - start["y"]) < 0.01
