"""Talk said straight after a stop with no pause ("stop I need to reset the map before you go to
station five ...") is talk to the end of its sentence: the stop wins and nothing named in the talk
is done. After "and then" such talk is a warning that calls the plan off. A request ("stop, I want
you to ...") and the stop's own words ("stop what you're doing and ...") are not talk."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser

PARSER = Parser()

TALK = [
    "i need to check your arm before you go to the kitchen and pick up the cup",
    "we're filming the drone cage and you keep walking into the shot",
    "you're about to walk into the workbench",
    "there's a cable on the floor near the entrance",
    "they want you to find the book later",
]


def actions(text: str) -> list[str]:
    return [i.action for i in PARSER.parse(text).intents]


@pytest.mark.parametrize("talk", TALK)
@pytest.mark.parametrize("stop", ["stop", "halt", "stop right now", "freeze please"])
def test_talk_straight_after_a_stop_is_not_done(stop: str, talk: str) -> None:
    assert actions(f"hey stuart {stop} {talk}") == ["stop"]


@pytest.mark.parametrize("talk", TALK[1:4])
def test_a_warning_after_and_then_stop_calls_the_plan_off(talk: str) -> None:
    assert actions(f"stuart go to the reading room and find the book and then stop {talk}") == ["stop"]


def test_what_you_are_doing_is_the_stops_own_words() -> None:
    assert actions("stuart stop what you're doing and turn around") == ["stop", "turn_around"]


def test_a_stop_at_the_end_of_talk_after_a_pronoun_object_wins() -> None:
    assert actions("stuart you're heading for the bench with the soldering iron on it stop") == ["stop"]
    assert actions("stuart the kids are all standing right next to them halt") == ["stop"]
    assert actions("Stuart, the noise made it stop") == []


@pytest.mark.parametrize("asked", ["could you please stop there and wait for us", "can you stop for a second",
                                   "would you stop"])
def test_a_stop_asked_for_inside_talk_with_no_pause_wins(asked: str) -> None:
    assert actions(f"stuart um you're heading the wrong way towards the workbench {asked}") == ["stop"]


def test_asking_why_it_would_stop_is_no_stop() -> None:
    assert actions("stuart why would you stop at the kitchen") == []


@pytest.mark.parametrize("stop", ["no stop", "stop", "wait", "hold on", "freeze"])
@pytest.mark.parametrize("negated", ["don't pick up that cup", "do not go to the kitchen", "don't wave at them"])
def test_a_command_negated_right_after_a_stop_is_not_done(stop: str, negated: str) -> None:
    assert actions(f"hey stuart {stop} {negated} it's not ready yet") == ["stop"]


def test_a_stop_said_with_now_please_before_a_statement_wins() -> None:
    assert actions("stuart you're doing great with the tour but stop now please the floor is wet") == ["stop"]
