"""Arms and hands: trajectories in sim time, joint limits, grasping, carrying and letting go."""

from __future__ import annotations

import subprocess
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from stuart_bt.sim.world.client import WorldError, launch_world
from stuart_bt.sim.world.scene import default_robot_path

STANDIN = Path(__file__).parent / "data" / "standin_robot.xml"
ROBOT = None if default_robot_path().is_file() else STANDIN


@pytest.fixture(scope="module")
def world():
    with launch_world(robot=ROBOT, stderr=subprocess.DEVNULL) as w:
        yield w


def wait_for(world, test: Callable[[dict[str, Any]], bool], timeout: float = 20.0) -> dict[str, Any]:
    deadline = time.monotonic() + timeout
    while True:
        state = world.call("state")
        if test(state):
            return state
        assert time.monotonic() < deadline, f"timed out; last state {state}"
        time.sleep(0.005)


def test_trajectory_reaches_its_joints_in_sim_time(world):
    target = {"right_shoulder_pitch_joint": -0.4, "right_elbow_joint": 0.5, "right_wrist_roll_joint": 0.2}
    reply = world.call("arm_trajectory", id="reach",
                       points=[{"t": 0.5, "joints": {"right_shoulder_pitch_joint": -0.2}},
                               {"t": 1.0, "joints": target}])
    assert reply["id"] == "reach" and set(reply["joints"]) == set(target)
    busy = world.call("state")
    assert busy["arm_busy"] == {"left": False, "right": True} and "reach" in busy["trajectories"]
    state = wait_for(world, lambda s: not s["arm_busy"]["right"])
    assert state["t"] >= reply["ends_at"]
    for name, value in target.items():
        assert state["joints"][name] == pytest.approx(value, abs=1e-4)


def test_limits_are_checked_before_anything_moves(world):
    before = world.call("state")["joints"]["left_elbow_joint"]
    with pytest.raises(WorldError) as e:
        world.call("arm_trajectory", points=[{"t": 0.5, "joints": {"left_elbow_joint": 0.3}},
                                             {"t": 1.0, "joints": {"left_elbow_joint": 3.0}}])
    assert e.value.code == "out_of_range"
    with pytest.raises(WorldError) as e:
        world.call("arm_trajectory", points=[{"t": 0.5, "joints": {"left_elbo_joint": 0.3}}])
    assert e.value.code == "not_found"
    with pytest.raises(WorldError) as e:
        world.call("arm_trajectory", points=[{"t": 0.5, "joints": {}}, {"t": 0.2, "joints": {}}])
    assert e.value.code == "bad_request"
    state = world.call("state")
    assert state["joints"]["left_elbow_joint"] == before and not state["arm_busy"]["left"]


def test_new_trajectory_replaces_and_stop_holds(world):
    world.call("arm_trajectory", id="slow", points=[{"t": 5.0, "joints": {"left_shoulder_roll_joint": 1.0}}])
    wait_for(world, lambda s: s["joints"]["left_shoulder_roll_joint"] > 0.05)
    world.call("arm_trajectory", id="back", points=[{"t": 0.3, "joints": {"left_shoulder_roll_joint": 0.0}}])
    state = wait_for(world, lambda s: not s["arm_busy"]["left"])
    assert state["joints"]["left_shoulder_roll_joint"] == pytest.approx(0.0, abs=1e-6)
    world.call("arm_trajectory", points=[{"t": 5.0, "joints": {"left_shoulder_roll_joint": 1.0}}])
    wait_for(world, lambda s: s["joints"]["left_shoulder_roll_joint"] > 0.05)
    world.call("arm_stop")
    held = world.call("state")
    assert not held["arm_busy"]["left"]
    later = wait_for(world, lambda s: s["t"] > held["t"] + 0.5)
    assert later["joints"]["left_shoulder_roll_joint"] == held["joints"]["left_shoulder_roll_joint"]


def test_grasp_carry_and_release(world):
    world.call("set_base", x=3.5, y=1.5, yaw=0.0)  # the kitchen marker
    world.call("arm_trajectory", points=[{"t": 0.2, "joints": {"right_shoulder_pitch_joint": 0.0,
                                                              "right_elbow_joint": 0.0}}])
    wait_for(world, lambda s: not s["arm_busy"]["right"])
    driver = world.clock(driver=True)  # freeze time: the bottle must not fall before the hand closes
    try:
        time.sleep(0.05)
        point = world.call("state")["hand_points"]["right"]
        world.call("set_object", label="bottle", x=point[0], y=point[1], z=point[2])
        reply = world.call("hand", side="right", closed=True)
        assert reply["held"] == "bottle" and reply["state"] == "closing"
        driver.sleep_until(driver.now() + 0.6)
        state = world.call("state")
        assert state["held"] == {"left": None, "right": "bottle"} and state["hands"]["right"] == "closed"
        z0 = state["objects"]["bottle"]["z"]
        hand_z0 = state["hand_points"]["right"][2]
        world.call("arm_trajectory", points=[{"t": 1.0, "joints": {"right_shoulder_pitch_joint": -0.6}}])
        driver.sleep_until(driver.now() + 1.2)
        lifted = world.call("state")
        rise = lifted["objects"]["bottle"]["z"] - z0
        assert rise >= 0.05
        assert rise == pytest.approx(lifted["hand_points"]["right"][2] - hand_z0, abs=0.01)
        world.call("hand", side="right", closed=False)
        driver.sleep_until(driver.now() + 1.0)
        dropped = world.call("state")
        assert dropped["held"]["right"] is None and dropped["hands"]["right"] == "open"
        assert dropped["objects"]["bottle"]["z"] < lifted["objects"]["bottle"]["z"] - 0.05  # it fell
    finally:
        driver.close()
    world.call("set_object", label="bottle", x=4.01, y=1.38, z=0.855)


def test_closing_far_from_objects_holds_nothing(world):
    world.call("set_base", x=0.0, y=0.0, yaw=0.0)
    reply = world.call("hand", side="left", closed=True)
    assert reply["held"] is None
    state = wait_for(world, lambda s: s["hands"]["left"] == "closed")
    assert state["held"]["left"] is None
    assert any(abs(v) > 0.5 for k, v in state["joints"].items() if k.startswith("left_hand_"))
    world.call("hand", side="left", closed=False)
    state = wait_for(world, lambda s: s["hands"]["left"] == "open")
    assert all(abs(v) < 1e-6 for k, v in state["joints"].items() if k.startswith("left_hand_"))
