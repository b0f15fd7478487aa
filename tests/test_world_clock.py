"""Sim time through the shared clock file: lockstep with a driver, free-running, the speed cap."""

from __future__ import annotations

import math
import subprocess
import time
from pathlib import Path

import pytest

from stuart_bt.sim.world.client import launch_world
from stuart_bt.sim.world.clock import ClockFile, SimClock
from stuart_bt.sim.world.scene import default_robot_path

STANDIN = Path(__file__).parent / "data" / "standin_robot.xml"
ROBOT = None if default_robot_path().is_file() else STANDIN


def test_clock_file_round_trip(tmp_path):
    path = tmp_path / "c.clock"
    world_side = ClockFile(path, 0.004)
    reader = SimClock(path)
    driver = SimClock(path, driver=True)
    try:
        assert reader.spec() == f"sim:{path}"
        world_side.publish(1.25)
        assert reader.now() == 1.25 == driver.now()
        assert driver.factor == math.inf  # the executor must call sleep_until, never wait on the wall clock
        world_side.set_rate(30.0)
        assert reader.factor == 30.0
        assert world_side.driven()
        driver.close()
        assert not world_side.driven()
    finally:
        reader.close()
        world_side.close()
    assert not path.exists()


def test_a_world_is_stalled_only_when_its_time_stands_still_while_it_should_move(tmp_path):
    from stuart_bt.sim.world.clock import STALL_S

    path = tmp_path / "c.clock"
    world_side = ClockFile(path, 0.004)  # this process plays the world: alive while the test runs
    driver = SimClock(path, driver=True)
    try:
        world_side.publish(1.0)
        driver.sleep_until(0.5)  # already there: the permit stays at 0, the world waits for the driver
        assert not driver.world_stalled()
        time.sleep(STALL_S * 1.5)
        assert not driver.world_stalled(), "a world waiting for its driver's permit is not stalled"

        driver.sleep_until(2.0, max_wall=0.01)  # the driver asks for more: the world should move now
        assert not driver.world_stalled()  # not yet: a quarter of a second first
        time.sleep(STALL_S * 1.5)
        assert driver.world_stalled()
        world_side.publish(1.1)  # it moved
        assert not driver.world_stalled()
        world_side.close(remove=False)  # the world stopped: time goes on at wall rate, nothing to wait on
        time.sleep(STALL_S * 1.5)
        assert not driver.world_stalled()
    finally:
        driver.close()
        path.unlink(missing_ok=True)


@pytest.fixture(scope="module")
def world():
    with launch_world(robot=ROBOT, stderr=subprocess.DEVNULL) as w:
        yield w


def test_lockstep_world_waits_for_the_permit(world):
    driver = world.clock(driver=True)
    try:
        time.sleep(0.05)  # the world reaches the permit it had and stops there
        held = driver.now()
        time.sleep(0.2)
        assert driver.now() == held, "sim time moved without a permit"
        target = held + 0.5
        driver.sleep_until(target)
        reached = driver.now()
        assert target <= reached <= target + world.ready["timestep"] + 1e-9
        time.sleep(0.1)
        assert driver.now() == reached  # and stays there until the next permit
        state = world.call("state")  # requests are served while the world waits
        assert abs(state["t"] - reached) < 1e-3
        # A 20 Hz tick loop: each tick's deadline is met exactly, far faster than real time.
        start_wall, start_sim = time.monotonic(), driver.now()
        deadline = start_sim
        for _ in range(100):
            deadline += 0.05
            driver.sleep_until(deadline)
            assert deadline <= driver.now() <= deadline + world.ready["timestep"] + 1e-9
        assert (driver.now() - start_sim) / (time.monotonic() - start_wall) > 2.0
    finally:
        driver.close()
    reader = world.clock()
    t0 = reader.now()
    time.sleep(0.1)
    assert reader.now() > t0 + 0.1, "without a driver the world free-runs again"
    reader.close()


def test_reader_sleep_until_waits_for_sim_time(world):
    reader = world.clock()
    try:
        target = reader.now() + 2.0
        reader.sleep_until(target)
        assert reader.now() >= target
        assert reader.factor >= 1.0
    finally:
        reader.close()


def test_speed_cap_keeps_the_world_at_most_five_times_wall():
    """The cap is an upper bound: a free-running world would go tens of times faster than wall
    time here. How close to 5x it gets depends on the CPU it is given (a busy machine, other
    tests beside it), so below the cap only "faster than real time" is asserted."""
    with launch_world(robot=ROBOT, speed=5.0, stderr=subprocess.DEVNULL) as w:
        clock = w.clock()
        time.sleep(0.3)
        wall0, sim0 = time.monotonic(), clock.now()
        time.sleep(1.5)
        ratio = (clock.now() - sim0) / (time.monotonic() - wall0)
        print(f"sim seconds per wall second: {ratio:.2f}, world's own measure {clock.factor:.2f}")
        assert 1.5 <= ratio <= 5.5, ratio
        assert 1.0 <= clock.factor <= 6.0
        clock.close()
