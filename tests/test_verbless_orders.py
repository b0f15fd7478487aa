"""Orders said with little or no verb: "off to the kitchen with you", "on to station five", "let's
go, kitchen", "give Lily a high five", "let go of my arm"; and a retraction said twice takes back
the request once, with no stop made of the second."""

from __future__ import annotations

import math

import pytest

from stuart_bt.language.parse import Parser


@pytest.fixture(scope="module")
def parser() -> Parser:
    return Parser()


def did(parser: Parser, text: str) -> list[tuple[str, str]]:
    result = parser.parse(text)
    assert result.doubt == [], (text, result.doubt)
    return [(i.action, i.target) for i in result.intents]


@pytest.mark.parametrize("text,place", [
    ("Stuart, off to the workbench with you.", "workbench"),
    ("Stuart, on to station two now", "station two"),
    ("Stuart, over to the entrance", "entrance"),
    ("Stuart, onwards to the reading room", "reading room"),
    ("Stuart, to the kitchen we go", "kitchen"),
    ("OK Stuart, let's go, bathroom, quick", "bathroom"),
])
def test_a_place_after_off_to_on_to_or_lets_go_is_going_there(parser, text, place):
    assert did(parser, text) == [("navigate_to_marker", place)]


def test_places_listed_after_first_and_then_are_a_plan(parser):
    assert did(parser, "Stuart, first the drone cage, then the reading room") == [
        ("navigate_to_marker", "drone cage"), ("navigate_to_marker", "reading room")]
    assert parser.parse("Stuart, first the drone cage").intents == []  # no plan said: an answer, maybe


@pytest.mark.parametrize("text", ["Stuart, go, now", "Stuart, let's go, the visitors are waiting"])
def test_a_pause_after_go_names_no_place_unless_a_place_follows(parser, text):
    assert parser.parse(text).intents == []


@pytest.mark.parametrize("text,gesture", [
    ("Stuart, give Omar a high five", "high five"), ("stuart give the old man a hug", "hug"),
    ("Stuart, show my little sister a wave", "wave"),
])
def test_a_gesture_given_to_someone_named_is_that_gesture(parser, text, gesture):
    assert did(parser, text) == [("gesture", gesture)]


def test_a_turn_given_is_a_turn():
    result = Parser().parse("Stuart, give us a quarter turn to the left")
    assert [(i.action, round(i.yaw, 3)) for i in result.intents] == [("turn_by_angle", round(math.pi / 2, 3))]


@pytest.mark.parametrize("text", ["Stuart, let go", "stuart could you let go of my hand", "Stuart, let go of me"])
def test_let_go_releases_the_arm(parser, text):
    assert did(parser, text) == [("gesture", "release arm")]


def test_a_retraction_said_twice_takes_the_request_back_with_no_stop(parser):
    assert parser.parse("Stuart, walk to the kitchen - oh, never mind, forget it.").intents == []
    assert did(parser, "Stuart, walk to the kitchen, never mind, forget it, turn left") == [("turn_by_angle", "")]


def test_a_place_named_before_its_command_after_a_question_thought_aloud_is_its_topic(parser):
    text = "Stuart, hmm, where should you go now... the workbench, yes, go to the workbench."
    assert did(parser, text) == [("navigate_to_marker", "workbench")]
    assert did(parser, "Stuart, where did I leave the book? the book, find it") == [("find", "book")]
    assert parser.parse("Stuart, what's that? The kitchen, I think.").intents == []


@pytest.mark.parametrize("text,want", [
    ("Stuart, off to the workbench, my friend.", [("navigate_to_marker", "workbench")]),
    ("Stuart, next stop: the reading room.", [("navigate_to_marker", "reading room")]),
    ("Stuart, go to the kitchen, then over to the entrance", [("navigate_to_marker", "kitchen"),
                                                              ("navigate_to_marker", "entrance")]),
    ("Stuart, take yourself over to the drone cage", [("navigate_to_marker", "drone cage")]),
])
def test_more_ways_to_send_the_robot_somewhere(parser, text, want):
    assert did(parser, text) == want


def test_next_stop_alone_or_after_a_pause_is_still_a_stop(parser):
    assert did(parser, "Stuart, next, stop!") == [("stop", "")]
    assert did(parser, "Stuart, next stop.") == [("stop", "")]
