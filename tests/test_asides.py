"""Parts of an utterance said to someone else in the room are no commands to the robot; a part
said to the robot, even in the middle of talk with others, is (stuart_bt.language.asides)."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser


@pytest.fixture(scope="module")
def parser() -> Parser:
    return Parser()


def did(parser: Parser, text: str) -> list[tuple[str, str]]:
    return [(i.action, i.target) for i in parser.parse(text).intents]


def test_a_sentence_to_someone_else_after_a_command_adds_nothing_to_it(parser):
    text = "Stuart, go to the workbench and pick up the cup. Maria, could you hold the door?"
    assert did(parser, text) == [("navigate_to_marker", "workbench"), ("pick_up", "cup")]
    assert parser.parse(text).doubt == []


def test_the_robot_named_again_after_someone_else_is_addressed_gets_what_follows(parser):
    text = "Stuart - Priya, watch your feet - Stuart, turn left."
    assert did(parser, text) == [("turn_by_angle", "")]


def test_the_robot_named_in_the_middle_wakes_it_for_what_follows_only(parser):
    result = parser.parse("Tom, fetch the ladder - Stuart, freeze right there, please.")
    assert result.wake and did(parser, result.utterance) == [("stop", "")]
    assert not parser.parse("Tom, fetch the ladder and go to the kitchen.").wake


def test_a_place_said_as_an_order_right_after_the_wake_phrase_is_still_an_order(parser):
    assert did(parser, "Stuart, kitchen, now") == [("navigate_to_marker", "kitchen")]
    assert did(parser, "Stuart, Kitchen, go!") == [("navigate_to_marker", "kitchen")]


def test_words_that_open_sentences_are_no_ones_name(parser):
    for text in ("Stuart, go to the kitchen. Right, then wave.", "Stuart, go to the kitchen. Please, wave."):
        assert did(parser, text) == [("navigate_to_marker", "kitchen"), ("gesture", "wave")], text


def test_text_with_no_vocative_keeps_every_word_for_the_grammar(parser):
    text = "stuart go to the kitchen sam can you wait here"
    assert parser.parse(text).command == text.removeprefix("stuart ")
    cut = "Stuart, go to the kitchen. Sam, can you wait here?"
    assert parser.parse(cut).command == "go to the kitchen"


def test_a_group_called_after_a_command_is_someone_else(parser):
    assert did(parser, "Stuart, walk to the drone cage - everyone, follow him please.") == [
        ("navigate_to_marker", "drone cage")]
    text = "Stuart, go to the entrance - watch your step, folks - thanks."
    assert did(parser, text) == [("navigate_to_marker", "entrance")] and parser.parse(text).doubt == []


def test_the_robot_named_after_thanks_with_no_pause_gets_what_follows(parser):
    text = "stella can you get the lights thanks stuart go to the robot arms"
    assert did(parser, text) == [("navigate_to_marker", "robot arms")]
    assert did(parser, "ok so stuart go to the kitchen") == [("navigate_to_marker", "kitchen")]


@pytest.mark.parametrize("text", ["me and stuart go to the kitchen every day", "I told stuart go to the kitchen",
                                  "thanks stuart that was great", "ok so stuart is going to the kitchen now"])
def test_the_robot_named_inside_talk_with_no_pause_is_spoken_about(parser, text):
    assert did(parser, text) == []


@pytest.mark.parametrize("text,want", [
    ("Sorry to bother you, Stuart. Could you give us a wave?", [("gesture", "wave")]),
    ("It's photo time. Please, Stuart, put your hands up.", [("gesture", "hands up")]),
    ("Once you've found the cup, Stuart, pick it up.", [("find", "cup"), ("pick_up", "cup")]),
    ("Would you mind going to the entrance, Stuart? The delivery guy is there.", [("navigate_to_marker", "entrance")]),
    ("these are the students from the summer school stuart wave", [("gesture", "wave")]),
    ("the kids want a story stuart when you get to the reading room find the book",
     [("navigate_to_marker", "reading room"), ("find", "book")]),
])
def test_the_robot_named_inside_the_utterance_gets_what_is_said_to_it(parser, text, want):
    assert did(parser, text) == want


@pytest.mark.parametrize("text", ["I saw stuart go to the kitchen", "I think stuart should go to the kitchen",
                                  "yesterday stuart went to the kitchen", "Stuart's battery is low so go to the dock",
                                  "I was talking to Stuart, the robot, about the kitchen",
                                  "haha stuart you walk to the kitchen slower than my grandad"])
def test_the_robot_named_inside_talk_about_it_is_not_woken(parser, text):
    assert did(parser, text) == []
