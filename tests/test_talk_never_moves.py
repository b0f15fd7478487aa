"""Talk never moves the robot: a sentence is a command only when it has the form of one.

Properties over generated sentences (every frame x every command phrase), not lists of examples:
whatever verbs a question, a statement, a tag question, a gerund subject, a report, a memory, a
conditional or a retraction holds, it gives no intent that moves the robot.
"""

from __future__ import annotations

from typing import Any

from hypothesis import given, settings
from hypothesis import strategies as st

from stuart_bt.language.parse import Parser

PARSER = Parser()

COMMANDS = ["go to the kitchen", "walk to the charging dock", "turn left", "turn right ninety degrees",
            "move forward two metres", "pick up the bottle", "grab the apple", "find the cup", "look for the book",
            "wave", "head over to station three", "spin around", "back up a metre", "fetch the screwdriver"]

GERUNDS = {"go": "going", "walk": "walking", "turn": "turning", "move": "moving", "pick": "picking",
           "grab": "grabbing", "find": "finding", "look": "looking", "wave": "waving", "head": "heading",
           "spin": "spinning", "back": "backing", "fetch": "fetching"}


def gerund(command: str) -> str:
    verb, _, rest = command.partition(" ")
    return f"{GERUNDS[verb]} {rest}".strip()


# frames that make talk of a command phrase, whatever the phrase is
TALK = [
    lambda c: f"you can {c} on your own, right?",
    lambda c: f"you could {c} if you wanted, couldn't you?",
    lambda c: f"it would be silly to {c} now, wouldn't it?",
    lambda c: f"{gerund(c)} takes ages.",
    lambda c: f"{gerund(c)} would be silly here, wouldn't it?",
    lambda c: f"{gerund(c)} was fun this morning.",
    lambda c: f"she told you to {c}.",
    lambda c: f"yesterday you had to {c}.",
    lambda c: f"if you {c} you will be tired.",
    lambda c: f"do you want to {c}?",
    lambda c: f"why did you {c}?",
    lambda c: f"I think you should not {c}.",
    lambda c: f"{c}, just kidding.",
    lambda c: f"{c}, I'm joking.",
    lambda c: f"{c}? no, don't.",
    lambda c: f"{c}. no.",
    lambda c: f"{c}, forget it.",
    lambda c: f"remember when you tried to {c}?",
]


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.sampled_from(COMMANDS), st.sampled_from(range(len(TALK))))
def test_talk_about_a_command_never_gives_an_intent(command: str, frame: int) -> None:
    said = "Hey Stuart, " + TALK[frame](command)
    result = PARSER.parse(said)
    assert result.wake and result.intents == [], said


# a command with a tag word: a check that the robot heard, or a question about the plan?
PUT_AS_A_QUESTION = [lambda c: f"{c}, right?", lambda c: f"{c}, correct?", lambda c: f"so {c}, eh?"]


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.sampled_from(COMMANDS), st.sampled_from(range(len(PUT_AS_A_QUESTION))))
def test_a_command_put_as_a_question_is_asked_about_never_done_at_once(command: str, frame: int) -> None:
    said = "Hey Stuart, " + PUT_AS_A_QUESTION[frame](command)
    result = PARSER.parse(said)
    assert result.intents and [d.reason for d in result.doubt] == ["question"], said


@settings(max_examples=100, deadline=None, derandomize=True)
@given(st.sampled_from(COMMANDS))
def test_the_same_phrases_said_as_commands_do_move_it(command: str) -> None:
    result = PARSER.parse(f"Hey Stuart, {command}.")
    assert result.intents and not result.doubt, command


@settings(max_examples=100, deadline=None, derandomize=True)
@given(st.sampled_from(COMMANDS), st.sampled_from(["will you?", "won't you?", "would you?", "please."]))
def test_a_request_tag_after_a_command_keeps_it_a_command(command: str, tag: str) -> None:
    assert PARSER.parse(f"Hey Stuart, {command}, {tag}").intents, command


@settings(max_examples=100, deadline=None, derandomize=True)
@given(st.lists(st.sampled_from(COMMANDS), min_size=1, max_size=4),
       st.sampled_from([", oh no, stop!", ". Stop.", ", wait, no, stop.", ", you know what, just stop."]))
def test_a_stop_said_over_a_plan_cancels_all_of_it(commands: list[str], stop: str) -> None:
    said = "Hey Stuart, " + ", then ".join(commands) + stop
    assert [i.action for i in PARSER.parse(said).intents] == ["stop"], said


def test_a_stop_as_the_next_step_of_a_plan_stays_a_step() -> None:
    assert [i.action for i in PARSER.parse("Hey Stuart, go to the kitchen and then stop").intents] == [
        "navigate_to_marker", "stop"]
    assert [i.action for i in PARSER.parse("Hey Stuart, when you get to the kitchen, stop").intents] == [
        "navigate_to_marker", "stop"]


def test_a_stop_past_the_length_limit_still_wins() -> None:
    said = "Hey Stuart, " + "turn left and then " * 60 + "stop"
    result = PARSER.parse(said)
    assert [i.action for i in result.intents] == ["stop"] and result.coverage.unread


def test_a_correction_that_nothing_replaces_takes_the_command_back() -> None:
    assert PARSER.parse("Hey Stuart, go to the kitchen. No.").intents == []
    assert [i.target for i in PARSER.parse("Hey Stuart, go to the kitchen, no, the bathroom").intents] == ["bathroom"]
    assert [i.target for i in PARSER.parse("Hey Stuart, go to the kitchen. no need to hurry").intents] == ["kitchen"]


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.sampled_from(COMMANDS), st.sampled_from([
    lambda c: f"back when you first arrived, you could not {c}.",
    lambda c: f"why did the robot {c}? To {c}!",
    lambda c: f"could you {c}, actually, don't worry, I'll do it.",
    lambda c: f"{c}. Oh, no worries, forget it.",
]))
def test_memories_punchlines_and_never_minds_move_nothing(command: str, frame: Any) -> None:
    said = "Hey Stuart, " + frame(command)
    assert [i.action for i in PARSER.parse(said).intents if i.action != "stop"] == [], said  # a stop moves nothing


@settings(max_examples=100, deadline=None, derandomize=True)
@given(st.sampled_from(COMMANDS), st.sampled_from(range(len(TALK))),
       st.sampled_from([", stop", ", actually stop", " but stop right now please", ", just stop", ", oh stop"]))
def test_a_stop_said_after_talk_still_stops(command: str, frame: int, stop: str) -> None:
    talk = TALK[frame](command).rstrip(".?")
    got = PARSER.parse(f"Hey Stuart, {talk}{stop}.")
    assert [i.action for i in got.intents] == ["stop"], (talk, stop, got.intents)
