"""Skill and built-in leaves against the real dry daemons: commands, world updates, failures."""

from __future__ import annotations

import math

from stuart_bt.testing import run_tree

# Lab map (sim/maps/lab_markers.json): the robot starts at 'entrance' (0, 0, 0).


def test_navigate_to_marker_moves_the_robot_and_records_the_visit():
    result = run_tree(text="root: {navigate: kitchen}")
    result.assert_success()
    result.assert_visited("kitchen")
    result.assert_final_pose(3.5, 1.5, 0.0)
    assert result.world["last_marker"] == "kitchen"


def test_navigate_to_map_pose_and_body_relative_offsets_follow_rep103():
    result = run_tree(text="""
root:
  sequence:
    - navigate: {x: 1.0, y: 0.0, yaw: 1.5708}
    - navigate: {dx: 1.0}          # forward, i.e. along +y now (facing left)
    - turn: {degrees: -90}          # clockwise back to yaw 0
    - navigate: {dy: 0.5}           # to the left: +y
""")
    result.assert_success()
    result.assert_final_pose(1.0, 1.5, 0.0)


def test_turn_takes_radians_counter_clockwise():
    result = run_tree(text="root: {turn: 3.14159}")
    result.assert_success()
    result.assert_final_pose(0.0, 0.0, math.pi)


def test_unknown_marker_from_the_blackboard_fails_with_a_suggestion_and_sends_nothing():
    result = run_tree(text="""
blackboard: {goal: kitchn}
root: {navigate: {name: go, marker: $goal}}
""")
    assert result.status == "FAILURE"
    assert result.failure("go").startswith(
        "unknown marker 'kitchn' (did you mean 'kitchen'?); the markers are entrance, charging_dock, kitchen, "
        'bathroom, workbench, station_1 "Robot arms"')
    assert result.events("command") == []
    result.assert_final_pose(0.0, 0.0)


def test_a_display_name_from_the_blackboard_walks_to_its_marker():
    result = run_tree(text="""
blackboard: {goal: electronics bench}
root: {navigate: {name: go, marker: $goal}}
""")
    result.assert_success()
    [command] = result.commands("navigate")
    assert command["args"]["marker"] == "station_4"
    result.assert_final_pose(6.5, 0.5)


def test_speak_without_waiting_overlaps_the_next_leaf():
    result = run_tree(text="""
root:
  sequence:
    - speak: {text: "Let me show you the kitchen while we walk there.", wait: false}
    - navigate: kitchen
""")
    result.assert_success()
    speech = result.report["spoken"][0]
    walk_start = next(e["t"] for e in result.events("command") if e["cmd"] == "navigate")
    assert walk_start < speech["end"]  # the walk began while still speaking


def test_speech_and_gestures_in_parallel_overlap():
    result = run_tree(text="""
root:
  parallel:
    - speak: "Hello, I am Stuart and I will show you around."
    - gesture: {sequence: [wave, clap]}
""")
    result.assert_success()
    result.assert_gestured("high wave")  # 'wave' is an alias of 'high wave'
    speech, gesture = result.report["spoken"][0], result.report["gestures"][0]
    assert speech["start"] < gesture["end"] and gesture["start"] < speech["end"]


def test_templates_fill_speech_from_the_blackboard():
    result = run_tree(text="""
blackboard: {guest: Ada}
root: {speak: "Welcome, ${guest}!"}
""")
    result.assert_said("Welcome, Ada!")


def test_pick_out_of_reach_fails_before_any_motion():
    result = run_tree(text="root: {pick: {name: grab, object: bottle}}")
    assert result.status == "FAILURE"
    assert result.failure("grab").startswith("unreachable:")
    result.assert_holding(None)
    assert result.report["picks"] == []


def test_fetch_picks_at_the_kitchen_and_releases_at_the_workbench():
    result = run_tree("trees/fetch_bottle.yaml")
    result.assert_success()
    result.assert_visited("kitchen", "workbench")
    assert [p["object"] for p in result.report["picks"]] == ["bottle"]
    result.assert_holding(None)
    released = result.world["objects"]["bottle"]
    assert math.hypot(released["x"] - 1.0, released["y"] - (-2.4)) < 1.0  # put down at the workbench


def test_find_unknown_object_fails_with_not_found():
    result = run_tree(text="root: {find: {name: look, object: unicorn}}")
    assert result.status == "FAILURE"
    assert result.failure("look").startswith("not_found:")


def test_leaf_timeout_cancels_the_daemon_command_and_the_robot_stops_short():
    result = run_tree(text="root: {navigate: {name: go, marker: bathroom, timeout: 3}}")
    assert result.status == "FAILURE"
    assert result.failure("go") == "timed out after 3 s"
    cancels = [e for e in result.events("command") if e["cmd"] == "cancel"]
    assert len(cancels) == 1
    pose = result.report["final_pose"]
    assert 0.3 < math.hypot(pose["x"], pose["y"]) < 3.0  # stopped on the way, not at the goal (7.5, 3.0)


def test_wait_condition_set_and_log_run_inside_the_executor():
    result = run_tree(text="""
blackboard: {battery: 80, count: 1}
root:
  sequence:
    - condition: "battery > 20"
    - set: {key: count, expr: "count + 1"}
    - set: {key: mode, value: tour}
    - wait: 1.5
    - log: "count is ${count}, mode ${mode}"
""")
    result.assert_success()
    (log,) = result.events("log")
    assert log["message"] == "count is 2, mode tour"
    assert result.outcome.duration >= 1.5
    assert result.events("command") == []  # nothing went to a daemon


def test_false_condition_fails_with_its_expression_as_reason():
    result = run_tree(text="""
blackboard: {battery: 10}
root: {condition: {name: charged, expr: "battery > 20"}}
""")
    assert result.failure("charged") == "'battery > 20' is false"


def test_stop_leaf_stops_every_daemon():
    result = run_tree(text="""
root:
  parallel:
    policy: one
    children:
      - navigate: bathroom
      - sequence:
          - wait: 2
          - stop: {}
""")
    stops = {e["family"] for e in result.events("command") if e["cmd"] == "stop"}
    assert stops == {"loco"}  # the only daemon this tree started
    pose = result.report["final_pose"]
    assert math.hypot(pose["x"] - 7.5, pose["y"] - 3.0) > 3.0  # halted well short of the bathroom
