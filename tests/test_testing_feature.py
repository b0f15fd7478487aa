"""The simulated-tree-test feature itself: the stuart_sim / stuart_dry fixtures, hooks acting on
the world mid-run, the world shut down whatever the test does, and assertion messages that
say what happened."""

from __future__ import annotations

import os
from pathlib import Path
from types import SimpleNamespace

import pytest

from stuart_bt.run.executor import RunOutcome
from stuart_bt.testing import RunResult, at, when

PLUGIN_CONFTEST = """
from stuart_bt import pytest_plugin

def pytest_configure(config):
    if not config.pluginmanager.is_registered(pytest_plugin):
        config.pluginmanager.register(pytest_plugin, "stuart_bt")
"""


def made_up(report: dict | None = None, timeline: list[dict] | None = None, **world) -> RunResult:
    """A result without a run, for the assertion messages."""
    base = {"status": "SUCCESS", "backend": "sim", "visited": [], "spoken": [], "gestures": [], "failures": [],
            "final_pose": {"x": 0.0, "y": 0.0, "yaw": 0.0}, "held": None, "events": []}
    timeline = timeline or []
    return RunResult(RunOutcome("SUCCESS", 0.0, 1.0, 20), {**base, **(report or {})}, {},
                     world.get("initial", timeline[0] if timeline else None),
                     world.get("final", timeline[-1] if timeline else None), timeline)


def state(t: float, x: float = 0.0, **changes) -> dict:
    return {"t": t, "base": {"x": x, "y": 0.0, "yaw": 0.0}, "base_status": "idle", "collision": False,
            "collision_with": [], "collided": False, "joints": {"right_elbow_joint": 1.25},
            "held": {"left": None, "right": None}, "objects": {"bottle": {"x": 4.0, "y": 1.4, "z": 0.855}},
            "person": None, **changes}


# --- the fixtures, on real runs --------------------------------------------------------------------


def test_stuart_dry_runs_a_tree_file_and_assert_visited_explains_a_wrong_order(stuart_dry):
    result = stuart_dry(text="root: {sequence: [{navigate: kitchen}, {navigate: workbench}]}")

    result.assert_visited("kitchen", "workbench")
    with pytest.raises(AssertionError) as wrong:
        result.assert_visited("workbench", "kitchen")
    assert str(wrong.value).startswith(
        "visited ['kitchen', 'workbench'], expected in order ['workbench', 'kitchen'] (first out of order: 'kitchen')")
    with pytest.raises(AssertionError, match=r"expected exactly \['kitchen'\]"):
        result.assert_visited("kitchen", exactly=True)


def test_world_assertions_on_the_dry_backend_say_they_need_the_sim(stuart_dry):
    result = stuart_dry(text="root: {navigate: kitchen}")

    with pytest.raises(AssertionError, match="needs the simulated world's state; this run used the dry backend"):
        result.assert_no_collisions()
    with pytest.raises(AssertionError, match="no arrival carries a measured error"):
        result.assert_arrivals_within()


def test_hooks_move_the_person_and_an_object_during_the_run(stuart_sim):
    result = stuart_sim(text="root: {wait: 1.0}", start="kitchen", seed=3, on_tick=[
        at(0.3, lambda run: run.world.person_at(2.0, -1.0)),
        at(0.5, lambda run: run.world.move_object("bottle", 4.3, 1.2, 0.9)),
    ])

    result.assert_success()
    assert result.initial_world["base"] == {"x": 3.5, "y": 1.5, "yaw": 0.0}  # start= put the robot there
    assert result.timeline[0]["t"] < 0.1  # the world waited at t = 0 for the run to start
    assert result.state_at(0.25)["person"] is None
    assert result.final_world["person"] == {"x": 2.0, "y": -1.0}
    result.assert_object_at("bottle", 4.3, 1.2, z=0.855, tolerance=0.01)  # dropped onto the table top


def test_assert_no_collisions_catches_the_base_pushed_into_furniture(stuart_sim):
    result = stuart_sim(text="root: {wait: 0.5}", on_tick=at(0.2, lambda run: run.world.call("set_base", x=4.3, y=1.5)))

    with pytest.raises(AssertionError, match=r"the base collided by t=0.2\d at \(4.30, 1.50\) with \['"):
        result.assert_no_collisions()


def test_when_fires_once_after_its_condition_held_long_enough():
    fired: list[float] = []
    trigger = when(lambda run: run.t >= 1.0, lambda run: fired.append(run.t), held_for=0.5)
    for tick in range(40):
        trigger(SimpleNamespace(t=tick * 0.05))
    assert fired == [pytest.approx(1.5)] and trigger.fired_at == pytest.approx(1.5)


def test_sim_fixture_defaults_mujoco_gl_to_egl_and_marks_its_tests(pytester, monkeypatch):
    monkeypatch.delenv("MUJOCO_GL", raising=False)
    pytester.makeconftest(PLUGIN_CONFTEST)
    pytester.makepyfile(test_inner="""
import os

def test_uses_the_sim(stuart_sim):
    assert os.environ["MUJOCO_GL"] == "egl"

def test_dry_only(stuart_dry):
    assert "MUJOCO_GL" not in os.environ
""")
    pytester.runpytest_inprocess("-p", "no:cacheprovider").assert_outcomes(passed=2)
    pytester.runpytest_inprocess("-m", "not sim", "-p", "no:cacheprovider").assert_outcomes(passed=1, deselected=1)
    assert "MUJOCO_GL" not in os.environ


