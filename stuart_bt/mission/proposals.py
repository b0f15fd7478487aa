"""Task proposals: when the grammar finds no command in a woken request, a language model may
propose one, constrained to the domain's intent tasks, and the robot asks before doing it.

The model never moves the robot. Its output is held to a JSON schema (the intent task names as
an enum, typed fields), so it is always well formed; then the same resolver and domain checks as
for a parsed utterance decide whether the proposal can be planned at all. Only a proposal that
passes is spoken back ("Shall I go to the kitchen? Say yes to go ahead.") and it runs only after a
yes. Backends that can propose implement ``propose(messages, schema) -> str`` (the raw JSON);
the canned conversation cannot, so without a model there are no proposals. :class:`Offers` holds
the one proposal waiting for its yes or no.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

from ..core.jsonfile import is_finite_number
from ..language import TaskIntent
from ..language.intents import ACTIONS
from .queue import Say

if TYPE_CHECKING:
    from ..core.world import WorldState
    from .commands import Command
    from .queue import JobQueue

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


_NO_BUT = re.compile(r"^\W*(?:no|nope|not)\W+(?:i meant\W+|i mean\W+)?(?P<rest>\w.*)$", re.IGNORECASE)
VERBS = {"navigate_to_marker": "go to", "pick_up": "pick up", "find": "find"}


def _instead_of(text: str, offered: list[TaskIntent],
                reread: Callable[[str], list[TaskIntent]]) -> list[TaskIntent] | None:
    """The answer "no, the bathroom" to "Did you mean: go to the kitchen?": the offer's one
    targeted request, with the target said instead; None for any other answer."""
    m = _NO_BUT.match(text)
    targeted = [i for i in offered if i.action in VERBS]
    if not m or len(targeted) != 1:
        return None
    again = reread(f"{VERBS[targeted[0].action]} {m.group('rest')}")
    return again if len(again) == 1 and again[0].action == targeted[0].action else None


@dataclass(eq=False)
class Offers:
    """The proposal offered and waiting for a yes (guarded by the job queue's condition, like the
    question that offers it). ``resolve`` checks intents as for a parsed utterance (resolved
    intents, calls, sentences for those that would not); ``accept`` queues a confirmed one."""

    jobs: JobQueue
    conversation: Any
    lab: WorldState  # the places and objects a proposal may name
    enabled: bool
    resolve: Callable[[list[TaskIntent]], tuple[list[TaskIntent], Any, list[str]]]
    accept: Callable[[str, list[TaskIntent], bool], object]
    reread: Callable[[str], list[TaskIntent]] = lambda text: []  # the grammar, for "no, the bathroom"
    _pending: tuple[str, list[TaskIntent]] | None = field(default=None, init=False)  # (request, intents) awaiting a yes

    def offer(self, text: str) -> bool:
        """On the reply thread: a request the grammar missed may get a model's proposal. Only one
        that resolves and plans-checks is offered ("Shall I ...?"); it waits for a yes."""
        if not self.enabled or is_question(text) or not isinstance(self.conversation, Proposer):
            return False
        from ..core.gestures import LIBRARY

        events = self.jobs.events
        prompt = messages(text, sorted(self.lab.markers), sorted(self.lab.objects), sorted(LIBRARY))
        try:
            intents = parse(self.conversation.propose(prompt, schema()))
        except Exception as e:  # noqa: BLE001 - a failing model must leave the plain reply
            events.publish("warning", message=f"task proposal failed: {type(e).__name__}: {e}")
            return False
        checked, _, unknown = self.resolve(intents or [])
        if not checked or unknown:  # a proposal that would not resolve or plan is not offered
            return False
        question = f"Shall I {describe(checked)}? Say yes to go ahead."
        with self.jobs.cond:
            self._pending = (text, checked)
            self.jobs.queue.appendleft(Say(question, "proposal"))
            self.jobs.cond.notify_all()
        events.publish("proposal", phase="offered", to=text, intents=[i.to_dict() for i in checked])
        return True

    def ask(self, text: str, intents: list[TaskIntent], reasons: Sequence[str]) -> str:
        """A command in doubt (:mod:`stuart_bt.language.doubt`): ask before acting; returns what
        the robot says. What it would do is checked as for any command first: a place it does not
        know is said, not asked."""
        checked, _, unknown = self.resolve(intents)
        if unknown:
            sentence = " ".join(unknown)
            self.jobs.say_first(Say(sentence, "unknown"))
            return sentence
        question = f"Did you mean: {describe(checked)}? Say yes or no."
        with self.jobs.cond:
            self._pending = (text, checked)
            self.jobs.queue.appendleft(Say(question, "proposal"))
            self.jobs.cond.notify_all()
        self.jobs.events.publish("proposal", phase="offered", to=text, intents=[i.to_dict() for i in checked],
                                 doubt=list(reasons))
        return question

    def answer(self, command: Command) -> bool:
        """A yes runs the offered proposal, a no drops it (no wake phrase needed for either: the
        robot just asked); anything else drops it and is handled as usual."""
        with self.jobs.cond:
            pending, self._pending = self._pending, None
        if pending is None:
            return False
        events = self.jobs.events
        text = command.parse.command if command.parse.wake else command.parse.utterance
        if YES.match(text or ""):
            events.publish("proposal", phase="confirmed", to=pending[0])
            self.accept(pending[0], pending[1], False)
            return True
        if NO.match(text or ""):
            events.publish("proposal", phase="declined", to=pending[0])
            self.jobs.say_first(Say("OK, I won't.", "proposal"))
            return True
        instead = _instead_of(text or "", pending[1], self.reread)
        if instead:  # "no, the bathroom": the same request with the named target
            events.publish("proposal", phase="corrected", to=pending[0], intents=[i.to_dict() for i in instead])
            self.accept(pending[0], instead, False)
            return True
        events.publish("proposal", phase="dropped", to=pending[0])
        return False
