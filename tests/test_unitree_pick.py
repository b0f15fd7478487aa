"""The unitree pick backend against the fake robot's rt/arm_sdk and Dex3 topics: the confirmation
gate, IK-planned targets within the limits, the hand closing, the release blending back out."""

from __future__ import annotations

import pytest

from stuart_bt.daemon.supervisor import Supervisor
from stuart_bt.sim.robot import description as desc

pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")
pytest.importorskip("pinocchio", reason="the pick planner needs the 'ik' extra")

OBJECTS = {"bottle": {"x": 0.3, "y": -0.2, "z": 0.95}, "far_cup": {"x": 2.0, "y": 0.0, "z": 0.9}}
HERE = {"x": 0.0, "y": 0.0, "yaw": 0.0}
RIGHT_ARM_MOTORS = range(22, 29)


@pytest.fixture
def pick(unitree_daemon):
    return unitree_daemon("pick", objects=OBJECTS, ramp=0.2)


def request(sup: Supervisor, cmd: str, **args):
    return sup.client("pick").request(cmd, args)


def test_a_pick_waits_for_confirmation_then_streams_planned_targets_and_closes_the_hand(robot, pick):
    before_arm, before_hand = len(robot.topic("rt/arm_sdk")), len(robot.topic("rt/dex3/right/cmd"))
    grasp = request(pick, "pick", object="bottle", robot_pose=HERE)
    pick.wait(request(pick, "state"), timeout=5)
    assert grasp.accepted_data["awaiting_confirm"] is True
    assert grasp.accepted_data["planned"]["arm"] == "right"
    assert len(robot.topic("rt/arm_sdk")) == before_arm  # nothing moves before the confirmation
    assert pick.wait(request(pick, "confirm"), timeout=5).ok
    assert pick.wait(grasp, timeout=20).ok, grasp.reason
    assert grasp.result["object"] == "bottle" and grasp.result["arm"] == "right"
    samples = robot.topic("rt/arm_sdk")[before_arm:]
    assert all(s["crc_ok"] for s in samples)
    weights = [s["weight"] for s in samples]
    full = weights.index(1.0)
    assert full > 0 and weights[:full] == sorted(weights[:full]) and weights[0] < 0.5  # ramped in, not jumped
    assert samples[-1]["weight"] == 1.0  # holding
    limits = desc.arm_limits("right")
    for motor, joint in zip(RIGHT_ARM_MOTORS, desc.arm_joints("right"), strict=True):
        low, high = limits[joint]
        assert all(low - 1e-4 <= s["q"][str(motor)] <= high + 1e-4 for s in samples), joint
    planned = grasp.accepted_data["planned"]["joints"]
    lifted = samples[-1]["q"]
    pairs = zip(RIGHT_ARM_MOTORS, desc.arm_joints("right"), strict=True)
    assert any(abs(lifted[str(m)] - desc.NEUTRAL[j]) > 0.1 for m, j in pairs)
    assert set(planned) == set(desc.arm_joints("right"))
    hands = robot.topic("rt/dex3/right/cmd")[before_hand:]
    grip = [max(abs(q) for q in h["q"]) for h in hands]
    assert 0.0 in grip  # open while approaching ...
    assert grip[-1] > 0.3 and grip.index(grip[-1]) > grip.index(0.0)  # ... then closed

    before_arm, mark = len(robot.topic("rt/arm_sdk")), len(robot.records)
    put = request(pick, "release", robot_pose=HERE)
    assert pick.wait(put, timeout=20).ok, put.reason
    robot.wait_for(lambda r: r.get("topic") == "rt/arm_sdk" and r["weight"] == 0.0, what="the ramp-out",
                   since=mark)
    samples = robot.topic("rt/arm_sdk")[before_arm:]
    assert samples[0]["weight"] == 1.0 and samples[-1]["weight"] == 0.0
    assert put.result["position"]["z"] == pytest.approx(0.95, abs=0.01)


def test_an_object_out_of_reach_is_refused_before_anything_moves(robot, pick):
    before = len(robot.topic("rt/arm_sdk"))
    result = pick.wait(request(pick, "pick", object="far_cup", robot_pose=HERE), timeout=10)
    assert result.error_code == "unreachable"
    assert "beyond the left arm's reach" in result.reason or "beyond the right arm's reach" in result.reason
    assert len(robot.topic("rt/arm_sdk")) == before


def test_stopping_a_pick_blends_the_arm_back_to_the_controller(robot, pick):
    mark = len(robot.records)
    grasp = request(pick, "pick", object="bottle", robot_pose=HERE)
    pick.wait(request(pick, "confirm"), timeout=5)
    robot.wait_for(lambda r: r.get("topic") == "rt/arm_sdk" and r["weight"] > 0.5, what="the arm blended in",
                   since=mark)
    assert pick.wait(request(pick, "stop"), timeout=5).ok
    assert grasp.error_code == "stopped"
    last = robot.wait_for(lambda r: r.get("topic") == "rt/arm_sdk" and r["weight"] == 0.0, what="the ramp-out",
                          since=mark)
    assert last["crc_ok"]
