"""The project domain (tasks/domain.yaml): every intent and mission plans from the lab's start
state into steps the compiler can turn into existing leaves, and impossible requests fail with
the reason a person needs."""

from __future__ import annotations

import json
import math
from importlib.resources import files
from typing import Any

import pytest

from stuart_bt.core.catalogue import LEAVES
from stuart_bt.core.world import Pose
from stuart_bt.htn import Plan, Planner, PlanningFailed, State, TaskCall, lab_world
from stuart_bt.htn.domain import check_skill_args
from stuart_bt.tasks import project_domain

INTENTS = {"navigate_to_marker", "move_relative", "turn_by_angle", "turn_around", "pick_up", "gesture", "stop", "find"}


def lab(**changes: Any) -> State:
    """The lab as the CLI starts it (markers, objects.json, robot at the entrance), with changes."""
    state = project_domain().initial_state(lab_world())
    return State({**state, **changes})


def plan(task: str | list[TaskCall], state: State | None = None) -> Plan:
    """Plan task text (read by the domain: task calls or JSON TaskIntents) or TaskCalls."""
    domain = project_domain()
    calls = domain.calls_from_text(task) if isinstance(task, str) else task
    return Planner(domain).plan(calls, state if state is not None else lab())


def steps(p: Plan) -> list[str]:
    """Each step as ``skill key=value ...``: what the compiler will turn into a leaf."""
    out = []
    for s in p.primitives():
        args = " ".join(f"{k}={_short(v)}" for k, v in (s.skill_args or {}).items())
        out.append(f"{s.skill} {args}".strip())
    return out


def _short(v: Any) -> str:
    return f"{v:.2f}" if isinstance(v, float) else str(v)


def failure_of(task: str, state: State | None = None) -> str:
    with pytest.raises(PlanningFailed) as caught:
        plan(task, state)
    return str(caught.value)


# -- the domain and its start state ---------------------------------------------------------------------
def test_the_domain_ships_with_the_package_and_has_one_task_per_intent() -> None:
    assert files("stuart_bt.tasks").joinpath("domain.yaml").is_file()
    domain = project_domain()
    assert set(domain.intents) == INTENTS
    for name in ("fetch", "bring", "tour", "greet", "go_and_say", "find", "do_all"):
        assert domain.get(name) is not None, name


def test_the_default_state_is_the_lab_with_the_robot_at_the_entrance() -> None:
    state = lab()
    assert state["at"] == "entrance" and state["speaker_at"] == "entrance" and state["held"] is None
    assert state["objects"]["bottle"] == {"x": 4.01, "y": 1.38, "z": 0.855}
    assert state["names"]["station_2"] == "3D printers" and state["names"]["kitchen"] == "kitchen"
    assert state["look_steps"] == 4 and state["standoff"] == 0.29


def test_a_robot_away_from_its_last_marker_is_at_no_marker() -> None:
    world = lab_world()
    world.pose = Pose(1.0, 1.0, 0.0)
    state = State.from_world(world)
    assert state["at"] is None and state["speaker_at"] == {"x": 1.0, "y": 1.0, "yaw": 0.0}


# -- one task per intent --------------------------------------------------------------------------------
@pytest.mark.parametrize(("task", "expected"), [
    ("navigate_to_marker(kitchen)", ["speak text=Navigating to the kitchen", "navigate marker=kitchen"]),
    ("navigate_to_marker(entrance)", ["speak text=I am already at the entrance"]),
    ("move_relative(1.0, 0.5, 0)", ["speak text=Moving", "navigate dx=1.00 dy=0.50 dyaw=0"]),
    ("move_relative", ["speak text=I am staying where I am"]),
    ("turn_by_angle(1.5708)", ["speak text=Turning", "turn angle=1.57"]),
    ("turn_around", ["speak text=Turning around", "turn angle=3.14"]),
    ("pick_up(bottle)", ["speak text=Picking up the bottle", "approach object=bottle standoff=0.29 lateral=-0.10",
                         "find object=bottle", "pick object=bottle"]),  # the camera has the last word up close
    ("gesture('high wave')", ["speak text=Doing a high wave", "gesture play=high wave"]),
    ("stop", ["speak text=Stopping", "stop"]),
    ("find(cup)", ["speak text=Looking for the cup", "view object=cup", "find object=cup"]),  # sight, not reach
])
def test_each_intent_starts_with_its_acknowledgement(task: str, expected: list[str]) -> None:
    p = plan(task)
    assert steps(p) == expected
    assert p.primitives()[0].ack


