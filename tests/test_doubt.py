"""Doubt: every word accounted for, amounts the robot can do; otherwise the parse says why to ask."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser

PARSER = Parser()


def reasons(said: str) -> list[str]:
    return [d.reason for d in PARSER.parse("Hey Stuart, " + said).doubt]


@pytest.mark.parametrize("said", ["go to the kitchen", "pick up the apple on the counter please",
                                  "could you bring me a bottle of water, mate", "turn left ninety degrees now",
                                  "stop"])
def test_a_clear_command_has_no_doubt(said: str) -> None:
    assert reasons(said) == []


@pytest.mark.parametrize("said", ["turn right at the door", "go to the kitchen and make me a sandwich",
                                  "go to the bathroom in twenty minutes", "move forward until you reach the wall"])
def test_content_words_no_clause_used_are_doubt(said: str) -> None:
    result = PARSER.parse("Hey Stuart, " + said)
    assert result.intents and "unused" in [d.reason for d in result.doubt] and result.coverage.unused


@pytest.mark.parametrize("said", ["move forward minus two metres", "walk forward 10000 metres",
                                  "turn left 5000 degrees", "back up negative three feet"])
def test_an_amount_the_robot_cannot_do_is_doubt(said: str) -> None:
    assert "amount" in reasons(said)


@pytest.mark.parametrize("said, leftover", [("head to the kitchen, mate", "mate"),
                                            ("pick up the apple and juggle it", "juggle it"),
                                            ("walk to the bathroom backwards", "bathroom backwards"),
                                            ("pick up whatever Dave left lying around", "whatever dave left lying")])
def test_leftover_words_never_become_targets(said: str, leftover: str) -> None:
    assert leftover not in [i.target for i in PARSER.parse("Hey Stuart, " + said).intents]


def test_coverage_sorts_every_word_of_the_command() -> None:
    result = PARSER.parse("Hey Stuart, I'm thirsty, could you bring me a bottle of water")
    cov = result.coverage
    assert "bottle" in cov.used and "thirsty" in cov.talk and cov.unused == ()
    assert result.to_dict()["coverage"]["talk"] == list(cov.talk)


@pytest.mark.parametrize("said", ["pick up the cup with your teeth", "hop to the workbench on one leg",
                                  "go to the kitchen and stay there until the professor arrives"])
def test_how_or_until_when_is_not_a_phrase_saying_which_so_it_is_doubt(said: str) -> None:
    assert "unused" in reasons(said)


def test_a_letter_said_long_is_the_letter_once() -> None:
    result = PARSER.parse("Hey Stuart, pick up the apple pleeease!")
    assert [i.target for i in result.intents] == ["apple"] and not result.doubt
    assert [i.action for i in PARSER.parse("Hey Stuart, stooooop").intents] == ["stop"]


def test_list_labels_are_not_targets() -> None:
    result = PARSER.parse("Hey Stuart, step one, go to station 2; step two, find the cup; step three, wave.")
    assert [(i.action, i.target) for i in result.intents] == [
        ("navigate_to_marker", "station 2"), ("find", "cup"), ("gesture", "wave")]
