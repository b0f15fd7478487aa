"""Answers from facts first: the robot's state and the lab's knowledge, before any model."""

from __future__ import annotations

from typing import Any

import pytest

from stuart_bt.conversation.facts import FactAnswers, FactIndex, Situation, checked_reply, lab_facts
from stuart_bt.conversation.prompt import load_knowledge
from stuart_bt.mission.executor import MissionExecutor, MissionOptions

KNOWLEDGE = load_knowledge()
FACTS = FactAnswers(KNOWLEDGE)
HERE = Situation(at="kitchen", held="cup", doing="busy with: go to the workbench",
                 seen=["bottle", "apple"], places={"kitchen": "kitchen", "bathroom": "bathroom"},
                 objects={"screwdriver": "near the workbench"})
IDLE = Situation()


@pytest.mark.parametrize("question, expected", [
    ("what are you holding?", "I'm holding the cup."),
    ("what have you got in your hand?", "I'm holding the cup."),
    ("where are you right now?", "I'm at the kitchen."),
    ("what are you up to?", "I'm busy with: go to the workbench."),
    ("what do you see?", "I can see a bottle and an apple."),
    ("where is the screwdriver?", "The screwdriver is near the workbench, as far as I know."),
])
def test_questions_about_the_robot_are_answered_from_its_state(question: str, expected: str) -> None:
    assert FACTS.answer(question, HERE) == expected


def test_an_idle_empty_handed_robot_says_so_and_claims_nothing() -> None:
    assert FACTS.answer("what are you holding?", IDLE) == "I'm not holding anything."
    assert FACTS.answer("what are you doing?", IDLE).startswith("Nothing right now")
    assert FACTS.answer("what do you see?", IDLE) == "I don't see anything I recognise right now."
    assert FACTS.answer("where is the unicorn?", IDLE).startswith("I don't know where the unicorn is")


def test_a_place_on_the_map_is_offered_as_a_walk() -> None:
    assert "go to the bathroom" in FACTS.answer("where's the bathroom?", HERE)


@pytest.mark.parametrize("item", [*KNOWLEDGE["stations"], *KNOWLEDGE["places"]], ids=lambda i: i["name"])
def test_every_station_and_place_is_answered_from_its_own_fact(item: dict[str, Any]) -> None:
    said = FACTS.answer(f"what happens at the {item['name']}?", IDLE)
    assert said is not None and item["about"].split()[1].lower() in said.lower()


@pytest.mark.parametrize("person", KNOWLEDGE["people"], ids=lambda p: p["name"])
def test_who_questions_find_the_person_by_what_they_do(person: dict[str, Any]) -> None:
    duty = person["role"].split(",")[-1].strip()  # "works on the robot arms"
    assert FACTS.answer(f"who {duty}?", IDLE) == f"{person['name']} is the {person['role']}."


def test_chit_chat_and_requests_are_left_to_the_model() -> None:
    for said in ("do you like pizza?", "tell me a joke", "I'd love it if you popped over to the kitchen"):
        assert FACTS.answer(said, IDLE) is None, said


def test_every_fact_in_the_knowledge_file_can_be_found() -> None:
    facts = lab_facts(KNOWLEDGE)
    index = FactIndex(facts)
    for fact in facts:
        assert index.search(fact.topic, 1)[0][1] == fact


def test_a_model_reply_that_claims_a_held_object_loses_that_sentence() -> None:
    said = checked_reply("I'm holding a small box of tools. Happy to help!", IDLE)
    assert said == "Happy to help!"
    assert checked_reply("I'm holding the cup.", HERE) == "I'm holding the cup."
    assert len(checked_reply("Blah. " * 200, IDLE)) <= 240 and checked_reply("", IDLE)


def test_the_executor_answers_state_questions_from_facts_without_the_model() -> None:
    events: list[Any] = []
    with MissionExecutor(MissionOptions(speed=50.0)) as mx:
        mx.events.subscribe(events.append)
        for said in ("Hey Stuart, go to the kitchen", "Hey Stuart, where are you?", "Hey Stuart, what are you holding?",
                     "Hey Stuart, what happens in the drone cage?"):
            mx.submit(said)
            assert mx.wait_idle(30)
    replies = [(e.data["text"], e.data["source"]) for e in events if e.kind == "reply"]
    assert replies == [("I'm at the kitchen.", "facts"), ("I'm not holding anything.", "facts"),
                       ("The drone cage: a netted cage where flying robots practise without hurting anyone.", "facts")]
