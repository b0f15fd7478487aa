"""Task proposals: when the grammar finds no command in a woken request, a language model may
propose one, constrained to the domain's intent tasks, and the robot asks before doing it.

The model never moves the robot. Its output is held to a JSON schema (the intent task names as
an enum, typed fields), so it is always well formed; then the same resolver and domain checks as
for a parsed utterance decide whether the proposal can be planned at all. Only a proposal that
passes is spoken back ("Shall I go to the kitchen? Say yes to go ahead.") and it runs only after a
yes. Backends that can propose implement ``propose(messages, schema) -> str`` (the raw JSON);
the canned conversation cannot, so without a model there are no proposals.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterable, Sequence
from typing import Any, Protocol, runtime_checkable

from ..core.jsonfile import is_finite_number
from ..language import TaskIntent
from ..language.intents import ACTIONS

MAX_TASKS = 3

YES = re.compile(r"^\W*(?:yes|yeah|yep|sure|ok(?:ay)?|please do|do it|go ahead|confirm(?:ed)?|affirmative)"
                 r"(?:\W+(?:please|do it|go ahead|thanks|thank you|stuart))*\W*$", re.IGNORECASE)
NO = re.compile(r"^\W*(?:no|nope|don't|do not|cancel|never mind|forget it|negative)"
                r"(?:\W+(?:thanks|thank you|stuart|do not|don't))*\W*$", re.IGNORECASE)
_QUESTION = re.compile(r"^\W*(?:what|who|where|when|why|how|which|is|are|am|do|does|did|have|has|was|were|will)\b",
                       re.IGNORECASE)


@runtime_checkable
class Proposer(Protocol):
    """A conversation backend that can also answer with JSON held to a schema."""

    def propose(self, messages: list[dict[str, str]], schema: dict[str, Any]) -> str: ...


def schema(actions: Sequence[str] = ACTIONS) -> dict[str, Any]:
    """The JSON schema a proposal must follow: 1-3 TaskIntents whose action is a domain task."""
    intent = {
        "type": "object",
        "properties": {
            "action": {"type": "string", "enum": list(actions)},
            "target": {"type": "string"},
            "x": {"type": "number"},
            "y": {"type": "number"},
            "yaw": {"type": "number"},
        },
        "required": ["action", "target"],
    }
    return {"type": "object", "properties": {"tasks": {"type": "array", "items": intent, "minItems": 1,
                                                       "maxItems": MAX_TASKS}},
            "required": ["tasks"]}


def messages(request: str, places: Iterable[str], objects: Iterable[str],
             gestures: Iterable[str]) -> list[dict[str, str]]:
    """The prompt: what each task means, the names the robot knows, and the request."""
    system = (
        "You turn a request to a humanoid robot into robot tasks. Answer with JSON only. Tasks: "
        "navigate_to_marker (target: a place), move_relative (x metres forward, y metres left), "
        "turn_by_angle (yaw radians, left positive), turn_around, pick_up (target: an object), "
        "find (target: an object), gesture (target: a gesture), stop. "
        f"Places: {', '.join(places)}. Objects: {', '.join(objects)}. Gestures: {', '.join(gestures)}."
    )
    return [{"role": "system", "content": system}, {"role": "user", "content": request}]


def parse(raw: str, actions: Sequence[str] = ACTIONS) -> list[TaskIntent] | None:
    """The proposal's intents, or None when it is not a usable proposal (bad JSON, unknown task,
    non-finite numbers, too many tasks). ``raw_text`` marks them as proposed."""
    try:
        doc = json.loads(raw)
    except (TypeError, ValueError):
        return None
    tasks = doc.get("tasks") if isinstance(doc, dict) else None
    if not isinstance(tasks, list) or not 1 <= len(tasks) <= MAX_TASKS:
        return None
    out: list[TaskIntent] = []
    for task in tasks:
        if not isinstance(task, dict) or task.get("action") not in actions:
            return None
        numbers = {k: task.get(k, 0.0) for k in ("x", "y", "yaw")}
        if not all(is_finite_number(v) for v in numbers.values()):
            return None
        target = task.get("target", "")
        out.append(TaskIntent(task["action"], str(target).strip().lower() if isinstance(target, str) else "",
                              float(numbers["x"]), float(numbers["y"]), float(numbers["yaw"]), raw_text="(proposed)"))
    return out


def is_question(text: str) -> bool:
    """Questions are answered, never turned into tasks."""
    return text.rstrip().endswith("?") or bool(_QUESTION.match(text))


PHRASES = {"navigate_to_marker": "go to the {place}", "pick_up": "pick up the {target}",
           "find": "look for the {target}", "gesture": "do a {target}",
           "move_relative": "move {x:g} m forward and {y:g} m left",
           "turn_by_angle": "turn {degrees:.0f} degrees", "turn_around": "turn around", "stop": "stop"}


def describe(intents: Sequence[TaskIntent]) -> str:
    """The proposal in words, for the robot to ask: "go to the kitchen, then do a wave"."""
    return ", then ".join(
        PHRASES.get(i.action, i.action.replace("_", " ")).format(
            place=i.target.replace("_", " "), target=i.target, x=i.x, y=i.y, degrees=math.degrees(i.yaw))
        for i in intents)
