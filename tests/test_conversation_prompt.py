"""The prompt builder: persona, lab knowledge, vision context only for vision questions, and
at most 20 messages of history (no model needed)."""

from __future__ import annotations

import json
import re
from importlib.resources import files
from pathlib import Path

import pytest

from stuart_bt.conversation.prompt import (
    HISTORY_LIMIT,
    PERSONA,
    History,
    build_messages,
    is_vision_question,
    load_knowledge,
    trim_history,
)

DETECTIONS = [{"label": "red bottle", "distance": 1.24}, "coffee cup"]
VISION = ["What do you see?", "what's in front of you", "Can you see a bottle?", "look around please",
          "Do you see anything near the kitchen?", "what are you looking at", "what is there"]
NOT_VISION = ["Hello!", "Where is the kitchen?", "Who is the lab director?", "Tell me about the drone cage",
              "What can you do?", "Thank you", "seaside holidays"]


def _all_text(messages: list[dict[str, str]]) -> str:
    return "\n".join(m["content"] for m in messages)


@pytest.mark.parametrize("text", VISION)
def test_vision_questions_get_the_detections(text: str) -> None:
    assert is_vision_question(text)
    messages = build_messages(text, {"detections": DETECTIONS})
    assert "red bottle (1.2 m away)" in messages[-1]["content"] and "coffee cup" in messages[-1]["content"]
    assert messages[-1]["content"].endswith(text)


@pytest.mark.parametrize("text", NOT_VISION)
def test_other_questions_do_not(text: str) -> None:
    assert not is_vision_question(text)
    text_all = _all_text(build_messages(text, {"detections": DETECTIONS}))
    assert "red bottle" not in text_all and "coffee cup" not in text_all and "You currently see" not in text_all


def test_vision_question_with_nothing_seen_says_so() -> None:
    assert "nothing in particular" in build_messages("what do you see", {})[-1]["content"]


def test_system_message_has_persona_and_knowledge_and_is_stable() -> None:
    a = build_messages("hello", {"at": "kitchen", "held": "bottle", "busy": True})
    b = build_messages("what do you see", {"detections": DETECTIONS})
    assert a[0]["role"] == "system" and a[0]["content"].startswith(PERSONA)
    assert a[0] == b[0]  # the changing context rides on the user message: the prefix cache stays valid
    for fact in ("Drone cage", "Dr. Maria Lopez", "Charging dock", "[wave]"):
        assert fact in a[0]["content"]
    assert "at the kitchen" in a[-1]["content"] and "holding the bottle" in a[-1]["content"]


def test_history_is_capped_at_20_messages() -> None:
    history = [{"role": "user" if i % 2 == 0 else "assistant", "content": f"m{i}"} for i in range(30)]
    messages = build_messages("latest", {}, history)
    assert len(messages) == 1 + HISTORY_LIMIT + 1 == 22
    assert [m["content"] for m in messages[1:-1]] == [f"m{i}" for i in range(10, 30)]
    assert messages[-1] == {"role": "user", "content": "latest"}
    assert trim_history([{"role": "system", "content": "x"}, *history[:2]]) == history[:2]


def test_history_object_keeps_the_last_20() -> None:
    history = History()
    for i in range(15):
        history.add(f"q{i}", f"a{i}")
    assert len(history) == 20 and history.messages[0] == {"role": "user", "content": "q5"}
    assert history.messages[-1] == {"role": "assistant", "content": "a14"}


def test_knowledge_agrees_with_markers_and_tour() -> None:
    knowledge = load_knowledge()
    markers = json.loads(files("stuart_bt.sim").joinpath("maps/lab_markers.json").read_text())["markers"]
    entries = knowledge["stations"] + knowledge["places"]
    assert {e["marker"] for e in entries} == set(markers)
    for e in entries:
        assert e["name"] == markers[e["marker"]]["display_name"]
    tour = (Path(__file__).resolve().parents[1] / "trees" / "lab_tour.yaml").read_text().lower()
    for e in knowledge["stations"]:  # each station's knowledge shares a key phrase with its tour script
        words = [w for w in re.findall(r"[a-z]+", e["about"].lower()) if len(w) > 5]
        assert sum(w in tour for w in words) >= 2, e
