"""The unitree gesture backend against the fake arm service and rt/arm_sdk: action ids, the
hold / release-99 rule, vendor error codes, and recorded gestures streamed with the blend ramp."""

from __future__ import annotations

import pytest

from stuart_bt.daemon.supervisor import Supervisor
from unitree_fake import FakeRobot

pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")

RAMP = 0.2


@pytest.fixture
def gesture(unitree_daemon):
    return unitree_daemon("gesture", 4.0, ramp=RAMP)  # library durations pass 4x faster; the stream keeps 50 Hz


def play(sup: Supervisor, **args):
    return sup.wait(sup.client("gesture").request("play", args), timeout=20.0)


def actions_since(robot: FakeRobot, before: int) -> list[tuple[int, int]]:
    return [(r["parameter"]["data"], r["code"]) for r in robot.rpc("arm", 7106)[before:]]


def test_a_sequence_executes_the_vendor_action_ids_in_order(robot, gesture):
    before = len(robot.rpc("arm", 7106))
    result = play(gesture, sequence=["face wave", "clap"])
    assert result.ok, result.reason
    assert result.accepted_data["ids"] == [25, 17]
    assert actions_since(robot, before) == [(25, 0), (17, 0)]
    assert result.result["played"] == ["face wave", "clap"]


def test_a_held_pose_is_released_with_99_before_the_next_gesture(robot, gesture):
    before = len(robot.rpc("arm", 7106))
    assert play(gesture, name="hands up").ok
    assert gesture.wait(gesture.client("gesture").request("state"), timeout=5).result["holding"] == "hands up"
    assert play(gesture, name="high wave").ok
    assert actions_since(robot, before) == [(15, 0), (99, 0), (26, 0)]


def test_stopping_releases_a_held_action(robot, gesture):
    assert play(gesture, name="heart").ok
    before = len(robot.rpc("arm", 7106))
    assert gesture.wait(gesture.client("gesture").request("stop"), timeout=5).ok
    assert actions_since(robot, before) == [(99, 0)]


def test_a_busy_arm_fails_with_7400_and_a_readable_reason(robot, gesture):
    robot.fault("arm", 7106, 7400)
    result = play(gesture, name="clap")
    assert result.error_code == "backend_error"
    assert result.vendor_code == 7400
    assert "the arm is busy" in result.reason


def test_a_pose_held_elsewhere_fails_with_7401_and_says_to_release(robot, gesture):
    robot.fault("arm", 7106, 7401)  # held by someone else (the remote, the app): the daemon did not know
    result = play(gesture, name="clap")
    assert (result.error_code, result.vendor_code) == ("backend_error", 7401)
    assert "release it (release arm, action 99) first" in result.reason


def test_an_action_the_service_does_not_know_is_unknown_gesture_7402(robot, gesture):
    robot.fault("arm", 7106, 7402)
    result = play(gesture, name="x-ray")
    assert (result.error_code, result.vendor_code) == ("unknown_gesture", 7402)


def test_a_recorded_gesture_streams_50_hz_targets_with_the_blend_ramp_and_the_crc(robot, gesture):
    before, mark = len(robot.topic("rt/arm_sdk")), len(robot.records)
    frames = [{"t": 0.0, "joints": {"right_shoulder_pitch_joint": 0.0}},
              {"t": 1.0, "joints": {"right_shoulder_pitch_joint": -1.0}}]
    result = play(gesture, keyframes=frames)
    assert result.ok, result.reason
    robot.wait_for(lambda r: r.get("topic") == "rt/arm_sdk" and r["weight"] == 0.0, what="the ramp-out's last sample",
                   since=mark)
    samples = robot.topic("rt/arm_sdk")[before:]
    weights = [s["weight"] for s in samples]
    assert all(s["crc_ok"] for s in samples)
    # ramp in, one second of keyframes, ramp out: (0.2 + 1.0 + 0.2) s at 50 Hz
    assert 70 - 4 <= len(samples) <= 70 + 4
    peak = weights.index(1.0)
    # rising from near 0 (a loaded machine may send the first sample a period late: 0.1 instead of 0)
    assert weights[:peak] == sorted(weights[:peak]) and weights[0] < 0.5
    assert weights[peak:] == sorted(weights[peak:], reverse=True) and weights[-1] == 0.0
    shoulder = [s["q"]["22"] for s in samples]  # right shoulder pitch is motor 22
    assert shoulder[0] == 0.0 and shoulder[-1] == pytest.approx(-1.0)
    # every arm motor is commanded (the unnamed ones at rest): none is left limp at kp = 0
    assert all(s["kp"][str(motor)] > 0 for s in samples for motor in range(15, 29))


def test_a_recorded_gesture_beyond_the_joint_limits_is_refused_before_anything_moves(robot, gesture):
    before = len(robot.topic("rt/arm_sdk"))
    result = play(gesture, keyframes=[{"t": 0.5, "joints": {"left_elbow_joint": 3.0}}])
    assert result.error_code == "bad_request"
    assert "left_elbow_joint" in result.reason
    assert len(robot.topic("rt/arm_sdk")) == before
