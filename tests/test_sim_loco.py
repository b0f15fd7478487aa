"""Walking on the simulated lab: planned paths through the doorway, body-relative moves and
turns (REP-103), unreachable goals, a person in the way, and the operator's stop.

Lab map (docs/sim.md): the robot starts at 'entrance' (0, 0, facing +x); the bathroom's 1.2 m
doorway spans x 6.05 .. 7.25 in its south wall at y 1.9; 'kitchen' is (3.5, 1.5).
"""

from __future__ import annotations

import math

import pytest

from stuart_bt.testing import LiveRun, when

DOORWAY_X = (6.05, 7.25)
BATHROOM_WALL_Y = 1.9
KITCHEN = {"x": 3.5, "y": 1.5}
TICK = 0.05  # s, at the default 20 Hz
ACCEL = 1.0  # m/s^2: the walking controller's braking limit (docs/sim.md)
MAX_SPEED = 0.6  # m/s: the loco daemon's path speed


def distance(a: dict, b: dict) -> float:
    return math.hypot(a["x"] - b["x"], a["y"] - b["y"])


def test_navigate_to_the_bathroom_goes_through_the_doorway(stuart_sim):
    result = stuart_sim(text="root: {navigate: {name: walk, marker: bathroom}}")

    result.assert_success()
    result.assert_visited("bathroom", exactly=True)
    result.assert_arrivals_within(0.10, math.radians(5))
    result.assert_final_pose(7.5, 3.0, math.pi / 2)
    result.assert_no_collisions()
    crossing = [s["base"] for s in result.timeline if abs(s["base"]["y"] - BATHROOM_WALL_Y) < 0.05]
    assert crossing, "the robot never crossed the bathroom's south wall line"
    assert all(DOORWAY_X[0] + 0.2 < b["x"] < DOORWAY_X[1] - 0.2 for b in crossing), crossing


def test_body_relative_moves_and_turns_follow_rep103(stuart_sim):
    result = stuart_sim(text="""
root:
  sequence:
    - navigate: {name: forward, dx: 1.0}      # x is forward: (1, 0), still facing +x
    - turn: {name: left, degrees: 90}          # counter-clockwise: now facing +y
    - navigate: {name: ahead, dx: 0.5}         # forward is +y now: (1, 0.5)
    - navigate: {name: sideways, dy: 0.5}      # y is left, i.e. -x when facing +y: (0.5, 0.5)
    - navigate: {name: right, dyaw: -1.5708}   # clockwise back to facing +x
""")

    result.assert_success()
    result.assert_arrivals_within(0.10, math.radians(5))
    expected = {"forward": (1.0, 0.0, 0.0), "left": (1.0, 0.0, math.pi / 2), "ahead": (1.0, 0.5, math.pi / 2),
                "sideways": (0.5, 0.5, math.pi / 2), "right": (0.5, 0.5, 0.0)}
    arrived = {a["path"].rsplit("/", 1)[-1]: a["pose"] for a in result.arrivals()}
    assert list(arrived) == list(expected)
    for step, (x, y, yaw) in expected.items():
        pose = arrived[step]
        assert distance(pose, {"x": x, "y": y}) < 0.05, f"{step}: at {pose}, expected ({x}, {y})"
        assert abs(math.remainder(pose["yaw"] - yaw, math.tau)) < math.radians(3), f"{step}: yaw {pose['yaw']:.3f}"


@pytest.mark.parametrize("goal, why", [
    ("{x: 4.3, y: 1.5}", "inside an obstacle"),  # the kitchen table
    ("{x: 20.0, y: 0.0}", "off the map"),
    ("{dx: 30.0}", "would hit an obstacle"),  # straight through the east wall
], ids=["inside_furniture", "off_the_map", "through_a_wall"])
def test_unreachable_goal_fails_before_the_robot_moves(stuart_sim, goal: str, why: str):
    result = stuart_sim(text=f"root: {{navigate: {{name: walk, {goal[1:-1]}}}}}")

    assert result.status == "FAILURE"
    assert why in result.assert_failed("walk", "unreachable")
    result.assert_robot_did_not_move()


