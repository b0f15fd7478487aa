"""A command that hangs on a condition said before it ("if you see the kids, wave at them") is
not done: the robot cannot wait for the condition. A stop needs none; a polite "if" ("if you
don't mind, ...") is no condition; the next sentence is not under it."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser

PARSER = Parser()


def actions(text: str) -> list[str]:
    return [i.action for i in PARSER.parse(text).intents]


@pytest.mark.parametrize("text", [
    "Stuart, if you see the kids, wave at them.",
    "Stuart, if you get lost, go back to the charging dock",
    "stuart if you find the cup pick it up and bring it here",
    "Stuart, if the visitors arrive, turn around and clap.",
])
def test_a_command_under_a_condition_is_not_done(text: str) -> None:
    assert actions(text) == []


def test_a_stop_under_a_condition_still_stops() -> None:
    assert actions("stuart if you're about to fall stop") == ["stop"]


@pytest.mark.parametrize("text", [
    "Stuart, if you don't mind, turn around",
    "stuart if you don't mind could you turn around",
    "hey stuart if it's not too much trouble could you turn around",
    "Stuart, if you could turn around",
])
def test_a_polite_if_is_no_condition(text: str) -> None:
    assert actions(text) == ["turn_around"]


def test_the_next_sentence_is_not_under_the_condition() -> None:
    assert actions("Stuart, if you see the kids, wave. Then go to the kitchen.") == ["navigate_to_marker"]
