"""A step asked for once more, said as a clause of its own ("turn left and again", "..., one more
time", "do it again"), is done twice; "do the same to the left" mirrors a turn or a sidestep;
"turn left again" is one turn, and "again" with nothing before it repeats nothing."""

from __future__ import annotations

import math

import pytest

from stuart_bt.language.parse import Parser

PARSER = Parser()


def steps(text: str) -> list[tuple[str, float, float, float]]:
    return [(i.action, round(i.x, 2), round(i.y, 2), round(i.yaw, 3)) for i in PARSER.parse(text).intents]


@pytest.mark.parametrize("text", [
    "Stuart, turn right 30 degrees. And again.",
    "stuart turn right thirty degrees and again",
    "Stuart, turn right 30 degrees, one more time.",
    "Stuart, turn right 30 degrees and then do it again.",
    "stuart turn right thirty degrees then once more",
])
def test_a_step_said_again_is_done_twice(text: str) -> None:
    turn = ("turn_by_angle", 0.0, 0.0, round(-math.radians(30), 3))
    assert steps(text) == [turn, turn]


def test_a_step_back_said_again_is_two_steps_back() -> None:
    assert steps("stuart take a step back and one more time") == [("move_relative", -0.5, 0.0, 0.0)] * 2


@pytest.mark.parametrize("text,first,second", [
    ("stuart move right two metres then do the same to the left", -2.0, 2.0),
    ("Stuart, sidestep left one metre, then the same to the right.", 1.0, -1.0),
    ("Stuart, step left half a metre and then do the same the other way.", 0.5, -0.5),
])
def test_the_same_to_the_other_side_mirrors_a_sidestep(text: str, first: float, second: float) -> None:
    assert steps(text) == [("move_relative", 0.0, first, 0.0), ("move_relative", 0.0, second, 0.0)]


def test_the_same_the_other_way_mirrors_a_turn() -> None:
    assert steps("Stuart, turn left ninety degrees, then do the same the other way.") == [
        ("turn_by_angle", 0.0, 0.0, 1.571), ("turn_by_angle", 0.0, 0.0, -1.571)]


def test_again_trailing_a_command_is_one_step() -> None:
    assert steps("stuart turn left again") == [("turn_by_angle", 0.0, 0.0, 1.571)]


def test_again_with_nothing_before_it_repeats_nothing() -> None:
    assert steps("Stuart, again") == [] and steps("Stuart, one more time please") == []


def test_a_side_for_a_walk_to_a_place_is_asked_about() -> None:
    result = PARSER.parse("Stuart, go to the kitchen and then do the same to the left")
    assert [i.action for i in result.intents] == ["navigate_to_marker"] and result.doubt
