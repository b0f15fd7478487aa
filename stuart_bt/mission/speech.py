"""What the robot says about its plans and failures: one spoken sentence built from a reason.

A task that cannot be planned is said with the planner's first rejection of it in words ("Sorry,
I cannot wave: my hands are full."); a mission that failed after its repairs with the failed
leaf's facts in words (:mod:`.failures`: "Sorry, I could not pick up the apple: I can't get close
enough to it - the kitchen table is in the way."). The technical sentence with the leaf's own
reason (:func:`could_not`) stays the mission's ``reason`` in the report and events. Only the
sentences are made here; the executor speaks them through a speak leaf.
"""

from __future__ import annotations

from typing import Any

from ..htn import PlanningFailed
from ..htn.values import TaskCall
from ..leaves import failure_code
from .failures import Failure, Words, in_words

WATCHDOG_SENTENCE = "I stopped: I lost touch with my controller for a moment. Say continue when it is safe to go on."

HUMAN_CLAUSES = {"held == null": "my hands are full", "held == obj": "I am not holding it",
                 "place in markers": "I do not know that place", "obj in objects": "I do not know where it is"}


def clause(text: str) -> str:
    text = text.strip().rstrip(".!?")
    return text[0].lower() + text[1:] if text else "do that"


def cannot(text: str, call: TaskCall, error: Exception) -> str:
    """One spoken sentence for a task that cannot be planned."""
    cause = why(error.failure, call.name) if isinstance(error, PlanningFailed) else None
    return f"Sorry, I cannot {clause(text) if text else str(call)}: {cause or str(error).splitlines()[0]}."


def could_not(texts: list[str], done: int, reason: str) -> str:
    """The technical sentence for a mission that failed at its call ``done``, for ``reason``: the
    mission's ``reason`` in the report and events (what is said is :func:`said_could_not`)."""
    what = _asked(texts, done)
    detail = reason.split(": ", 1)[1] if failure_code(reason) else reason
    return f"Sorry, I could not {clause(what)}: {detail.rstrip('.')}."


def said_could_not(texts: list[str], done: int, failure: Failure, words: Words) -> str:
    """What the robot says when a mission failed at its call ``done``: the failure in words."""
    what = _asked(texts, done)
    return f"Sorry, I could not {clause(what)}: {in_words(failure, Words(what, words.places, words.held))}."


def _asked(texts: list[str], done: int) -> str:
    return texts[min(done, len(texts) - 1)] if texts else "do that"


def why(failure: Any, task: str) -> str | None:
    """The first rejection of the failed ``task`` inside a nested planning failure, in words."""
    stack = [failure]
    while stack:
        f = stack.pop()
        if f.task.split("(")[0] == task:
            for attempt in f.attempts:
                if not attempt.chosen and attempt.reason is not None and not hasattr(attempt.reason, "attempts"):
                    condition = str(attempt.reason).split(" is false")[0].strip()
                    return HUMAN_CLAUSES.get(condition, str(attempt.reason))
            return f.message
        stack.extend(a.reason for a in f.attempts if hasattr(a.reason, "attempts"))
    return None
