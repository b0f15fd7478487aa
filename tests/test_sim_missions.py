"""Voice missions end to end on the MuJoCo world: "Hey Stuart, ..." in, and the verdict taken
from the simulated world's own state (what the hand holds, where the base stands, whether it kept
moving after a stop) and from the mission records and events, not from what the tree believed."""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import pytest

from stuart_bt.core.events import Event
from stuart_bt.core.world import KnownObject
from stuart_bt.mission.executor import MissionExecutor, MissionOptions
from stuart_bt.perception.projection import head_camera_view

pytestmark = pytest.mark.sim

FAMILIES = {"loco", "tts", "gesture", "pick", "vision"}
WALL_LIMIT = 60.0  # wall seconds any one wait may take before the test fails
BRAKE = 1.0  # m/s^2: the walking controller's acceleration limit (docs/sim.md)
CAMERA = head_camera_view()  # what the head camera sees from a base pose (stuart_bt.maps.viewpoints)


class Trace:
    """Every event of a mission executor (as in tests/test_mission_executor.py)."""

    def __init__(self, robot: MissionExecutor) -> None:
        self.events: list[Event] = []
        robot.events.subscribe(self.events.append)

    def said(self) -> list[str]:
        return [e.data["args"]["text"] for e in self.events
                if e.kind == "command" and e.data.get("family") == "tts" and e.data.get("cmd") == "say"]

    def commands(self, family: str | None = None, cmd: str | None = None) -> list[Event]:
        return [e for e in self.events if e.kind == "command" and (family is None or e.data.get("family") == family)
                and (cmd is None or e.data.get("cmd") == cmd)]

    def missions(self, phase: str | None = None) -> list[dict[str, Any]]:
        return [e.data for e in list(self.events)
                if e.kind == "mission" and (phase is None or e.data["phase"] == phase)]

    def index(self, kind: str, **match: Any) -> int:
        return next(i for i, e in enumerate(self.events)
                    if e.kind == kind and all(e.data.get(k) == v for k, v in match.items()))


@contextmanager
def robot(**options: Any) -> Iterator[tuple[MissionExecutor, Trace]]:
    pytest.importorskip("mujoco")
    os.environ.setdefault("MUJOCO_GL", "egl")
    with MissionExecutor(MissionOptions(backend="sim", **options)) as mx:
        yield mx, Trace(mx)


def state(mx: MissionExecutor) -> dict[str, Any]:
    """The simulated world's own state (docs/sim.md), not the robot's belief."""
    return mx.session.world.call("state")


