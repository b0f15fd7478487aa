"""Task proposals for requests the grammar misses: the proposal is checked like a parsed command,
offered in words, and runs only after a yes (tests/test_conversation_llama.py checks that the
real model's output is held to the schema)."""

from __future__ import annotations

import json
from typing import Any

import pytest

from stuart_bt.conversation.reply import CannedConversation
from stuart_bt.language import Parser
from stuart_bt.mission import proposals
from stuart_bt.mission.executor import MissionExecutor, MissionOptions


class ScriptedModel(CannedConversation):
    """A conversation backend whose 'model' answers with fixed JSON: what a model might propose,
    so the executor's side (checks, question, yes / no) is tested without sampling noise."""

    def __init__(self, answer: dict[str, Any] | str) -> None:
        super().__init__()
        self.answer = answer if isinstance(answer, str) else json.dumps(answer)
        self.prompts: list[list[dict[str, str]]] = []

    def propose(self, messages: list[dict[str, str]], schema: dict[str, Any]) -> str:
        self.prompts.append(messages)
        return self.answer


def run(answer: Any, *said: str) -> tuple[MissionExecutor, list[Any], ScriptedModel]:
    assert not Parser().parse(said[0]).intents, "the grammar understands this request: pick one it misses"
    model = ScriptedModel(answer)
    events: list[Any] = []
    with MissionExecutor(MissionOptions(speed=50.0, propose_tasks=True), conversation=model) as mx:
        mx.events.subscribe(events.append)
        for text in said:
            mx.submit(text)
            assert mx.wait_idle(30)
    return mx, events, model


def spoken(events: list[Any]) -> list[str]:
    return [e.data["args"]["text"] for e in events if e.kind == "command" and e.data.get("cmd") == "say"]


KITCHEN = {"tasks": [{"action": "navigate_to_marker", "target": "the kitchen area"}]}


def test_a_missed_request_is_offered_and_runs_only_after_yes():
    mx, events, model = run(KITCHEN, "Hey Stuart, I'd love it if you popped over to the kitchen", "yes please")

    assert spoken(events)[0] == "Shall I go to the kitchen? Say yes to go ahead."
    phases = [e.data["phase"] for e in events if e.kind == "proposal"]
    assert phases == ["offered", "confirmed"]
    assert [str(c) for c in mx.missions[0].calls] == ["navigate_to_marker(place=kitchen)"]
    assert mx.missions[0].status == "succeeded" and mx.world.last_marker == "kitchen"
    assert "kitchen" in model.prompts[0][0]["content"]  # the prompt names the places the robot knows


def test_no_declines_and_nothing_moves():
    mx, events, _ = run(KITCHEN, "Hey Stuart, I'd love it if you popped over to the kitchen", "no thanks")

    assert spoken(events) == ["Shall I go to the kitchen? Say yes to go ahead.", "OK, I won't."]
    assert not mx.missions and not [e for e in events if e.kind == "command" and e.data.get("family") == "loco"
                                    and e.data.get("cmd") not in ("stop", "shutdown")]


def test_something_else_said_drops_the_offer():
    mx, events, _ = run(KITCHEN, "Hey Stuart, I'd love it if you popped over to the kitchen", "Hey Stuart, wave",
                        "yes")

    assert [e.data["phase"] for e in events if e.kind == "proposal"] == ["offered", "dropped"]
    assert [str(c) for m in mx.missions for c in m.calls] == ["gesture(name=wave)"]  # the yes ran nothing


@pytest.mark.parametrize("answer", [
    {"tasks": [{"action": "navigate_to_marker", "target": "the moon"}]},  # no such place
    {"tasks": [{"action": "pick_up", "target": "unicorn"}]},  # no such object
    {"tasks": [{"action": "fly", "target": "kitchen"}]},  # not a domain task
    "{not json",
])
def test_a_proposal_that_does_not_check_out_gets_the_ordinary_reply(answer):
    mx, events, _ = run(answer, "Hey Stuart, I'd love it if you popped over somewhere nice")

    assert not [e for e in events if e.kind == "proposal"]
    assert [e.kind for e in events].count("reply") == 1 and not mx.missions


def test_questions_are_answered_never_proposed():
    _, events, model = run(KITCHEN, "Hey Stuart, how far is the kitchen?")
    assert not model.prompts and not [e for e in events if e.kind == "proposal"]


def test_the_schema_holds_the_domain_s_intent_tasks_and_describes_them():
    schema = proposals.schema()
    item = schema["properties"]["tasks"]["items"]
    assert item["properties"]["action"]["enum"] == list(proposals.ACTIONS)
    assert proposals.parse('{"tasks": [{"action": "turn_by_angle", "target": "", "yaw": 1e999}]}') is None
    intents = proposals.parse('{"tasks": [{"action": "gesture", "target": "Wave"}, {"action": "turn_around", '
                              '"target": ""}]}')
    assert intents is not None and proposals.describe(intents) == "do a wave, then turn around"
