"""Words said around a command that change nothing are neither targets nor doubt: the one
spoken to at the end of a target ("go find the apple buddy"), framing adverbs before the verb
("so basically just turn left")."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser


@pytest.mark.parametrize("text,want", [
    ("stuart go find the book buddy", [("find", "book")]),
    ("stuart go to the entrance mate", [("navigate_to_marker", "entrance")]),
    ("Stuart, so basically just wave and then clap, cheers.", [("gesture", "wave"), ("gesture", "clap")]),
    ("Stuart, honestly, turn around", [("turn_around", "")]),
])
def test_words_that_change_nothing_are_neither_targets_nor_doubt(text, want):
    result = Parser().parse(text)
    assert [(i.action, i.target) for i in result.intents] == want and result.doubt == [], text


def test_a_name_that_is_part_of_a_place_stays():
    assert [i.target for i in Parser().parse("stuart go to the charging dock").intents] == ["charging dock"]