def test_world_and_daemons_are_shut_down_after_failing_tests(pytester):
    pytester.makeconftest(PLUGIN_CONFTEST)
    pytester.makepyfile(test_inner="""
from pathlib import Path
from stuart_bt.testing import at

def note_processes(run):
    with open("processes.txt", "a") as f:
        f.write(f"{run.world.pid} {run.supervisor.pid('loco')} "
                f"{run.world.socket_path} {run.world.process.clock_path}\\n")

def test_assertion_fails_after_the_run(stuart_sim):
    result = stuart_sim(text="root: {navigate: {dx: 0.5}}", on_tick=at(0.0, note_processes))
    result.assert_visited("kitchen")

def test_hook_raises_mid_run(stuart_sim):
    def trip(run):
        raise RuntimeError("the hook tripped")
    stuart_sim(text="root: {navigate: kitchen}", on_tick=[at(0.0, note_processes), at(1.0, trip)])
""")
    result = pytester.runpytest_inprocess("-p", "no:cacheprovider")

    result.assert_outcomes(failed=2)
    result.stdout.fnmatch_lines(["*stuart_bt runs*", "run 1: SUCCESS (sim, <string>*", "*report: *stuart_run_1.json",
                                 "*RuntimeError: the hook tripped*"])
    lines = (pytester.path / "processes.txt").read_text().split("\n")[:-1]
    assert len(lines) == 2
    for line in lines:
        world_pid, loco_pid, socket_path, clock_path = line.split()
        for pid in (int(world_pid), int(loco_pid)):
            with pytest.raises(ProcessLookupError):  # gone and reaped, not even a zombie
                os.kill(pid, 0)
        assert not Path(socket_path).exists() and not Path(clock_path).exists()


# --- assertion messages, on made-up results -------------------------------------------------------


def test_assert_arrivals_within_lists_each_arrival_off_the_mark():
    leaf = {"kind": "leaf", "skill": "navigate", "outcome": "SUCCESS", "path": "tour/station_2/go/walk", "t": 28.3,
            "result": {"marker": "station_2", "pose": {}, "error": {"position": 0.132, "yaw": 0.01,
                                                                      "within_tolerance": False}}}
    result = made_up({"events": [leaf]})

    with pytest.raises(AssertionError) as off:
        result.assert_arrivals_within(0.10)
    assert str(off.value) == ("1 of 1 arrivals outside 0.1 m / 5.0°:\n  tour/station_2/go/walk (station_2) at "
                              "t=28.30: 0.132 m, 0.6° off, within_tolerance=False")


def test_assert_speech_overlaps_gestures_shows_both_spans():
    result = made_up({"spoken": [{"text": "Hi", "path": "tour/s1/present/speak", "start": 1.0, "end": 2.0}],
                      "gestures": [{"name": ["clap"], "path": "tour/s1/present/gesture", "start": 2.5, "end": 4.0}]})

    with pytest.raises(AssertionError) as apart:
        result.assert_speech_overlaps_gestures("tour/s1/", "tour/s2/")
    assert str(apart.value) == ("speech did not overlap gestures:\n"
                                "  tour/s1/: speech 1.00..2.00 overlaps no gesture (['clap'] 2.50..4.00)\n"
                                "  tour/s2/: 0 utterance(s), 0 gesture(s) finished")


def test_world_assertions_say_when_and_where():
    bump = state(2.0, x=1.2, collision=True, collided=True, collision_with=["kitchen_table"])
    result = made_up(timeline=[state(0.0), state(1.0, x=0.6), bump])

    with pytest.raises(AssertionError, match=r"collided by t=2.00 at \(1.20, 0.00\) with \['kitchen_table'\]"):
        result.assert_no_collisions()
    with pytest.raises(AssertionError, match=r"the robot moved by t=1.00: \(0.000, 0.000, 0.000\) -> \(0.600"):
        result.assert_robot_did_not_move()
    with pytest.raises(AssertionError, match=r"no hand ever held 'bottle'"):
        result.assert_object_raised("bottle")
    with pytest.raises(AssertionError, match=r"bottle ended at .* 0.300 m from \(4.3, 1.4\)"):
        result.assert_object_at("bottle", 4.3, 1.4)


def test_assert_object_raised_reports_the_highest_point_in_hand():
    lifted = state(3.0, held={"left": None, "right": "bottle"}, objects={"bottle": {"x": 4.0, "y": 1.4, "z": 0.875}})
    result = made_up(timeline=[state(0.0), lifted, state(4.0)])

    with pytest.raises(AssertionError) as low:
        result.assert_object_raised("bottle", by=0.05)
    assert str(low.value) == ("bottle rose 2.0 cm at most while held (z 0.855 -> 0.875 at t=3.00); "
                              "expected at least 5.0 cm")
    assert result.assert_object_raised("bottle", by=0.01) == pytest.approx(0.02)


def test_assert_failed_names_the_failures_there_were():
    result = made_up({"failures": [{"path": "root/walk", "skill": "navigate", "t": 0.1,
                                    "reason": "unreachable: goal (20.00, 0.00) is off the map"}]})

    assert result.assert_failed("walk", "unreachable").endswith("off the map")
    with pytest.raises(AssertionError, match=r"failed with 'unreachable: .*', expected 'blocked'"):
        result.assert_failed("walk", "blocked")
    with pytest.raises(AssertionError, match=r"leaf 'grab' never failed; failures: \['root/walk: unreachable"):
        result.assert_failed("grab")
