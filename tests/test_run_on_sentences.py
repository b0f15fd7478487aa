"""Sentences run together with no pause written, as recognisers write them: a statement after a
command is talk, not part of its target; a stop is a stop even when a new sentence follows it;
someone named with a verb after them is talked about, not a place."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser


@pytest.fixture(scope="module")
def parser() -> Parser:
    return Parser()


def read(parser: Parser, text: str) -> tuple[list[tuple[str, str]], bool]:
    result = parser.parse(text)
    return [(i.action, i.target) for i in result.intents], bool(result.doubt)


@pytest.mark.parametrize("text,want", [
    ("stuart pick up the bottle the children want to look at it", ("pick_up", "bottle")),
    ("stuart go to the entrance they are waiting for you", ("navigate_to_marker", "entrance")),
    ("stuart go to the kitchen we are running late", ("navigate_to_marker", "kitchen")),
    ("Stuart, find the book, Priya is filming this", ("find", "book")),
])
def test_a_statement_run_on_after_a_command_is_talk_and_no_part_of_its_target(parser, text, want):
    assert read(parser, text) == ([want], False)


@pytest.mark.parametrize("text", [
    "hey stuart stop you are going to hit the wall",
    "hey stuart no no freeze you will knock the cup over",
])
def test_a_stop_followed_by_a_new_sentence_with_no_pause_is_a_stop(parser, text):
    assert read(parser, text) == ([("stop", "")], False)


@pytest.mark.parametrize("text", [
    "Stuart, Maria said you'd go to the workbench and pick up the cup later.",
    "Stuart, Tom told me you went to the kitchen.",
    "Stuart, Jess is going to the kitchen.",
])
def test_someone_named_with_a_verb_after_them_is_talked_about(parser, text):
    assert read(parser, text) == ([], False)


def test_a_noun_phrase_ends_where_another_one_opens_but_not_after_of(parser):
    assert read(parser, "stuart give the man a bottle")[0] == []  # no "man a bottle" to pick up
    assert read(parser, "stuart pick up a bottle of the water") == ([("pick_up", "bottle")], False)  # which bottle


@pytest.mark.parametrize("text,want", [
    ("stuart when you get to station four put your hands up", [("navigate_to_marker", "station four"),
                                                               ("gesture", "hands up")]),
    ("stuart once you reach the kitchen pick up the apple", [("navigate_to_marker", "kitchen"), ("pick_up", "apple")]),
    ("stuart go to station 3 wave", [("navigate_to_marker", "station 3"), ("gesture", "wave")]),
])
def test_a_command_after_a_place_with_no_pause_written_is_the_next_step(parser, text, want):
    assert read(parser, text) == (want, False)


def test_like_said_inside_a_place_name_is_a_filler(parser):
    assert read(parser, "stuart um walk to the like drone cage you know") == ([("navigate_to_marker", "drone cage")],
                                                                            False)


def test_the_robots_name_said_again_before_a_stop_does_not_hide_it(parser):
    text = "Stuart, go to the drone cage and wave, oh Stuart stop right now."
    assert read(parser, text) == ([("stop", "")], False)
    text = "Stuart, while the kids are watching, walk to the kitchen, actually Stuart, halt."
    assert read(parser, text) == ([("stop", "")], False)


def test_nah_before_a_retraction_is_part_of_it(parser):
    assert read(parser, "stuart, grab the book nah never mind") == ([], False)
