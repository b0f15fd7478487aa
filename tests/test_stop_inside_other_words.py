"""A stop said among words that only colour a command, or after a long polite lead-in in talk,
is read, and wins: the robot stops, whatever was asked before it in the same breath."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser


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
