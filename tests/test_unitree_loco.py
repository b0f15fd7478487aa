"""The unitree loco backend against the fake G1 services: SLAM navigation legs, velocity moves
under odometry, pause/resume, mapping, faults, and the READY refusal."""

from __future__ import annotations

import math
from itertools import pairwise

import pytest

from stuart_bt.daemon.supervisor import Supervisor
from unitree_fake import FakeRobot, start_failure

pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")

START = {"x": 1.0, "y": 2.0, "yaw": 0.0}


@pytest.fixture
def loco(unitree_daemon):
    return lambda **options: unitree_daemon("loco", start_pose=START, map="/home/unitree/lab.pcd", **options)


def run(sup: Supervisor, cmd: str, timeout: float = 20.0, **args):
    return sup.wait(sup.client("loco").request(cmd, args), timeout=timeout)


def test_start_up_relocalises_on_the_map_at_the_start_pose(robot, loco):
    before = len(robot.rpc("slam_operate", 1804))
    loco()
    call = robot.rpc("slam_operate", 1804)[before]
    assert call["parameter"]["data"]["address"] == "/home/unitree/lab.pcd"
    assert (call["parameter"]["data"]["x"], call["parameter"]["data"]["y"]) == (1.0, 2.0)
    assert call["parameter"]["data"]["q_w"] == 1.0


def test_a_long_map_goal_is_walked_in_legs_of_at_most_ten_metres(robot, loco):
    sup = loco()
    before = len(robot.rpc("slam_operate", 1102))
    walk = run(sup, "navigate", pose={"x": 23.0, "y": 2.0, "yaw": 1.5708}, marker="far")
    assert walk.ok, walk.reason
    goals = [r["parameter"]["data"] for r in robot.rpc("slam_operate", 1102)[before:]]
    assert [g["mode"] for g in goals] == [1, 1, 1]
    xs = [g["targetPose"]["x"] for g in goals]
    assert xs == pytest.approx([1.0 + 22.0 / 3, 1.0 + 44.0 / 3, 23.0], abs=1e-3)
    steps = [b - a for a, b in pairwise([1.0, *xs])]
    assert max(steps) <= 10.0
    last = goals[-1]["targetPose"]
    assert 2 * math.atan2(last["q_z"], last["q_w"]) == pytest.approx(1.5708, abs=1e-3)
    assert walk.result["marker"] == "far"
    assert walk.result["pose"]["x"] == pytest.approx(23.0, abs=0.05)


def test_a_relative_move_streams_short_velocity_commands_between_the_dead_band_and_the_limit(robot, loco):
    sup = loco(max_speed=0.5, min_speed=0.3)
    before = len(robot.rpc("sport", 7105))
    start = run(sup, "state").result["pose"]
    move = run(sup, "navigate", relative={"dx": 0.6})
    assert move.ok, move.reason
    commands = [r["parameter"] for r in robot.rpc("sport", 7105)[before:]]
    moving = [c for c in commands if any(c["velocity"])]
    assert len(moving) >= 5
    assert all(0.3 - 1e-6 <= math.hypot(*c["velocity"][:2]) <= 0.5 + 1e-6 for c in moving)
    assert all(c["duration"] <= 0.3 for c in moving)
    assert commands[-1]["velocity"] == [0.0, 0.0, 0.0]  # a stop ends the move
    end = move.result["pose"]
    assert math.hypot(end["x"] - start["x"] - 0.6, end["y"] - start["y"]) <= 0.1


def test_a_turn_commands_yaw_rate_only_and_ends_at_the_angle(robot, loco):
    sup = loco()
    start = run(sup, "state").result["pose"]["yaw"]
    before = len(robot.rpc("sport", 7105))
    turn = run(sup, "turn", angle=1.0)
    assert turn.ok, turn.reason
    commands = [r["parameter"]["velocity"] for r in robot.rpc("sport", 7105)[before:]]
    assert all(vx == 0.0 and vy == 0.0 for vx, vy, _ in commands)
    assert max(w for _, _, w in commands) <= 0.6 + 1e-6
    turned = math.atan2(math.sin(turn.result["pose"]["yaw"] - start), math.cos(turn.result["pose"]["yaw"] - start))
    assert turned == pytest.approx(1.0, abs=0.0873)