def person_ahead_of_the_robot(run: LiveRun, metres: float = 1.0) -> None:
    base = run.world.robot_pose()
    run.world.person_at(base["x"] + metres * math.cos(base["yaw"]), base["y"] + metres * math.sin(base["yaw"]))


def is_blocked(run: LiveRun) -> bool:
    return run.world.latest["base_status"] == "blocked"


def test_person_stepping_into_the_path_stops_the_robot_until_they_leave(stuart_sim):
    steps_in = when(lambda run: run.world.robot_pose()["x"] >= 1.0, person_ahead_of_the_robot)
    leaves = when(is_blocked, lambda run: run.world.person_leaves(), held_for=3.0)

    result = stuart_sim(text="root: {navigate: {name: walk, marker: kitchen}}", on_tick=[steps_in, leaves])

    result.assert_success()
    result.assert_visited("kitchen")
    result.assert_arrivals_within(0.10, math.radians(5))
    assert steps_in.fired and leaves.fired
    blocked = [s for s in result.samples(since=steps_in.fired_at, until=leaves.fired_at)
               if s["base_status"] == "blocked"]
    assert blocked and blocked[0]["t"] - steps_in.fired_at <= 2 * TICK, "the robot did not stop for the person"
    braked = [s for s in blocked if s["t"] >= blocked[0]["t"] + 1.0]  # well after braking from full speed
    assert braked, "blocked for less than a second"
    assert max(distance(s["base"], braked[0]["base"]) for s in braked) < 0.005, "the pose kept advancing while blocked"
    stood_at = braked[-1]["base"]
    assert distance(stood_at, KITCHEN) > 1.0  # stopped on the way, not at the goal
    resumed = [s for s in result.samples(since=leaves.fired_at) if s["base_status"] == "moving"]
    assert resumed and distance(resumed[-1]["base"], stood_at) > 0.5, "the robot did not walk on after the person left"


def test_person_who_stays_fails_the_walk_as_blocked_and_the_robot_stands(stuart_sim):
    steps_in = when(lambda run: run.world.robot_pose()["x"] >= 1.0, person_ahead_of_the_robot)

    result = stuart_sim(text="root: {navigate: {name: walk, marker: kitchen}}", on_tick=steps_in,
                        daemon_options={"loco": {"blocked_timeout": 2.0}})

    assert result.status == "FAILURE"
    reason = result.assert_failed("walk", "blocked")
    assert "stayed blocked for 2 s" in reason
    first_blocked = next(s["t"] for s in result.timeline if s["base_status"] == "blocked")
    failed_at = result.report["failures"][0]["t"]
    # after the 2 s option, well before the default 20 s (the daemon's wake-ups can be seconds late in sim time)
    assert 2.0 - 1e-6 <= failed_at - first_blocked < 10.0  # clock times are sums of 0.05 s ticks: 1.9999999...
    world = result.final_world
    assert world["base_velocity"] == {"vx": 0.0, "vy": 0.0, "wz": 0.0} and world["base_status"] == "idle"
    assert distance(world["base"], world["person"]) > 0.5  # stood off, short of the person


def test_stop_request_halts_the_robot_within_one_tick(stuart_sim):
    at_speed: dict = {}

    def press_stop(run: LiveRun) -> None:
        at_speed.update(run.world.latest)
        run.stop("operator pressed stop")

    stop = when(lambda run: run.world.latest["base_velocity"]["vx"] >= 0.5, press_stop)
    result = stuart_sim(text="root: {navigate: {name: walk, marker: kitchen}}", on_tick=stop, settle=1.5)

    assert result.status == "STOPPED" and result.report["reason"] == "operator pressed stop"
    assert {c["family"] for c in result.commands("stop")} == {"loco"}
    rest = result.final_world
    assert rest["base_velocity"] == {"vx": 0.0, "vy": 0.0, "wz": 0.0}
    # Braking starts within one tick: one tick at full speed, then braking at the limit.
    one_tick_then_brake = MAX_SPEED * TICK + MAX_SPEED**2 / (2 * ACCEL)
    travelled = distance(rest["base"], at_speed["base"])
    assert travelled <= one_tick_then_brake + 0.01, (
        f"coasted {travelled:.3f} m after stop (limit {one_tick_then_brake:.3f})")
    assert distance(rest["base"], KITCHEN) > 2.0  # nowhere near the goal