def test_task_intents_plan_like_the_task_text() -> None:
    intents = [{"action": "navigate_to_marker", "target": "kitchen", "x": None, "y": None, "yaw": None,
                "raw_text": "hey stuart go to the kitchen"},
               {"action": "move_relative", "x": 0.5, "raw_text": "step forward"},
               {"action": "turn_around"}]
    calls = project_domain().calls_from_intents(intents)
    assert steps(plan(calls)) == steps(plan("navigate_to_marker(kitchen); move_relative(0.5); turn_around"))
    assert steps(plan(json.dumps(intents))) == steps(plan(calls))


def test_approach_stops_with_the_object_in_front_of_a_shoulder_facing_it() -> None:
    approach = plan("pick_up(bottle)").primitives()[1]
    assert approach.name == "approach" and approach.skill == "approach"
    assert approach.skill_args == {"object": "bottle", "standoff": 0.29, "lateral": -0.1}  # arm reach ~0.42 m
    predicted = dict(approach.changes or [])["pose"]                          # where the planner expects it
    yaw = predicted["yaw"]
    dx, dy = 4.01 - predicted["x"], 1.38 - predicted["y"]                     # the bottle in the body frame:
    ahead, left = dx * math.cos(yaw) + dy * math.sin(yaw), -dx * math.sin(yaw) + dy * math.cos(yaw)
    assert (ahead, left) == (pytest.approx(0.29, abs=1e-6), pytest.approx(-0.1, abs=1e-6))  # before the right shoulder
    assert yaw == pytest.approx(math.atan2(1.38, 4.01), abs=0.01)             # looking from the entrance (0, 0)


# -- fetch, bring, find ---------------------------------------------------------------------------------
def test_fetch_a_known_object_goes_to_it_picks_it_and_puts_it_down_at_the_place() -> None:
    p = plan("fetch(bottle, workbench)")
    assert p.tasks[0].method == "known_location"
    assert steps(p) == ["speak text=Fetching the bottle for the workbench",
                        "approach object=bottle standoff=0.29 lateral=-0.10", "find object=bottle",
                        "pick object=bottle", "navigate marker=workbench", "release"]
    assert p.state["held"] is None and p.state["at"] == "workbench"
    assert p.state["objects"]["bottle"] == {"x": 1.0, "y": -2.8, "z": 0.8}  # 0.4 m ahead of the robot


def test_fetch_what_is_already_in_hand_only_carries_it() -> None:
    p = plan("fetch(bottle, workbench)", lab(held="bottle"))
    assert p.tasks[0].method == "already_holding"
    assert steps(p)[1:] == ["navigate marker=workbench", "release"]


def test_fetch_with_full_hands_puts_the_other_object_down_first() -> None:
    p = plan("fetch(bottle, workbench)", lab(held="cup"))
    assert p.tasks[0].method == "hands_full"
    assert steps(p)[1:3] == ["release", "approach object=bottle standoff=0.29 lateral=-0.10"]


def test_fetch_an_object_remembered_at_a_marker_walks_there_and_looks_for_it() -> None:
    p = plan("fetch(keys, workbench)", lab(objects={"keys": "kitchen"}))
    assert steps(p) == [
        "speak text=Fetching the keys for the workbench",
        "navigate marker=kitchen",
        "find object=keys",  # its position is known from now on
        "approach object=keys standoff=0.29 lateral=-0.10",  # the leaf reads the position when it starts
        "find object=keys",  # and looks again up close
        "pick object=keys",
        "navigate marker=workbench",
        "release",
    ]


def test_fetch_an_unknown_object_looks_around_in_steps_first() -> None:
    p = plan("fetch(orange, kitchen)")
    assert p.tasks[0].method == "unknown_location"
    looks = [s for s in p.primitives() if s.skill in ("find", "turn")]
    assert [(s.name, s.optional, s.skip_if) for s in looks] == [
        ("glance", True, "'orange' in world.objects"), ("scan_turn", False, "'orange' in world.objects"),
        ("glance", True, "'orange' in world.objects"), ("scan_turn", False, "'orange' in world.objects"),
        ("glance", True, "'orange' in world.objects"), ("scan_turn", False, "'orange' in world.objects"),
        ("look", False, None),                                                   # the last look must see it
        ("look", False, None),                                                   # and again up close, before the pick
    ]
    assert steps(p)[-3:] == ["pick object=orange", "navigate marker=kitchen", "release"]


