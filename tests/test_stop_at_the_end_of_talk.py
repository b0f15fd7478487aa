"""A stop said at the end of talk wins, with or without a pause before it ("stuart you're going
way too far you were only meant to do half a metre halt"); an urgent stop after "and then" calls
the plan off rather than ending it; the stop verb inside talk ("I told him to stop", "the bus
stop") is no order."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser

PARSER = Parser()

TALK = [
    "stuart you're going way too far you were only meant to do half a metre",
    "Stuart, the visitors are still looking at the drone cage",
    "stuart I think the kitchen floor is wet",
    "Stuart, you are heading straight for the kids' school bags",
    "stuart the professor said you would go to the workbench after lunch",
]
ENDINGS = ["halt", "stop", "freeze", "stop right now", "halt right there", "stop for a second", "hold it",
           "stop right there for a second"]


def actions(text: str) -> list[str]:
    return [i.action for i in PARSER.parse(text).intents]


@pytest.mark.parametrize("talk", TALK)
@pytest.mark.parametrize("ending", ENDINGS)
def test_a_stop_after_talk_with_no_pause_wins(talk: str, ending: str) -> None:
    assert actions(f"{talk} {ending}") == ["stop"]


@pytest.mark.parametrize("talk", TALK)
def test_a_stop_after_talk_with_softening_words_and_a_place_to_stay_wins(talk: str) -> None:
    assert actions(f"{talk}, but honestly, just halt right there for a second.") == ["stop"]


@pytest.mark.parametrize("text", [
    "Stuart, I told him to stop",
    "Stuart, we waited at the bus stop",
    "stuart why did you stop",
    "Stuart, the last stop was the drone cage",
    "Stuart, the printers came to a halt",
    "stuart why would you ever halt",
])
def test_the_stop_verb_inside_talk_is_no_order(text: str) -> None:
    assert actions(text) == []


def test_an_urgent_stop_after_and_then_calls_the_plan_off() -> None:
    said = "ok stuart go to station six and find the book and then um stop everything right now"
    assert actions(said) == ["stop"]
    assert actions("Hey Stuart, go to the kitchen and then stop immediately") == ["stop"]


def test_a_plain_stop_after_and_then_stays_the_last_step() -> None:
    assert actions("Hey Stuart, go to the kitchen and then stop") == ["navigate_to_marker", "stop"]


@pytest.mark.parametrize("text", [
    "stuart i was going to ask you to find the apple but first stop because your arm is making a weird noise",
    "stuart the kids are right behind you so please stop moving and stay where you are",
    "ok stuart move forward two metres and then turn around and then halt okay",
    "okay stuart so we're going to head over to the drone cage next and then maybe the reading room no stop stop "
    "there's a kid right in front of you",
    "Stuart, everyone's following you to the 3D printers, which is great, but stop for a second so the group can "
    "catch up.",
    "ok stuart um we said move forward two metres but stop you're way too close to the table",
])
def test_a_stop_after_a_lead_in_or_a_word_of_alarm_after_a_plan_wins(text: str) -> None:
    assert actions(text) == ["stop"]