def poll(mx: MissionExecutor, condition: Callable[[dict[str, Any]], bool], what: str,
         timeout: float = WALL_LIMIT) -> dict[str, Any]:
    """Poll the world's state (wall time; the sim runs on in lockstep with the mission's ticks)
    until ``condition`` holds; returns that state."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        s = state(mx)
        if condition(s):
            return s
        if not mx.busy:
            pytest.fail(f"the robot went idle before: {what}; world: base={s['base']} status={s['base_status']}")
        time.sleep(0.005)
    pytest.fail(f"timed out waiting for: {what}; world: base={s['base']} status={s['base_status']}")


def distance(pose: dict[str, float], x: float, y: float) -> float:
    return math.hypot(pose["x"] - x, pose["y"] - y)


def speed(s: dict[str, Any]) -> float:
    return math.hypot(s["base_velocity"]["vx"], s["base_velocity"]["vy"])


def marker(mx: MissionExecutor, name: str) -> tuple[float, float]:
    m = mx.world.markers[name].pose
    return m.x, m.y


def test_compound_utterance_goes_to_the_kitchen_picks_the_bottle_and_carries_it_to_the_workbench():
    with robot() as (mx, trace):
        mx.submit("Hey Stuart, go to the kitchen and pick up the bottle, then go to the workbench")
        assert mx.wait_idle(WALL_LIMIT)
        final = state(mx)

    mission = mx.missions[0]
    assert [str(c) for c in mission.calls] == [
        "navigate_to_marker(place=kitchen)", "pick_up(obj=bottle)", "navigate_to_marker(place=workbench)"]
    assert mission.status == "succeeded", mission.reason
    assert trace.said() == ["Navigating to the kitchen", "Picking up the bottle", "Navigating to the workbench"]
    hands = [side for side, label in final["held"].items() if label == "bottle"]
    assert len(hands) == 1, f"the world's hands hold {final['held']}"
    bench = marker(mx, "workbench")
    assert distance(final["base"], *bench) < 0.15, f"base at {final['base']}, workbench at {bench}"
    # carried, not left behind: the bottle is where the hand is, well away from the kitchen table
    hand, bottle = final["hand_points"][hands[0]], final["objects"]["bottle"]
    assert math.dist(hand, [bottle["x"], bottle["y"], bottle["z"]]) < 0.12
    assert distance(bottle, *bench) < 0.6


def test_a_command_said_while_busy_is_queued_and_runs_after_the_first():
    with robot() as (mx, trace):
        mx.submit("Hey Stuart, go to station one")
        mx.submit("Hey Stuart, wave")
        assert mx.wait_idle(WALL_LIMIT)
        final = state(mx)

    assert [m.status for m in mx.missions] == ["succeeded", "succeeded"]
    assert [str(c) for m in mx.missions for c in m.calls] == [
        "navigate_to_marker(place=station_1)", "gesture(name=wave)"]
    assert trace.index("mission", id=1, phase="finished") < trace.index("mission", id=2, phase="started")
    said = trace.said()
    assert said == ["Navigating to the robot arms", "Doing a wave"]
    # the wave played after the walk had ended, standing at station one
    walk_done = max(i for i, e in enumerate(trace.events) if e.kind == "mission" and e.data["id"] == 1)
    play = trace.index("command", family="gesture", cmd="play")
    assert play > walk_done
    assert distance(final["base"], *marker(mx, "station_1")) < 0.15


def test_stop_halts_the_walk_at_once_and_continue_walks_on_to_the_bathroom():
    with robot() as (mx, trace):
        start = state(mx)["base"]
        mx.submit("Hey Stuart, go to the bathroom")
        poll(mx, lambda s: distance(s["base"], start["x"], start["y"]) > 0.5, "the base to move 0.5 m")
        mx.submit("Hey Stuart, stop")
        assert mx.wait_idle(WALL_LIMIT)
        mission = mx.missions[0]
        assert mission.status == "stopped"
        assert mission.halt_tick - mission.stop_tick <= 1, "the halt waited more than one tick"
        stops = {e.data["family"] for e in trace.commands(cmd="stop")}
        assert stops == FAMILIES, f"stop reached only {stops}"

        # the executor is idle now, so the sim clock stands still: drive it ourselves for 1 s
        halted = state(mx)
        clock, t0 = mx.session.clock, halted["t"]
        samples = [halted]
        while samples[-1]["t"] < t0 + 1.0:
            clock.sleep_until(clock.now() + 0.05)
            samples.append(state(mx))
        v0 = speed(halted)
        assert v0 > 0.3, f"the stop came while the base was not walking ({v0:.2f} m/s)"
        assert speed(samples[1]) <= v0 - 0.8 * BRAKE * (samples[1]["t"] - t0), (
            f"{speed(samples[1]):.2f} m/s one tick after the halt, from {v0:.2f}: the braking did not start at once")
        half = next(s for s in samples if s["t"] >= t0 + 0.5)
        braking = v0 ** 2 / (2 * BRAKE)  # the braking distance at the walking controller's limit
        went_on = distance(half["base"], halted["base"]["x"], halted["base"]["y"])
        assert went_on <= braking + 0.02, (
            f"the base went on {went_on:.3f} m in 0.5 s after the halt "
            f"(braking from {v0:.2f} m/s needs {braking:.3f} m)")
        assert speed(half) <= max(0.0, v0 - 0.9 * BRAKE * (half["t"] - t0)), (
            f"still at {speed(half):.2f} m/s 0.5 s after the halt: it did not brake from the first step")
        still = [s for s in samples if s["t"] >= t0 + v0 / BRAKE + 0.05]
        assert still and all(speed(s) == 0.0 for s in still), "the base did not come to rest"
        drift = distance(still[-1]["base"], still[0]["base"]["x"], still[0]["base"]["y"])
        assert drift < 0.005, f"the base crept {drift:.3f} m after it had stopped"
        bathroom = marker(mx, "bathroom")
        assert distance(samples[-1]["base"], *bathroom) > 1.0, "it was not stopped short of the bathroom"

        mx.submit("Hey Stuart, continue")
        assert mx.wait_idle(WALL_LIMIT)
        final = state(mx)

    assert mission.status == "succeeded" and mission.resumed
    assert [p["phase"] for p in trace.missions() if p["id"] == 1] == [
        "queued", "started", "stopped", "resumed", "started", "finished"]
    assert trace.said()[-1] == "Carrying on."
    assert distance(final["base"], *bathroom) < 0.15, f"base at {final['base']}"


def test_an_apple_moved_while_the_robot_walks_to_it_is_looked_for_again_approached_and_picked():
    """The fault is real: the apple is moved along the table (set_object) while the robot walks to
    it. Standing before where it was, the robot's close look (the head camera) does not see it, the
    executor forgets the apple and re-plans ``pick_up``: it looks around until it sees the apple at
    its new place, walks along the table to it, looks again and picks it up. The test first stands
    the apple at the table's near edge, in the world and in memory alike: at its default place in
    the middle of the table no arm reaches it (the next test)."""
    first, moved_to = (4.05, 1.75, 0.79), (4.05, 1.2)
    with robot() as (mx, trace):
        mx.session.world.call("set_object", label="apple", x=first[0], y=first[1], z=first[2])
        mx.world.objects["apple"] = KnownObject("apple", *first)
        start = state(mx)["base"]
        mx.submit("Hey Stuart, pick up the apple")
        poll(mx, lambda s: distance(s["base"], start["x"], start["y"]) > 1.0, "the walk to the apple")
        moved_at = len(trace.events)
        mx.session.world.call("set_object", label="apple", x=moved_to[0], y=moved_to[1], z=first[2])
        assert mx.wait_idle(WALL_LIMIT)
        final = state(mx)

    leaves = [(e.path, e.data["outcome"], e.data["reason"] or "") for e in trace.events
              if e.kind == "leaf" and e.data["skill"] in ("approach", "pick", "find")]
    looks = [i for i, e in enumerate(trace.events) if e.kind == "command" and e.data.get("cmd") == "find"]
    assert looks and looks[0] > moved_at, "the apple was moved after the robot had arrived"
    assert [leaf[:2] for leaf in leaves] == [
        ("mission/pick_up/get/go_near/approach", "SUCCESS"),  # walked to where the apple was
        ("mission/pick_up/get/look", "FAILURE"),  # the close look: it is not there any more
        # repair: looked for again with the head camera; the apple is outside the camera's view
        # from here, so the glances see nothing and the scan turns until the last look sees it
        ("mission/pick_up/search/scan/glance/optional/find", "FAILURE"),
        ("mission/pick_up/search/scan/scan/glance/optional/find", "FAILURE"),
        ("mission/pick_up/search/scan/scan/scan/glance/optional/find", "FAILURE"),
        ("mission/pick_up/search/scan/scan/scan/scan/look", "SUCCESS"),
        ("mission/pick_up/get/go_near/approach", "SUCCESS"),  # walked along the table to it
        ("mission/pick_up/get/look", "SUCCESS"),
        ("mission/pick_up/get/pick_object", "SUCCESS"),
    ], "\n".join(map(str, leaves))
    assert all(leaf[2].startswith("not_found: no apple in view") for leaf in leaves[1:5]), leaves[1:5]
    assert not [e for e in trace.events if e.kind == "command" and e.data.get("cmd") == "pick"
                and e.data["args"].get("position", {}).get("y", 0) > 1.5], "a pick aimed where the apple was"

    mission = mx.missions[0]
    assert mission.status == "succeeded" and mission.repairs == 1
    assert [r["failed"] for r in trace.missions("repaired")] == ["mission/pick_up/get/look"]
    assert trace.said() == ["Picking up the apple"]
    assert "apple" in final["held"].values(), final["held"]  # the world's hand holds it
    apple = final["objects"]["apple"]
    assert distance(apple, *moved_to) < 0.1 and apple["z"] > first[2] + 0.05, "it was not lifted from its new place"
    base = final["base"]
    assert distance(base, *moved_to) < 0.45, "the robot picked it from where it stood before"


def test_an_object_no_arm_can_reach_from_any_side_is_said_and_nothing_moves():
    """The apple's default place is the middle of the kitchen table: every spot from which an arm
    would reach it is inside the table or the counter, so the approach fails before the walk."""
    with robot() as (mx, trace):
        before = state(mx)
        mx.submit("Hey Stuart, pick up the apple")
        assert mx.wait_idle(WALL_LIMIT)
        after = state(mx)
    mission = mx.missions[0]
    assert mission.status == "failed"
    assert trace.said()[-1] == ("Sorry, I could not pick up the apple: I can't get close enough to it - "
                                "the kitchen table is in the way."), "not said in words people use"
    assert mission.reason.startswith("Sorry, I could not pick up the apple: no free spot to stand within"), \
        "the technical reason left the report"
    assert mission.failure is not None and mission.failure["blocked_by"] == ["kitchen table"]
    assert mission.repairs == 1, "a repair that met the same failure again was tried again"
    assert distance(after["base"], before["base"]["x"], before["base"]["y"]) < 0.01
    assert not trace.commands("pick", "pick"), "an arm moved"


@pytest.mark.parametrize(("where", "spot"), [
    ("where the lab keeps it, 0.25 m in from the kitchen table's edge", (4.35, 1.85, 0.79)),
    ("the middle of the kitchen table", (4.31, 1.5, 0.79)),
    ("the middle of the workbench, whose back is at the wall", (1.0, -3.16, 0.89)),
])
def test_find_an_object_no_arm_could_reach_walks_to_where_the_camera_sees_it(where, spot):
    """Finding needs sight, not reach: from the table's edge the head camera sees an apple that no
    arm could reach (the previous test), so the robot looks from there, and memory takes the
    position the camera measured."""
    with robot() as (mx, trace):
        mx.session.world.call("set_object", label="apple", x=spot[0], y=spot[1], z=spot[2])
        mx.world.objects["apple"] = KnownObject("apple", *spot)
        mx.submit("Hey Stuart, find the apple")
        assert mx.wait_idle(WALL_LIMIT)
        final = state(mx)

    mission = mx.missions[0]
    assert mission.status == "succeeded", mission.said or mission.reason
    assert mission.repairs == 0
    skills = [(e.data["skill"], e.data["outcome"]) for e in trace.events if e.kind == "leaf"
              and e.data["skill"] in ("approach", "view", "find")]
    assert skills == [("view", "SUCCESS"), ("find", "SUCCESS")], skills
    apple, base = final["objects"]["apple"], final["base"]
    assert CAMERA.miss((base["x"], base["y"], base["yaw"]), (apple["x"], apple["y"], apple["z"])) is None, \
        f"the camera does not see the apple at {apple} from {base}"
    assert distance(base, apple["x"], apple["y"]) > 0.39, "it stood within arm's reach: not the case tested"
    assert not final["collided"], final["collision_with"]
    remembered = mx.world.objects["apple"]
    assert remembered.source == "vision" and math.hypot(remembered.x - apple["x"], remembered.y - apple["y"]) < 0.03


def body_frame(base: dict[str, float], x: float, y: float) -> tuple[float, float]:
    """(ahead, left) of the map point (x, y) as the robot at ``base`` sees it (REP-103)."""
    dx, dy, yaw = x - base["x"], y - base["y"], base["yaw"]
    return dx * math.cos(yaw) + dy * math.sin(yaw), -dx * math.sin(yaw) + dy * math.cos(yaw)


def test_go_to_an_object_ends_facing_it_within_arm_reach():
    with robot() as (mx, trace):
        mx.submit("Hey Stuart, go to the cup")
        assert mx.wait_idle(WALL_LIMIT)
        final = state(mx)

    assert mx.missions[0].status == "succeeded", mx.missions[0].reason
    assert trace.said() == ["Going to the cup"]
    ahead, left = body_frame(final["base"], final["objects"]["cup"]["x"], final["objects"]["cup"]["y"])
    assert 0.2 < ahead < 0.45 and abs(left) < 0.05, f"the cup is at ({ahead:.2f}, {left:.2f}) in the body frame"
    assert not final["collided"]


def test_find_the_cup_ends_where_the_camera_sees_it_with_the_camera_s_position_in_memory():
    with robot() as (mx, trace):
        mx.submit("Hey Stuart, find the cup")
        assert mx.wait_idle(WALL_LIMIT)
        final = state(mx)

    assert mx.missions[0].status == "succeeded", mx.missions[0].reason
    cup, base = final["objects"]["cup"], final["base"]
    assert CAMERA.miss((base["x"], base["y"], base["yaw"]), (cup["x"], cup["y"], cup["z"])) is None, (cup, base)
    ahead, left = body_frame(base, cup["x"], cup["y"])
    assert abs(math.atan2(left, ahead)) < math.radians(8), (ahead, left)  # facing it
    looks = [e for e in trace.events if e.kind == "leaf" and e.data["skill"] == "find"]
    assert looks and looks[-1].data["outcome"] == "SUCCESS"
    remembered = mx.world.objects["cup"]
    assert remembered.source == "vision" and math.hypot(remembered.x - cup["x"], remembered.y - cup["y"]) < 0.025


def test_pick_up_the_bottle_from_the_entrance_walks_up_looks_and_picks_where_the_camera_saw_it():
    with robot() as (mx, trace):
        initial = state(mx)
        mx.submit("Hey Stuart, pick up the bottle")
        assert mx.wait_idle(WALL_LIMIT)
        final = state(mx)

    assert distance(initial["base"], 0.0, 0.0) < 0.05, "the robot did not start at the entrance"
    assert mx.missions[0].status == "succeeded", mx.missions[0].reason
    order = [e.data["skill"] for e in trace.events
             if e.kind == "leaf" and e.data["skill"] in ("approach", "find", "pick")]
    assert order == ["approach", "find", "pick"]
    pick = next(e for e in trace.events if e.kind == "command" and e.data.get("cmd") == "pick")
    aimed, truth = pick.data["args"]["position"], initial["objects"]["bottle"]
    assert math.dist([aimed[k] for k in "xyz"], [truth[k] for k in "xyz"]) < 0.025, (aimed, truth)
    assert "bottle" in final["held"].values() and final["objects"]["bottle"]["z"] > 0.855 + 0.05


def test_an_unknown_place_is_said_and_the_base_does_not_move():
    with robot() as (mx, trace):
        before = state(mx)
        mx.submit("Hey Stuart, go to the garage")
        assert mx.wait_idle(WALL_LIMIT)
        after = state(mx)

    said = trace.said()
    assert len(said) == 1 and said[0].startswith("I don't know where the garage is."), said
    assert not mx.missions
    assert not [e for e in trace.commands() if e.data["family"] in ("loco", "pick", "gesture")
                and e.data["cmd"] not in ("stop", "shutdown")], "something was told to move"
    assert after["t"] > before["t"], "the sentence was not spoken on the sim's clock"
    assert distance(after["base"], before["base"]["x"], before["base"]["y"]) < 1e-3
    assert abs(after["base"]["yaw"] - before["base"]["yaw"]) < 1e-3
    assert after["base_status"] == before["base_status"] and speed(after) == 0.0
