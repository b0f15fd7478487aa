"""What every conversation backend is: ``reply(text, context) -> Reply``. The mission executor
depends on this interface only; the backends (canned, llama.cpp, an OpenAI-compatible server)
implement it."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Protocol


@dataclass
class Reply:
    """What the robot answers to conversation: a sentence, and gestures to play with it."""

    text: str
    gestures: list[str] = field(default_factory=list)


class Conversation(Protocol):
    """The conversation side (a language model later). ``reply`` may be slow: the mission
    executor calls it off the tick thread and speaks the reply when it comes. ``context`` holds
    what the robot knows right now (``held``, ``at``, ``busy``, ``mission``)."""

    def reply(self, text: str, context: dict[str, Any]) -> Reply: ...


class CannedConversation:
    """The ``none`` backend: one polite sentence that says what the robot can do."""

    name = "none"

    def reply(self, text: str, context: dict[str, Any]) -> Reply:
        return Reply("Sorry, I can only follow commands for now, like go to the kitchen or pick up the bottle.")
