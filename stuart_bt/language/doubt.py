"""Doubt: when the robot should ask before it acts ("Did you mean: go to the kitchen?").

A command is clear when every word is accounted for and every amount is one the robot can do.
Anything else is doubt, and doubt never moves the robot by itself: the mission executor asks and
waits for a yes. The reasons found from the words alone are here; the executor adds the ones that
need the lab (a target not on the map) or the ears (a low recogniser confidence, two readings).
A stop is never in doubt: it always wins.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from .grammar.coverage import Coverage
from .intents import MOVE, STOP, TURN, TaskIntent

SIGN_WORDS = frozenset({"minus", "negative"})  # "move forward minus two metres": which way is meant?


@dataclass(frozen=True)
class Limits:
    """The largest amounts one spoken command may ask for. Why these: a lab is a few metres
    across, so a relative walk of more than 10 m is a slip of the tongue or the ears (a walk to a
    place uses its name); more than two full turns is never needed."""

    move_m: float = 10.0
    turn_rad: float = 4 * math.pi


@dataclass(frozen=True)
class Doubt:
    """One reason to ask: ``reason`` is a code (``unused``, ``amount``, ``question``, ``unread``, and from the
    executor ``unresolved``, ``confidence``, ``readings``), ``detail`` says it in words."""

    reason: str
    detail: str

    def to_dict(self) -> dict[str, Any]:
        return {"reason": self.reason, "detail": self.detail}


def doubts(intents: Sequence[TaskIntent], coverage: Coverage, limits: Limits = Limits()) -> list[Doubt]:
    """What makes acting on ``intents`` unsafe without asking (empty: a clear command)."""
    if not intents or all(i.action == STOP for i in intents):
        return []
    found: list[Doubt] = []
    if coverage.unused:
        found.append(Doubt("unused", "I did not understand: " + " ".join(coverage.unused)))
    signs = [w for w in (*coverage.used, *coverage.unused) if w in SIGN_WORDS]
    if signs:
        found.append(Doubt("amount", f"a {signs[0]} amount"))
    found.extend(_out_of_range(intents, limits))
    if coverage.asked:  # "go to the kitchen, right?": a check that it heard, or a question about the plan?
        found.append(Doubt("question", f"it was put as a question (..., {coverage.asked[0]}?)"))
    if coverage.unread:
        found.append(Doubt("unread", "too long: the end was not read"))
    return found


def _out_of_range(intents: Sequence[TaskIntent], limits: Limits) -> list[Doubt]:
    found = []
    for i in intents:
        if i.action == MOVE and math.hypot(i.x, i.y) > limits.move_m:
            found.append(Doubt("amount", f"{math.hypot(i.x, i.y):g} m is further than I walk at once "
                                         f"({limits.move_m:g} m)"))
        elif i.action == TURN and abs(i.yaw) > limits.turn_rad:
            found.append(Doubt("amount", f"{math.degrees(abs(i.yaw)):.0f} degrees is more than I turn at once "
                                         f"({math.degrees(limits.turn_rad):.0f})"))
    return found
