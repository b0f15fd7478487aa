"""The base: the vendor controller's dead band, limits and expiry; the path follower; people."""

from __future__ import annotations

import json
import math
import subprocess
import time
from collections.abc import Callable
from itertools import pairwise
from pathlib import Path
from typing import Any

import pytest

from stuart_bt.sim.world.client import launch_world
from stuart_bt.sim.world.occupancy import scene_grid
from stuart_bt.sim.world.scene import MAPS_DIR, default_robot_path

STANDIN = Path(__file__).parent / "data" / "standin_robot.xml"
ROBOT = None if default_robot_path().is_file() else STANDIN
MARKERS = json.loads((MAPS_DIR / "lab_markers.json").read_text())["markers"]


@pytest.fixture(scope="module")
def world():
    with launch_world(robot=ROBOT, stderr=subprocess.DEVNULL) as w:
        yield w


def wait_for(world, test: Callable[[dict[str, Any]], bool], timeout: float = 20.0) -> dict[str, Any]:
    """Poll the state until ``test`` holds (wall-clock timeout; the world runs ~50x real time)."""
    deadline = time.monotonic() + timeout
    while True:
        state = world.call("state")
        if test(state):
            return state
        assert time.monotonic() < deadline, f"timed out; last state {state}"
        time.sleep(0.005)


def yaw_error(a: float, b: float) -> float:
    return abs(math.atan2(math.sin(a - b), math.cos(a - b)))


def test_dead_band_ignores_slow_commands_and_commands_expire(world):
    world.call("set_base", x=0.0, y=0.0, yaw=0.0)
    reply = world.call("base_velocity", vx=0.25, duration=1.0)
    assert reply["dead_band"] is True
    state = wait_for(world, lambda s: s["t"] >= reply["expires"] + 0.2)
    assert state["base"]["x"] == 0.0 and state["base_status"] == "idle"

    reply = world.call("base_velocity", vx=0.5, duration=1.0)
    moving = wait_for(world, lambda s: s["base_velocity"]["vx"] > 0.0)
    assert moving["base_status"] == "moving"
    state = wait_for(world, lambda s: s["t"] >= reply["expires"] + 1.0)
    # 1 s at 0.5 m/s less the ramp up (0.125 m), plus the ramp down after expiry
    assert 0.4 <= state["base"]["x"] <= 0.55
    assert state["base_velocity"] == {"vx": 0.0, "vy": 0.0, "wz": 0.0}
    assert state["base_status"] == "idle"


def test_speed_and_acceleration_limits(world):
    world.call("set_base", x=0.0, y=0.0, yaw=0.0)
    start = world.call("state")["t"]
    world.call("base_velocity", vx=3.0, wz=0.0, duration=2.0)
    state = wait_for(world, lambda s: s["t"] >= start + 0.3)
    assert state["base_velocity"]["vx"] <= 1.0 * (state["t"] - start) + 0.01  # accel limit
    state = wait_for(world, lambda s: s["t"] >= start + 1.5)
    assert state["base_velocity"]["vx"] == pytest.approx(0.8)  # speed limit
    world.call("base_stop")
    wait_for(world, lambda s: s["base_status"] == "idle")


def test_base_stop_brakes_from_the_next_control_step(world):
    world.call("set_base", x=0.0, y=0.0, yaw=0.0)
    world.call("base_velocity", vx=0.8, duration=5.0)
    wait_for(world, lambda s: s["base_velocity"]["vx"] >= 0.8)
    driver = world.clock(driver=True)  # freeze time to look at single steps
    try:
        time.sleep(0.05)
        dt = world.ready["timestep"]
        before = world.call("state")
        v0, x0 = before["base_velocity"]["vx"], before["base"]["x"]
        world.call("base_stop")
        driver.sleep_until(driver.now() + dt)
        after_one = world.call("state")
        assert after_one["base_velocity"]["vx"] == pytest.approx(v0 - 1.0 * dt, abs=1e-4)
        driver.sleep_until(driver.now() + v0 / 1.0 + dt)
        stopped = world.call("state")
        assert stopped["base_velocity"]["vx"] == 0.0 and stopped["base_status"] == "idle"
        assert stopped["base"]["x"] - x0 <= v0 * v0 / 2.0 + v0 * dt + 0.005
    finally:
        driver.close()


def test_slow_stop_is_immediate(world):
    world.call("set_base", x=0.0, y=0.0, yaw=0.0)
    world.call("base_velocity", wz=0.004, duration=5.0)  # turning below one step's change
    wait_for(world, lambda s: s["base_velocity"]["wz"] > 0.0)
    world.call("base_stop")
    t0 = world.call("state")["t"]
    state = wait_for(world, lambda s: s["t"] >= t0 + world.ready["timestep"])  # one control step
    assert state["base_velocity"]["wz"] == 0.0 and state["base_status"] == "idle"


def _segments_clear(points: list[tuple[float, float]]) -> bool:
    grid = scene_grid()
    for (ax, ay), (bx, by) in pairwise(points):
        n = max(2, int(math.hypot(bx - ax, by - ay) / 0.02))
        if not all(grid.is_free(ax + (bx - ax) * k / n, ay + (by - ay) * k / n) for k in range(n + 1)):
            return False
    return True


