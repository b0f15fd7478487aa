"""The chat-template messages for one conversational turn, the same for every backend.

The original system built its prompt from a persona, a lab-knowledge YAML, the robot's current
detections *only when asked about what it sees* (so a small model is not distracted by a list
of objects when asked about opening hours) and the last 20 messages. This module does exactly
that and nothing else, so it can be tested without a model.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from functools import lru_cache
from importlib.resources import files
from pathlib import Path
from typing import Any

import yaml

HISTORY_LIMIT = 20  # messages (user + assistant), as in the original system

PERSONA = (
    "You are Stuart, a friendly Unitree G1 humanoid robot and tour guide in a robotics lab. "
    "Your replies are spoken aloud: answer in one or two short sentences, plain words, no lists "
    "or markdown. Only state facts about the lab from the lab knowledge below; if you do not "
    "know, say so. When the reply is social (a greeting, thanks, goodbye, a compliment or small "
    "talk) you may add one gesture tag such as [wave], [high five] or [clap]."
)

_VISION = re.compile(
    r"\b(?:what(?:'s| is| do you| can you)?\s+(?:do you\s+)?(?:see|seeing|in front of you|around you|"
    r"over there|near you)|can you see|do you see|are you seeing|look around|looking at|"
    r"what(?:'s| is) (?:there|here)|in front of you|around you|anything (?:near|around)|"
    r"see any|spot any|notice any|what objects)\b",
    re.IGNORECASE,
)


def is_vision_question(text: str) -> bool:
    """Whether ``text`` asks about what the robot sees (keyword rules, like the original)."""
    return bool(_VISION.search(text))


@lru_cache(maxsize=4)
def load_knowledge(path: str | None = None) -> dict[str, Any]:
    """tasks/lab_knowledge.yaml (or ``path``), parsed once per process."""
    source = Path(path) if path else files("stuart_bt.tasks").joinpath("lab_knowledge.yaml")
    return yaml.safe_load(source.read_text(encoding="utf-8")) or {}


def knowledge_text(knowledge: Mapping[str, Any]) -> str:
    """The knowledge as short plain lines: small models follow prose better than YAML."""
    lines: list[str] = []
    lab = knowledge.get("lab") or {}
    if lab:
        lines.append(f"Lab: {lab.get('description', '')} {lab.get('hours', '')}".strip())
    robot = knowledge.get("robot") or {}
    if robot:
        lines.append(f"You: {robot.get('model', '')}; senses: {robot.get('senses', '')}; "
                     f"you can {robot.get('can', '')}.")
    for key, title in (("stations", "Tour stations"), ("places", "Places")):
        items = knowledge.get(key) or []
        if items:
            lines.append(f"{title}: " + " ".join(f"{i['name']}: {i['about']}" for i in items))
    people = knowledge.get("people") or []
    if people:
        lines.append("People: " + "; ".join(f"{p['name']}, {p['role']}" for p in people) + ".")
    robots = knowledge.get("robots") or []
    if robots:
        lines.append("Robots: " + "; ".join(f"{r['name']} ({r['kind']}): {r['job']}" for r in robots) + ".")
    return "\n".join(lines)


def vision_text(detections: Iterable[Any]) -> str:
    """Detections (strings, or dicts with ``label`` and optional ``distance``/``where``) as one line."""
    parts: list[str] = []
    for d in detections:
        if isinstance(d, Mapping):
            label = str(d.get("label", "object"))
            extra = [f"{d['distance']:.1f} m away" if isinstance(d.get("distance"), (int, float)) else "",
                     str(d.get("where") or "")]
            extra = [e for e in extra if e]
            parts.append(f"{label} ({', '.join(extra)})" if extra else label)
        else:
            parts.append(str(d))
    if not parts:
        return "You see nothing in particular right now."
    return "You currently see: " + ", ".join(parts) + "."


def state_text(context: Mapping[str, Any]) -> str:
    """What the mission executor says about the robot right now (``at``, ``held``, ``busy``)."""
    bits = []
    if context.get("at"):
        bits.append(f"you are at the {str(context['at']).replace('_', ' ')}")
    if context.get("held"):
        bits.append(f"you are holding the {context['held']}")
    if context.get("busy"):
        bits.append("you are busy with a task")
    return ("Right now " + ", ".join(bits) + ".") if bits else ""


def trim_history(history: Sequence[Mapping[str, str]], limit: int = HISTORY_LIMIT) -> list[dict[str, str]]:
    """The last ``limit`` user/assistant messages (other roles are dropped)."""
    kept = [{"role": m["role"], "content": m["content"]} for m in history if m.get("role") in ("user", "assistant")]
    return kept[-limit:] if limit > 0 else []


def context_text(text: str, context: Mapping[str, Any]) -> str:
    """The turn's changing facts: the robot's state, and its detections for vision questions."""
    parts = [state_text(context)]
    if is_vision_question(text):
        parts.append(vision_text(context.get("detections") or []))
    return " ".join(p for p in parts if p)


def system_text(knowledge: Mapping[str, Any] | None = None, persona: str = PERSONA, extra_system: str = "") -> str:
    """Persona + lab knowledge (+ ``extra_system``): the same for every turn."""
    knowledge = load_knowledge() if knowledge is None else knowledge
    return "\n\n".join(p for p in (persona, "Lab knowledge:\n" + knowledge_text(knowledge), extra_system) if p)


def build_messages(text: str, context: Mapping[str, Any] | None = None,
                   history: Sequence[Mapping[str, str]] = (), *,
                   knowledge: Mapping[str, Any] | None = None, persona: str = PERSONA,
                   extra_system: str = "", history_limit: int = HISTORY_LIMIT) -> list[dict[str, str]]:
    """``[system, *last 20 messages, user]``.

    The system message (persona, knowledge) never changes, and the turn's context (state, and
    ``context["detections"]`` only when ``text`` is a vision question) opens the *last* user
    message: the prompt's long prefix then stays identical from turn to turn, so llama.cpp's
    prefix cache skips re-reading it (about 3 s of prompt processing for the tiny model on 2
    cores). History keeps the user's words without it.
    """
    extra = context_text(text, context or {})
    user = f"({extra})\n{text}" if extra else text
    return [{"role": "system", "content": system_text(knowledge, persona, extra_system)},
            *trim_history(history, history_limit),
            {"role": "user", "content": user}]


class History:
    """The running dialogue, capped at ``limit`` messages (older ones fall off). Not locked:
    each backend updates it under its own generation lock."""

    def __init__(self, limit: int = HISTORY_LIMIT) -> None:
        self.limit = limit
        self._messages: list[dict[str, str]] = []

    def add(self, user: str, assistant: str) -> None:
        self._messages += [{"role": "user", "content": user}, {"role": "assistant", "content": assistant}]
        del self._messages[:-self.limit]

    def clear(self) -> None:
        self._messages.clear()

    @property
    def messages(self) -> list[dict[str, str]]:
        return list(self._messages)

    def __len__(self) -> int:
        return len(self._messages)
