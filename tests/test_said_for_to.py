"""Words said for "to" after a verb of going ("go at the kitchen", "please to go at station 2",
"go until the entrance", as speakers of other languages say them) name where to go; the same
words after other verbs keep their own sense ("wait until the visitors arrive")."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser


@pytest.fixture(scope="module")
def parser() -> Parser:
    return Parser()


@pytest.mark.parametrize("text,place", [
    ("Stuart, please to go at station 4", "station 4"),
    ("Stuart, go at the workbench please", "workbench"),
    ("stuart walk until the entrance", "entrance"),
    ("Stuart, come in the kitchen", "kitchen"),
])
def test_a_word_said_for_to_after_a_verb_of_going_names_the_place(parser, text, place):
    result = parser.parse(text)
    assert [(i.action, i.target) for i in result.intents] == [("navigate_to_marker", place)]
    assert result.doubt == []


def test_until_after_another_verb_is_a_condition_the_robot_asks_about(parser):
    result = parser.parse("Stuart, go to the kitchen and wait until the visitors arrive")
    assert [i.action for i in result.intents] == ["navigate_to_marker", "stop"] and result.doubt