def test_path_to_the_kitchen_on_a_straight_line(world):
    entrance, kitchen = MARKERS["entrance"], MARKERS["kitchen"]
    assert _segments_clear([(entrance["x"], entrance["y"]), (kitchen["x"], kitchen["y"])])
    world.call("set_base", x=entrance["x"], y=entrance["y"], yaw=entrance["yaw"])
    world.call("base_path", waypoints=[[kitchen["x"], kitchen["y"]]], final_yaw=kitchen["yaw"], max_speed=0.6)
    speeds = []
    state = wait_for(world, lambda s: speeds.append(math.hypot(s["base_velocity"]["vx"], s["base_velocity"]["vy"]))
                     or s["base_status"] == "arrived")
    base = state["base"]
    assert math.hypot(base["x"] - kitchen["x"], base["y"] - kitchen["y"]) <= 0.10
    assert yaw_error(base["yaw"], kitchen["yaw"]) <= math.radians(5)
    assert state["arrival_error"]["within_tolerance"] is True
    assert not state["collided"]
    assert max(speeds) == pytest.approx(0.6, abs=0.01)


def test_a_short_step_back_is_walked_backwards_without_turning_around(world):
    kitchen = MARKERS["kitchen"]
    world.call("set_base", x=kitchen["x"], y=kitchen["y"], yaw=0.0)
    world.call("base_path", waypoints=[[kitchen["x"] - 0.3, kitchen["y"]]], final_yaw=0.0, max_speed=0.6)
    yaws, speeds = [], []
    state = wait_for(world, lambda s: yaws.append(s["base"]["yaw"]) or speeds.append(s["base_velocity"]["vx"])
                     or s["base_status"] == "arrived")
    base = state["base"]
    assert math.hypot(base["x"] - (kitchen["x"] - 0.3), base["y"] - kitchen["y"]) <= 0.10
    assert max(abs(y) for y in yaws) < math.radians(10)  # it never turned round
    assert min(speeds) == pytest.approx(-0.3, abs=0.01)  # backwards, at the dead band speed
    assert state["arrival_error"]["within_tolerance"] is True


def test_path_through_the_bathroom_doorway(world):
    route = [(6.5, 0.5), (6.65, 1.4), (6.65, 2.5), (7.5, 3.0)]  # station_4 -> doorway -> bathroom
    assert _segments_clear(route)
    bathroom = MARKERS["bathroom"]
    world.call("set_base", x=6.5, y=0.5, yaw=0.0)
    world.call("base_path", waypoints=[list(p) for p in route], final_yaw=bathroom["yaw"])
    state = wait_for(world, lambda s: s["base_status"] == "arrived")
    base = state["base"]
    assert math.hypot(base["x"] - bathroom["x"], base["y"] - bathroom["y"]) <= 0.10
    assert yaw_error(base["yaw"], bathroom["yaw"]) <= math.radians(5)
    assert not state["collided"], state["collision_with"]


def test_collision_flag_when_driven_into_a_table(world):
    world.call("set_base", x=3.5, y=1.5, yaw=0.0)  # the kitchen marker, facing the table
    assert not world.call("state")["collision"]
    world.call("base_velocity", vx=0.5, duration=1.0)
    state = wait_for(world, lambda s: s["collision"])
    assert any(name.startswith("kitchen_table") for name in state["collision_with"])
    state = wait_for(world, lambda s: s["base_status"] == "idle")
    assert state["collided"]


def test_person_ahead_blocks_and_the_base_resumes(world):
    world.call("set_base", x=0.0, y=0.0, yaw=0.0)
    world.call("person", x=2.5, y=0.05)
    world.call("base_path", waypoints=[[0.0, 0.0], [4.0, 0.0]])
    blocked = wait_for(world, lambda s: s["base_status"] == "blocked")
    assert blocked["person"] == {"x": 2.5, "y": 0.05}
    state = wait_for(world, lambda s: s["t"] >= blocked["t"] + 3.0)
    assert state["base_status"] == "blocked" and state["base_velocity"]["vx"] == 0.0
    assert state["base"]["x"] < 2.5 - 0.25 - 0.3  # stopped short of the person
    world.call("person", present=False)
    state = wait_for(world, lambda s: s["base_status"] == "arrived")
    assert state["person"] is None
    assert math.hypot(state["base"]["x"] - 4.0, state["base"]["y"]) <= 0.10


def test_person_beside_the_path_does_not_block(world):
    world.call("set_base", x=0.0, y=0.0, yaw=0.0)
    world.call("person", x=2.0, y=1.2)
    world.call("base_path", waypoints=[[3.0, 0.0]])
    statuses = set()
    wait_for(world, lambda s: statuses.add(s["base_status"]) or s["base_status"] == "arrived")
    assert "blocked" not in statuses
    world.call("person", present=False)


def test_new_command_replaces_the_path(world):
    world.call("set_base", x=0.0, y=0.0, yaw=0.0)
    world.call("base_path", waypoints=[[3.0, 0.0]])
    wait_for(world, lambda s: s["base_velocity"]["vx"] > 0.3)
    world.call("base_stop")
    state = wait_for(world, lambda s: s["base_status"] == "idle")
    assert state["base"]["x"] < 2.5 and state["arrival_error"] is None


def test_turn_in_place_path(world):
    world.call("set_base", x=1.0, y=0.0, yaw=0.0)
    world.call("base_path", waypoints=[[1.0, 0.0]], final_yaw=math.pi / 2)
    state = wait_for(world, lambda s: s["base_status"] == "arrived")
    assert yaw_error(state["base"]["yaw"], math.pi / 2) <= math.radians(5)
    assert math.hypot(state["base"]["x"] - 1.0, state["base"]["y"]) < 1e-6