def test_bring_returns_to_where_the_command_was_given() -> None:
    p = plan("bring(cup)")
    assert steps(p) == ["speak text=Bringing you the cup", "approach object=cup standoff=0.29 lateral=-0.10",
                        "find object=cup", "pick object=cup", "navigate marker=entrance", "release",
                        "speak text=Here is your cup."]
    spot = {"x": 2.0, "y": 1.0, "yaw": 0.5}
    assert steps(plan("bring(cup)", lab(speaker_at=spot)))[4] == "navigate x=2.00 y=1.00 yaw=0.50"


def test_going_to_an_object_walks_up_to_it_looking_for_it_first_when_unknown() -> None:
    known = plan("navigate_to_marker(bottle)")
    assert known.tasks[0].method == "to_object"
    # squarely:
    assert steps(known) == ["speak text=Going to the bottle", "approach object=bottle standoff=0.29 lateral=0"]
    unknown = plan("navigate_to_marker(orange)")
    assert [s.skill for s in unknown.primitives()][:2] == ["speak", "find"]
    assert unknown.primitives()[-1].skill == "approach"
    assert plan("navigate_to_marker(kitchen)").tasks[0].method == "walk"  # a marker is walked to, not approached


def test_find_remembered_objects_directly_and_unknown_ones_by_looking_around() -> None:
    assert plan("find(bottle)").tasks[0].method == "remembered"
    p = plan("find(orange)")
    assert p.tasks[0].method == "look_around"
    assert [s.skill for s in p.primitives()] == ["speak", "find", "turn", "find", "turn", "find", "turn", "find",
                                                 "view"]
    assert [s.skill for s in plan("find(bottle)").primitives()] == ["speak", "view", "find"], \
        "finding walks to where the camera sees it, not to arm's reach"


# -- tour, greet, go_and_say, do_all ---------------------------------------------------------------------
def test_the_tour_visits_every_station_in_order_and_presents_it() -> None:
    p = plan("tour")
    visited = [s.skill_args["marker"] for s in p.primitives() if s.skill == "navigate"]
    assert visited == ["station_1", "station_2", "station_3", "station_4", "station_5", "station_6"]
    station_2 = [s for s in p.primitives() if s.parent is not None and s.parent.call == "present(station_2)"]
    assert [steps_of(s) for s in station_2] == [
        "speak text=Here are the 3D printers. Most of my spare parts were printed right here.", "gesture play=clap"]
    assert steps(p)[0] == "speak text=Welcome to the lab! Please follow me."
    assert steps(p)[-1] == "speak text=That is the end of our tour. Thank you for visiting!"


def steps_of(step: Any) -> str:
    return f"{step.skill} " + " ".join(f"{k}={v}" for k, v in step.skill_args.items())


def test_a_tour_while_holding_something_presents_without_gestures() -> None:
    p = plan("tour([station_1, station_2])", lab(held="cup"))
    assert "gesture" not in [s.skill for s in p.primitives()]
    present = next(n for n in p.root.walk() if n.call == "present(station_1)")
    assert present.method == "scripted"
    assert str(present.rejected[0].reason).startswith("held == null is false (held='cup')")


def test_greet_waves_when_the_hands_are_free_and_only_speaks_otherwise() -> None:
    assert steps(plan("greet")) == ["gesture play=high wave", "speak text=Hello! I am Stuart, nice to meet you."]
    assert steps(plan("greet", lab(held="cup"))) == [
        "speak text=Hello! I am Stuart. I would wave, but my hands are full."]


def test_go_and_say_walks_then_speaks() -> None:
    assert steps(plan("go_and_say(kitchen, 'Lunch is ready')")) == [
        "speak text=Going to the kitchen", "navigate marker=kitchen", "speak text=Lunch is ready"]
    assert steps(plan("go_and_say(entrance, 'Hi')"))[1:] == ["speak text=Hi"]


def test_a_compound_utterance_runs_its_intents_in_order_each_acknowledged() -> None:
    p = plan("do_all([gesture(wave), navigate_to_marker(kitchen), pick_up(apple), navigate_to_marker(workbench)])")
    acks = [s.skill_args["text"] for s in p.primitives() if s.ack]
    assert acks == ["Doing a wave", "Navigating to the kitchen", "Picking up the apple", "Navigating to the workbench"]
    assert p.state["held"] == "apple" and p.state["at"] == "workbench"


