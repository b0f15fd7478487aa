"""A command asking for a way of doing it that the robot cannot choose (one hand, a gait it
lacks) is asked about, not done as if the words were not there; whom it is done for ("for the
camera") changes nothing and is not asked about."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser


@pytest.fixture(scope="module")
def parser() -> Parser:
    return Parser()


@pytest.mark.parametrize("text,want", [
    ("Stuart, clap with your left hand", ("gesture", "clap")),
    ("Stuart, wave with one hand", ("gesture", "wave")),
    ("stuart crawl over to the kitchen", ("navigate_to_marker", "kitchen")),
])
def test_a_way_the_robot_cannot_choose_is_asked_about(parser, text, want):
    result = parser.parse(text)
    assert [(i.action, i.target) for i in result.intents] == [want] and result.doubt


@pytest.mark.parametrize("text,want", [
    ("Stuart, wave with both hands", ("gesture", "wave")),
    ("Stuart, turn around for the camera", ("turn_around", "")),
    ("Stuart, could you clap for the children?", ("gesture", "clap")),
    ("Stuart, please high five this young lady", ("gesture", "high five")),
    ("Stuart, look for the cup", ("find", "cup")),
    ("hey stuart put your hands together for our speaker", ("gesture", "clap")),
    ("Stuart, shake hands with Dr. Okafor.", ("gesture", "shake hand")),
    ("Stuart, high five to the kids", ("gesture", "high five")),
])
def test_whom_it_is_for_changes_nothing(parser, text, want):
    result = parser.parse(text)
    assert [(i.action, i.target) for i in result.intents] == [want] and result.doubt == []


def test_a_time_after_for_is_still_asked_about(parser):
    assert parser.parse("Stuart, turn around for a minute").doubt


def test_a_time_of_day_after_whom_a_gesture_is_for_is_asked_about(parser):
    result = parser.parse("stuart wave to the visitors at half past two")
    assert [i.target for i in result.intents] == ["wave"] and result.doubt


def test_a_gesture_done_before_the_next_step_may_be_said_in_the_perfect(parser):
    result = parser.parse("Stuart, after you've shaken his hand, go back to the charging dock.")
    assert [(i.action, i.target) for i in result.intents] == [("gesture", "shake hand"),
                                                               ("navigate_to_marker", "charging dock")]


@pytest.mark.parametrize("text", ["Stuart, hop forward two metres.", "Stuart, go to the kitchen at half two.",
                                  "Stuart, go to the kitchen at three"])
def test_a_gait_it_lacks_or_a_clock_time_is_asked_about(parser, text):
    result = parser.parse(text)
    assert result.intents and result.doubt, text
