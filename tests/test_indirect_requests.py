"""Requests said indirectly: wanted somewhere ("I'd like you over at the dock"), permissions
("feel free to", "you may"), "show me how you ...", thanks before the name; and what is said
around a request that changes nothing ("if you please", "nice to meet you", "would ya")."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser


@pytest.fixture(scope="module")
def parser() -> Parser:
    return Parser()


@pytest.mark.parametrize("text,want", [
    ("Stuart, I'd like you over at the workbench.", ("navigate_to_marker", "workbench")),
    ("Stuart, we need you back in the kitchen", ("navigate_to_marker", "kitchen")),
    ("Stuart, feel free to grab the apple.", ("pick_up", "apple")),
    ("Stuart, you may head to the entrance now", ("navigate_to_marker", "entrance")),
    ("Stuart, show us how you clap", ("gesture", "clap")),
    ("Cheers Stuart, you can go back to the reading room now.", ("navigate_to_marker", "reading room")),
    ("Stuart, the workbench, if you please.", ("navigate_to_marker", "workbench")),
    ("Stuart, give me a high five, lovely to meet you.", ("gesture", "high five")),
    ("stuart find the book would ya", ("find", "book")),
])
def test_an_indirect_request_is_the_command_it_asks_for(parser, text, want):
    result = parser.parse(text)
    assert [(i.action, i.target) for i in result.intents] == [want] and result.doubt == [], text


def test_needing_the_robot_to_do_something_is_still_politeness(parser):
    assert [(i.action, i.target) for i in parser.parse("Stuart, I need you to wave").intents] == [("gesture", "wave")]


def test_one_more_metre_is_one_metre():
    result = Parser().parse("stuart move forward one more metre")
    assert [(i.action, i.x) for i in result.intents] == [("move_relative", 1.0)] and result.doubt == []