def test_a_later_intent_that_cannot_follow_an_earlier_one_is_explained() -> None:
    assert failure_of("pick_up(apple); gesture(moonwalk)") == (
        "no plan for pick_up(apple), gesture(moonwalk):\n"
        "  pick_up(apple): no method works\n"
        "    ✗ already_holding: held == obj is false (held=null, obj='apple')\n"
        "    ✗ known: worked, then a later task failed:\n"
        "      play_holding(moonwalk): precondition not met: hook known_gesture(name='moonwalk') returned false\n"
        "    ✗ search_first: obj not in objects is false "
        "(obj='apple', objects={bottle, apple, cup, screwdriver, book})\n"
        "    ✗ hands_full: held != null is false (held=null)")


# -- impossible requests ---------------------------------------------------------------------------------
def test_an_unknown_place_fails_with_a_suggestion() -> None:
    assert (
        "    ✗ walk: place in markers is false (place='kitchn', markers={entrance, charging_dock, kitchen, bathroom, "
        "workbench, station_1, +5 more}) (did you mean 'kitchen'?)"
    ) in failure_of("navigate_to_marker(kitchn)").splitlines()
    assert "✗ known_location: place in markers is false (place='moon'" in failure_of("fetch(bottle, moon)")
    assert "visit(moon): no method applies" in failure_of("tour([station_1, moon])")


def test_an_unknown_object_with_nowhere_to_look_fails_with_the_reason() -> None:
    assert failure_of("find(unicorn)") == (
        "no plan for find(unicorn):\n"
        "  search(unicorn): no method applies\n"
        "    ✗ remembered: obj in objects is false (obj='unicorn', objects={bottle, apple, cup, screwdriver, book})\n"
        "    ✗ look_around: obj in detectable is false (obj='unicorn', detectable=['bottle', 'cup', 'apple', "
        "'banana', 'orange', 'book', +10 more])")
    assert "look_steps > 0 is false (look_steps=0)" in failure_of("fetch(orange, kitchen)", lab(look_steps=0))


def test_gestures_play_with_something_in_hand_and_need_a_known_name() -> None:
    plan = Planner(project_domain()).plan([TaskCall.parse("gesture(wave)")], lab(held="cup"))
    assert [(n.name, n.skill_args) for n in plan.primitives()][-1] == ("play_holding", {"play": "wave"})
    assert "hook known_gesture(name='moonwalk') returned false" in failure_of("gesture(moonwalk)")


def test_bring_needs_to_know_where_the_command_came_from() -> None:
    assert "speaker_at != null is false (speaker_at=null)" in failure_of("bring(cup)", lab(speaker_at=None))


# -- ready for the compiler -------------------------------------------------------------------------------
@pytest.mark.parametrize("task", [
    "navigate_to_marker(kitchen)", "move_relative(1, 0, 0.5)", "turn_by_angle(-0.5)", "turn_around", "pick_up(book)",
    "gesture(clap)", "stop", "find(orange)", "fetch(keys, workbench)", "fetch(screwdriver, kitchen)", "bring(apple)",
    "tour", "greet", "go_and_say(bathroom, 'Hello')",
])
def test_every_step_is_an_existing_leaf_with_valid_parameters(task: str) -> None:
    state = lab(objects={**lab()["objects"], "keys": "kitchen"})
    for step in plan(task, state).primitives():
        assert step.skill in LEAVES, step.call
        assert check_skill_args(step.skill, step.skill_args) is None, step.call
        for key, value in step.skill_args.items():
            param = LEAVES[step.skill].param(key)
            if isinstance(value, str) and value.startswith("$"):
                assert param.type in ("number", "angle"), step.call       # a run-time reference for a number
            elif param.type in ("number", "angle", "seconds"):
                assert isinstance(value, (int, float)), step.call
            elif param.type in ("string", "marker", "gesture", "choice"):
                assert isinstance(value, str), step.call


def test_task_intent_objects_plan_like_their_mappings() -> None:
    from dataclasses import dataclass

    @dataclass
    class TaskIntent:  # the shape the utterance parser produces
        action: str
        target: str | None = None
        x: float | None = None
        y: float | None = None
        yaw: float | None = None
        raw_text: str = ""

    intents = [TaskIntent("find", "cup", raw_text="hey stuart find the cup"), TaskIntent("turn_by_angle", yaw=-0.5)]
    calls_from_intents = project_domain().calls_from_intents
    assert steps(plan(calls_from_intents(intents))) == steps(plan("find(cup); turn_by_angle(-0.5)"))
    assert steps(plan(calls_from_intents(intents[:1]))) == steps(plan("find(cup)"))
