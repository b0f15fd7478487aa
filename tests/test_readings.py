"""Which reading of an utterance the robot acts on: the recogniser's best, unless that is no
clear command and a reading a hair less likely is one."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser
from stuart_bt.language.readings import READING_MARGIN, choose_reading, is_clear_command
from stuart_bt.language.resolve import Resolver
from stuart_bt.testing import lab_markers


@pytest.fixture(scope="module")
def lab() -> tuple[Parser, Resolver]:
    return Parser(), Resolver.from_files(lab_markers())


@pytest.mark.parametrize("text,clear", [
    ("Hey Stuart, go to the kitchen", True),
    ("Hey Stuart, stop.", True),
    ("head to it, go to the kitchen", False),         # not addressed to the robot
    ("Hey Stuart, go to the morning", False),         # a place nobody knows
    ("Hey Stuart, how are you?", False),              # talk
    ("go to the kitchen", False),
])
def test_a_clear_command_is_addressed_has_intents_and_resolves(lab, text, clear):
    assert is_clear_command(text, *lab) is clear


def test_the_best_reading_wins_when_it_is_a_clear_command(lab):
    readings = [("Hey Stuart, go to the kitchen", -0.2), ("Hey Stuart, go to the bathroom", -0.21)]
    assert choose_reading(readings, *lab) == 0


def test_a_command_a_hair_less_likely_than_a_near_miss_is_taken(lab):
    readings = [("head to it, go to the 3D printers", -0.15), ("hey Stuart, turn left", -0.155),
                ("hey Stuart, go to the 3D printers", -0.16)]
    assert choose_reading(readings, *lab) == 1, "the first clear command within the margin, in order"


def test_a_command_far_less_likely_than_the_best_reading_is_not_taken(lab):
    readings = [("head to it, go to the 3D printers", -0.2),
                ("hey Stuart, go to the 3D printers", -0.21 - READING_MARGIN)]
    assert choose_reading(readings, *lab) == 0


def test_talk_stays_talk_when_no_reading_is_a_clear_command(lab):
    readings = [("Hey Stuart, good morning", -0.3), ("hey Stuart, go to the morning", -0.31),
                ("Hey Stuart, good morning!", -0.32)]
    assert choose_reading(readings, *lab) == 0
    assert choose_reading([], *lab) == 0 and choose_reading([("hello", -0.1)], *lab) == 0


def test_two_clear_readings_that_ask_for_different_things_are_rivals():
    from stuart_bt.language.readings import rival_reading

    parser, resolver = Parser(), Resolver.from_files(lab_markers())
    readings = [("Hey Stuart, go to the kitchen.", -0.30), ("Hey Stuart, go to the bathroom.", -0.35),
                ("Hey Stuart, go to the kitchen!", -0.36)]
    assert rival_reading(readings, 0, parser, resolver) == 1
    assert rival_reading([readings[0], readings[2]], 0, parser, resolver) is None  # the same command twice
    assert rival_reading([readings[0], ("Hey Stuart, go to the bathroom.", -0.9)], 0, parser, resolver) is None


def test_two_readings_naming_the_same_place_or_thing_differently_are_no_rivals(lab):
    from stuart_bt.language.readings import rival_reading

    place = [("hey Stuart, go to the Humanoid corner.", -0.2), ("hey Stuart, go to the Humanoids corner.", -0.25)]
    thing = [("hey Stuart, look for the screwdriver.", -0.2), ("hey Stuart, look for this crew driver.", -0.25)]
    assert rival_reading(place, 0, *lab) is None and rival_reading(thing, 0, *lab) is None
    other = [place[0], ("hey Stuart, go to the Humanoids corner and wave.", -0.25)]
    assert rival_reading(other, 0, *lab) == 1  # the same place, but more asked of it


def test_a_reading_that_greets_someone_else_by_name_makes_the_robot_ask_who_was_meant(lab):
    from stuart_bt.language.readings import ADDRESSEE_MARGIN, rival_reading

    said = [("hey Stuart, pick up the book.", -0.28), ("hey Sarah, pick up the book.", -0.45)]
    assert rival_reading(said, 0, *lab) == 1  # further behind than a command rival may be, still asked
    far = [said[0], ("hey Sarah, pick up the book.", -0.29 - ADDRESSEE_MARGIN)]
    assert rival_reading(far, 0, *lab) is None
    unknown = [("hey Stuart, let's pick up the remote.", -0.43), ("hey Sarah, let's pick up the remote.", -0.56)]
    assert rival_reading(unknown, 0, *lab) == 1  # a thing the robot would ask about: still, who was it said to?
    unsure = [said[0], ("hey, Stuart, pick up the book.", -0.3), ("hey sir, pick up the book.", -0.31)]
    assert rival_reading(unsure, 0, *lab) is None  # the robot's name again, and no name at all


def test_a_reading_that_only_stops_the_robot_is_acted_on_further_behind_than_a_task(lab):
    from stuart_bt.language.readings import STOP_MARGIN

    heard = [("do it, stop.", -0.46), ("screw there, stop.", -0.57), ("Stewart, stop.", -0.64)]
    assert choose_reading(heard, *lab) == 2  # 0.18 behind: too far for a task, near enough to stop
    far = [heard[0], ("Stewart, stop.", -0.47 - STOP_MARGIN)]
    assert choose_reading(far, *lab) == 0


def test_a_stop_with_a_task_after_it_is_held_to_the_margin_of_a_task(lab):
    heard = [("do it, stop.", -0.46), ("Stewart, stop and go to the kitchen.", -0.64)]
    assert choose_reading(heard, *lab) == 0  # the task would move the robot: not on a reading this far behind


def test_talk_about_stopping_is_no_stop(lab):
    heard = [("the bus stop is outside.", -0.3), ("the bus stops outside.", -0.4), ("Stuart, the bus stop.", -0.5)]
    assert choose_reading(heard, *lab) == 0
