"""An amount said alone after a pause says how far the move or turn just asked for goes: "turn
left, ninety degrees" is one quarter turn, not two; said roughly ("like", "or so") it is the same."""

from __future__ import annotations

import math

import pytest

from stuart_bt.language.grammar import parse_command


def steps(text: str) -> list[tuple[str, float, float, float]]:
    return [(i.action, round(i.x, 3), round(i.y, 3), round(i.yaw, 3)) for i in parse_command(text)]


@pytest.mark.parametrize("text,want", [
    ("turn left, ninety degrees", [("turn_by_angle", 0, 0, round(math.pi / 2, 3))]),
    ("turn right, about 45", [("turn_by_angle", 0, 0, round(-math.pi / 4, 3))]),
    ("move forward, two metres", [("move_relative", 2, 0, 0)]),
    ("go back, like half a metre", [("move_relative", -0.5, 0, 0)]),
    ("move left, 30 centimetres", [("move_relative", 0, 0.3, 0)]),
    ("turn left, yeah, like ninety degrees or so", [("turn_by_angle", 0, 0, round(math.pi / 2, 3))]),
])
def test_an_amount_after_a_pause_says_how_far_the_step_before_goes(text, want):
    assert steps(text) == want


@pytest.mark.parametrize("text,count", [
    ("turn left, then ninety degrees", 2),        # "then": another step
    ("turn left 90 degrees, 45", 2),              # the first said its amount
    ("turn left, right 45", 2),                   # another direction: another step
    ("turn around, 90 degrees", 2),               # no amount to restate
])
def test_an_amount_that_cannot_restate_the_step_before_is_another_step(text, count):
    assert len(steps(text)) == count


def test_an_amount_said_roughly_is_no_choice_and_no_leftover():
    from stuart_bt.language.parse import Parser

    for text in ("Stuart, walk forward roughly two metres, give or take", "Stuart, turn left ninety degrees or so"):
        result = Parser().parse(text)
        assert len(result.intents) == 1 and result.doubt == [], text


def test_a_spin_said_more_than_once_is_whole_spins_and_too_many_are_asked_about():
    from stuart_bt.language.parse import Parser

    twice = Parser().parse("Stuart, spin right twice")
    assert [round(i.yaw, 3) for i in twice.intents] == [round(-4 * math.pi, 3)] and twice.doubt == []
    thrice = Parser().parse("Stuart, spin left three times")
    assert [round(i.yaw, 3) for i in thrice.intents] == [round(6 * math.pi, 3)] and thrice.doubt
    assert [round(i.yaw, 3) for i in Parser().parse("Stuart, turn left three times").intents] == [
        round(3 * math.pi / 2, 3)]  # a turn is a quarter turn each time


@pytest.mark.parametrize("text,want", [
    ("forward two metres then right ninety", [("move_relative", 2, 0, 0),
                                              ("turn_by_angle", 0, 0, round(-math.pi / 2, 3))]),
    ("forward one point five then left then forward one", [
        ("move_relative", 1.5, 0, 0), ("turn_by_angle", 0, 0, round(math.pi / 2, 3)), ("move_relative", 1, 0, 0)]),
    ("move forward two metres, then left one metre", [("move_relative", 2, 0, 0), ("move_relative", 0, 1, 0)]),
])
def test_a_side_said_after_a_move_with_no_distance_is_a_turn_and_a_forward_after_a_turn_a_move(text, want):
    assert steps(text) == want
