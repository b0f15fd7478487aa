"""A stop said among words that only colour a command, or after a long polite lead-in in talk,
is read, and wins: the robot stops, whatever was asked before it in the same breath."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from stuart_bt.language.parse import Parser

PARSER = Parser()


@pytest.fixture(scope="module")
def parser() -> Parser:
    return Parser()


@pytest.mark.parametrize("text", [
    "stuart clap for the children stop",
    "stuart walk to the workbench and wave halt",
    "stuart go to the kitchen and then maybe wave at everyone actually hold it",
    "stuart pick up the cup from the table freeze",
    "hey stuart we talked about going to the kitchen but right now I need you to just stop",
    "Stuart, I asked you to find the book, but could you please freeze",
])
def test_a_stop_said_in_the_same_breath_wins(parser, text):
    assert [i.action for i in parser.parse(text).intents] == ["stop"], text


def test_a_plain_command_is_not_cut_short(parser):
    assert [i.action for i in parser.parse("stuart wave at the visitors and then clap").intents] == [
        "gesture", "gesture"]


COMMANDS = ["walk to the charging dock", "turn right ninety degrees", "move forward two metres", "grab the apple",
            "look for the book", "head over to station three", "spin around", "fetch the screwdriver",
            "clap for the kids", "give us a high five", "go to the kitchen and pick up the cup",
            "when you get to the kitchen wave", "take two steps back", "do a little dance",
            "pick up the red cup from the table", "could you go to the bathroom please", "I want you to find the cup"]
STOPS = ["stop", "freeze", "halt", "actually stop", "oh no stop", "wait stop", "hold it", "actually hold it", "hold on",
         "please stop", "no no freeze", "stop right there", "just stop", "um stop", "hang on", "oh wait hold on"]


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.sampled_from(COMMANDS), st.sampled_from(STOPS), st.sampled_from(["stuart ", "Hey Stuart, "]))
def test_a_stop_said_after_any_command_with_no_pause_written_is_a_stop(command: str, stop: str, wake: str) -> None:
    said = f"{wake}{command} {stop}"
    assert [i.action for i in PARSER.parse(said).intents] == ["stop"], said