def test_locomotion_unavailable_fails_the_move_with_the_vendor_code(robot, loco):
    sup = loco()
    robot.fault("sport", 7105, 7301)
    move = run(sup, "navigate", relative={"dx": 0.5})
    assert not move.ok
    assert move.error_code == "backend_error"
    assert move.vendor_code == 7301
    assert "locomotion is unavailable" in move.reason


def test_the_navigation_service_giving_up_fails_the_walk_and_stops_the_robot(robot, loco):
    sup = loco()
    robot.order(arrive=False)
    try:
        before = len(robot.rpc("sport", 7105))
        walk = run(sup, "navigate", pose={"x": 2.0, "y": 1.0, "yaw": None})
    finally:
        robot.order(arrive=True)
    assert walk.error_code == "unreachable"
    assert "is_arrived false" in walk.reason
    assert robot.rpc("sport", 7105)[before:][-1]["parameter"]["velocity"] == [0.0, 0.0, 0.0]


def test_pause_and_resume_reach_the_navigation_service(robot, loco):
    sup = loco()
    client = sup.client("loco")
    here = run(sup, "state").result["pose"]
    mark = len(robot.records)
    walk = client.request("navigate", {"pose": {"x": here["x"] + 8.0, "y": here["y"], "yaw": None}})
    robot.wait_for(lambda r: r.get("api") == 1102, what="the navigation goal", since=mark)
    assert run(sup, "pause").result == {"paused": True}
    assert run(sup, "resume").result == {"paused": False}
    assert sup.wait(walk, timeout=20).ok
    apis = [r["api"] for r in robot.rpc("slam_operate") if r["api"] in (1102, 1201, 1202)]
    assert apis[-3:] == [1102, 1201, 1202]


def test_mapping_commands_send_the_slam_service_its_ids_and_paths(robot, loco):
    sup = loco()
    assert run(sup, "map_start").ok
    assert run(sup, "map_save", path="/home/unitree/new.pcd").result == {"saved": "/home/unitree/new.pcd"}
    bad = run(sup, "map_save", path="new.map")
    assert bad.error_code == "bad_request" and "absolute .pcd path" in bad.reason
    assert robot.rpc("slam_operate", 1801)[-1]["parameter"] == {"data": {"slam_type": "indoor"}}
    assert robot.rpc("slam_operate", 1802)[-1]["parameter"] == {"data": {"address": "/home/unitree/new.pcd"}}


def test_a_map_that_will_not_load_refuses_ready_with_code_507(robot, tmp_path):
    message = start_failure("loco", robot.options(map="/home/unitree/missing.pcd"), tmp_path)
    assert "vendor code 507 (the map could not be loaded)" in message
    assert "Traceback" not in message


def test_a_silent_service_refuses_ready_naming_service_interface_and_domain(tmp_path):
    with FakeRobot(silent="sport") as silent:
        message = start_failure("loco", silent.options(probe_timeout=0.5), tmp_path)
    assert "'sport' service does not answer on interface lo, DDS domain" in message
    assert str(silent.domain) in message


def test_a_navigation_service_that_does_not_answer_fails_with_the_timeout_code(robot, loco):
    sup = loco()
    robot.fault("slam_operate", 1102, None)  # no answer at all
    walk = run(sup, "navigate", pose={"x": 2.0, "y": 2.0, "yaw": None})
    assert (walk.error_code, walk.vendor_code) == ("backend_error", 3104)
    assert "did not answer in time" in walk.reason


def test_older_firmware_uses_the_loco_service_and_start_fsm_200(robot, loco):
    sport_before = len(robot.rpc("sport", 7105))
    sup = loco(firmware="loco", stand_up=True)
    assert robot.rpc("loco", 7101)[-1]["parameter"] == {"data": 200}
    assert run(sup, "turn", angle=0.5).ok
    assert robot.rpc("loco", 7105) and len(robot.rpc("sport", 7105)) == sport_before
