"""A phrase of two or three words said twice with no pause is a speaker restarting, said once
("keep going keep going a bit more to the left"), as a word said twice is ("the the"); with a
pause it is two steps; a stop said twice stays, as it interrupts a plan."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser

PARSER = Parser()


def steps(text: str) -> list[tuple[str, str, float, float, float]]:
    result = PARSER.parse(text)
    assert result.doubt == [], text
    return [(i.action, i.target, round(i.x, 3), round(i.y, 3), round(i.yaw, 3)) for i in result.intents]


@pytest.mark.parametrize("once,twice", [
    ("stuart keep going a bit to the right", "stuart keep going keep going a bit to the right"),
    ("stuart keep going a bit to the right", "stuart keep going keep going keep going a bit to the right"),
    ("stuart go to the bathroom", "stuart go to go to the bathroom"),
    ("stuart pick up the cup", "stuart pick up the pick up the cup"),
    ("stuart walk forward two metres", "stuart walk forward walk forward two metres"),
])
def test_a_phrase_said_twice_with_no_pause_is_done_once(once: str, twice: str) -> None:
    assert steps(twice) == steps(once) != []


def test_a_turn_said_twice_with_a_pause_is_two_turns() -> None:
    assert [a for a, *_ in steps("stuart turn right, turn right")] == ["turn_by_angle", "turn_by_angle"]


def test_a_stop_phrase_said_twice_still_calls_the_plan_off() -> None:
    assert [a for a, *_ in steps("stuart go to the kitchen and hold it hold it")] == ["stop"]
