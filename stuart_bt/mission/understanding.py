"""What the tasks in an utterance refer to: intents checked against the lab and made domain calls.

:func:`~.commands.interpret` says what kind of utterance it was (stop, continue, tasks,
conversation); here the tasks it found are held to what the robot knows: places on the map,
objects it has heard of, gestures it can play, and arguments the domain's tasks accept. An intent
that fails either check becomes a sentence to say instead, so nothing of that command moves the
robot.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..htn import TaskArgumentError
from ..language import TaskIntent

if TYPE_CHECKING:
    from ..htn.domain import Domain
    from ..htn.values import TaskCall
    from ..language import Resolver


def resolve(resolver: Resolver, domain: Domain,
            intents: list[TaskIntent]) -> tuple[list[TaskIntent], list[TaskCall], list[str]]:
    """Targets resolved against the map, objects and gestures, and each intent made a domain
    call; the sentences to say for those that would not (an unknown place, a bad argument)."""
    resolved: list[TaskIntent] = []
    calls: list[TaskCall] = []
    unknown: list[str] = []
    for intent in intents:
        resolution = resolver.resolve(intent) if intent.action != "gesture" else None
        if resolution is not None and not resolution.ok:
            unknown.append(resolution.say())
            continue
        if resolution is not None:
            intent = TaskIntent(**{**intent.to_dict(), "target": resolution.name})
        try:
            calls.append(domain.to_call(intent.to_dict()))
        except TaskArgumentError as e:
            unknown.append(f"I cannot do that: {e}.")
            continue
        resolved.append(intent)
    return resolved, calls, unknown


def said(intents: list[TaskIntent]) -> list[str]:
    """What was said for each intent, for explanations ("Sorry, I could not ...")."""
    return [i.raw_text or i.action for i in intents]
