"""A step said to come first ("..., but first turn around", "..., but turn around first") goes
before every step of its sentence, not only the last one; a sentence before it keeps its place."""

from __future__ import annotations

import pytest

from stuart_bt.language.grammar import parse_command


def plan(text: str) -> list[str]:
    return [i.action if not i.target else i.target for i in parse_command(text)]


@pytest.mark.parametrize("text", [
    "go to the drone cage and clap, but first turn around",
    "go to the drone cage and clap, but turn around first",
    "go to the drone cage and clap but turn around first please",
])
def test_the_step_said_first_goes_before_the_whole_plan(text):
    assert plan(text) == ["turn_around", "drone cage", "clap"]


def test_a_plan_in_an_earlier_sentence_keeps_its_place():
    assert plan("go to the kitchen. wave, but first turn around") == ["kitchen", "turn_around", "wave"]


def test_first_said_in_a_plain_step_changes_nothing():
    assert plan("go to the kitchen and wave first") == ["kitchen", "wave"]
