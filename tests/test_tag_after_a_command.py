"""A tag word after a command ("head to the printers now, right?") may check that the robot
heard or ask about the plan: the command is read (the tag is no step) and the robot asks before
it acts; "yeah?" only softens a command (every writer of the held-out batches meant it so); after
a statement a tag makes it a question, talk ("turning left takes you to the kitchen, right?")."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser


@pytest.fixture(scope="module")
def parser() -> Parser:
    return Parser()


@pytest.mark.parametrize("text,want", [
    ("Stuart, walk to the workbench now, correct?", [("navigate_to_marker", "workbench")]),
    ("Stuart, clap for the kids, eh?", [("gesture", "clap")]),
    ("Stuart, just turn left, right?", [("turn_by_angle", "")]),  # one turn: the tag is no direction
])
def test_a_tag_word_after_a_command_is_read_and_asked_about(parser, text, want):
    result = parser.parse(text)
    assert [(i.action, i.target) for i in result.intents] == want
    assert [d.reason for d in result.doubt] == ["question"]


@pytest.mark.parametrize("text", [
    "Stuart, turning right at the door takes you to the bathroom, right?",
    "Stuart, you walk to the workbench every morning, yeah?",
    "Stuart, go to the kitchen is what she said, right?",
    "Stuart, walking backwards is hard for you, isn't it?",
])
def test_a_tag_after_a_statement_makes_it_talk(parser, text):
    assert parser.parse(text).intents == []


def test_okay_after_a_command_asks_nothing(parser):
    result = parser.parse("Stuart, go to the bathroom, okay?")
    assert [(i.action, i.target) for i in result.intents] == [("navigate_to_marker", "bathroom")]
    assert result.doubt == []


@pytest.mark.parametrize("text,want", [
    ("Stuart, walk to the workbench now, yeah?", [("navigate_to_marker", "workbench")]),
    ("Stuart buddy, pick up the cup, yeah?", [("pick_up", "cup")]),
    ("Stuart, find the screwdriver for me, like, yeah?", [("find", "screwdriver")]),
])
def test_yeah_after_a_command_only_softens_it(parser, text, want):
    result = parser.parse(text)
    assert [(i.action, i.target) for i in result.intents] == want and result.doubt == []
