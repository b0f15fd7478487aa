"""A thing or place said instead of the last one, after an interjection and with no verb, replaces
it, across a sentence end too ("could you go to the kitchen? Oh, actually, the bathroom", "find the
bottle. Wait, not the bottle, the cup"); a statement after the interjection corrects nothing."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser

PARSER = Parser()


def did(text: str) -> list[tuple[str, str]]:
    return [(i.action, i.target) for i in PARSER.parse(text).intents]


@pytest.mark.parametrize("text,want", [
    ("Stuart, could you go to the kitchen? Oh, actually, the bathroom.", [("navigate_to_marker", "bathroom")]),
    ("Stuart, go to the kitchen, actually, the bathroom.", [("navigate_to_marker", "bathroom")]),
    ("Stuart, find the bottle. Wait, not the bottle, the cup.", [("find", "cup")]),
    ("stuart pick up the apple hmm actually the book", [("pick_up", "book")]),
])
def test_a_thing_said_instead_replaces_the_last_one(text, want):
    assert did(text) == want


def test_a_statement_after_actually_corrects_nothing():
    assert did("Stuart, go to the kitchen. Actually, the bathroom is closer.") == [("navigate_to_marker", "kitchen")]


def test_wait_with_nothing_said_instead_is_still_a_stop():
    assert did("Stuart, go to the kitchen. Wait.") == [("stop", "")]
