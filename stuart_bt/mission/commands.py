"""Utterance -> what the mission executor should do: a control command, tasks, or conversation.

The grammar (stuart_bt.language) knows the robot's eight intents; a running mission also needs
words *about* the mission, which the grammar treats as conversation or drops:

- **stop**: a ``stop`` intent first ("stop", "halt", "freeze", "never mind") halts everything and
  clears the queue; commands after it ("stop, go to the bathroom") start a new mission, so
  "cancel that and ..." / "forget that, ..." / "never mind, ..." replace the current mission;
- **continue**: "continue", "resume", "carry on", "keep going", "go on" resume a halted mission;
- **replace**: a command that says "instead" replaces the current mission instead of queueing;
- a ``stop`` later in a compound ("turn left and then stop") stays a task of the domain;
- **doubt** (``ParseResult.doubt``: unused words, an amount it cannot do) makes tasks a question
  the robot asks first ("Did you mean: ...?", :meth:`~.proposals.Offers.ask`); a stop never waits.

Utterances without the wake phrase are ignored (unless the parser does not require it); woken
utterances without a command are conversation.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from ..language import Parser, ParseResult, TaskIntent
from ..language.doubt import Doubt

IGNORE, STOP, CONTINUE, TASKS, CONVERSATION = "ignore", "stop", "continue", "tasks", "conversation"

_FILLER = r"(?:please|ok(?:ay)?|now|then|and|so|just|,|\s)*"
_CONTINUE = re.compile(rf"^{_FILLER}(?:continue|resume|carry on|keep going|go on|proceed|carry on with that)"
                       rf"(?:\s+(?:please|with (?:it|that|the mission|what you were doing)))?\W*$", re.IGNORECASE)
_INSTEAD_LEAD = re.compile(r"^\s*(?:no,?\s*)?(?:actually,?\s*)?instead,?\s*(?:of that,?\s*)?", re.IGNORECASE)
_INSTEAD_TAIL = re.compile(r",?\s*instead(?: of that)?\s*([.!?]*)\s*$", re.IGNORECASE)


@dataclass
class Command:
    """What one utterance asks of the mission executor.

    ``kind``: ignore | stop | continue | tasks | conversation. ``intents`` are the tasks to plan
    (for ``tasks``, and after a ``stop`` that goes on: "stop, go to the bathroom"). ``replace``:
    the tasks replace the current mission instead of waiting behind it.
    """

    kind: str
    parse: ParseResult
    intents: list[TaskIntent] = field(default_factory=list)
    replace: bool = False
    mission: int | None = None  # the id of the mission MissionExecutor.submit queued for it
    refused: str | None = None  # why its tasks were not queued: what the robot says instead

    @property
    def text(self) -> str:
        return self.parse.command or self.parse.utterance


def interpret(parser: Parser, utterance: str, woken: bool = False) -> Command:
    """Classify one utterance (never raises on text). ``woken``: the wake phrase was already heard
    (a channel that filtered it, e.g. the ROS bridge's ``/llm/input``), so it is not required."""
    wake = parser.wake_match(utterance)
    if not wake.woke and parser.require_wake and not woken:
        return Command(IGNORE, ParseResult(utterance))
    text = (wake.command if wake.woke else utterance).strip()
    stripped, instead = _strip_instead(text)
    read = parser.read_command(stripped) if stripped else None
    intents = read.intents if read is not None else []
    result = ParseResult(utterance, wake.woke, text, intents, not intents,
                         *((read.coverage, read.doubt) if read is not None else ()))
    if intents and intents[0].action == "stop":
        rest = [i for i in intents[1:] if i.action != "stop"]
        return Command(STOP, result, rest, replace=bool(rest))
    if intents:
        return Command(TASKS, result, intents, replace=instead)
    if _CONTINUE.match(stripped):
        return Command(CONTINUE, result)
    return Command(CONVERSATION, result)


def _strip_instead(text: str) -> tuple[str, bool]:
    """The command without "instead" (which the grammar does not know), and whether it was there."""
    lead = _INSTEAD_LEAD.match(text)
    if lead and lead.end() > 0 and "instead" in lead.group(0).lower():
        return text[lead.end():], True
    tail = _INSTEAD_TAIL.search(text)
    if tail:
        return text[:tail.start()] + tail.group(1), True
    return text, False


MAX_UTTERANCE = 2000  # characters: longer input is not speech, it is a mistake (ROS topics, the web console)


def clean_utterance(text: object) -> str | None:
    """Input text as the robot should see it (control characters made spaces, trimmed), or None
    when it is not speech at all (not a string, empty, only control characters, or far too long)."""
    if not isinstance(text, str) or len(text) > MAX_UTTERANCE:
        return None
    text = "".join(c if c.isprintable() else " " for c in text).strip()
    return text or None


MIN_CONFIDENCE = 0.35  # a recogniser's confidence below this (exp(-1.05)) is a guess, not a hearing


def hearing_doubts(command: Command, heard: Mapping[str, Any]) -> list[Doubt]:
    """Doubt that comes from the ears, not the words: the recogniser was unsure of what it heard
    (``confidence`` under MIN_CONFIDENCE), or heard two readings that ask for different things
    (``rival_reading``). Only tasks are in doubt: a stop always wins."""
    if not command.intents or all(i.action == "stop" for i in command.intents):
        return []
    found = []
    confidence = heard.get("confidence")
    if isinstance(confidence, (int, float)) and confidence < MIN_CONFIDENCE:
        found.append(Doubt("confidence", f"I was not sure I heard you right (confidence {confidence:.2f})"))
    if heard.get("rival_reading"):
        found.append(Doubt("readings", f"I also heard: {heard['rival_reading']}"))
    return found
