"""TaskIntent: one thing the robot was asked to do, as the grammar understood it.

The fields are the original system's (``action, target, x, y, yaw, raw_text``) so scripts and the
HTN planner written against it keep working. Units follow REP-103: ``x`` forward and ``y`` left
in metres, ``yaw`` in radians, counter-clockwise (left) positive. Fields an action does not use
are 0 (numbers) or "" (target), never missing, so every intent has the same JSON shape.

| action | target | x, y | yaw |
|---|---|---|---|
| navigate_to_marker | spoken place ("kitchen", "station three") | 0 | 0 |
| move_relative | "" | metres | 0 |
| turn_by_angle | "" | 0 | radians |
| turn_around | "" | 0 | pi |
| pick_up | spoken object ("bottle", "red cup") | 0 | 0 |
| gesture | gesture library name ("wave", "high five") | 0 | 0 |
| stop | "" | 0 | 0 |
| find | spoken object or place | 0 | 0 |
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..core.jsonfile import to_json

NAVIGATE, MOVE, TURN, TURN_AROUND = "navigate_to_marker", "move_relative", "turn_by_angle", "turn_around"
PICK, GESTURE, STOP, FIND = "pick_up", "gesture", "stop", "find"
ACTIONS: tuple[str, ...] = (NAVIGATE, MOVE, TURN, TURN_AROUND, PICK, GESTURE, STOP, FIND)
TARGETED = frozenset({NAVIGATE, PICK, GESTURE, FIND})  # actions whose target means something
FIELDS = ("action", "target", "x", "y", "yaw", "raw_text")


@dataclass(frozen=True, slots=True)
class TaskIntent:
    """One command. ``raw_text`` is the part of the utterance it came from, as written."""

    action: str
    target: str = ""
    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0
    raw_text: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {"action": self.action, "target": self.target, "x": self.x, "y": self.y, "yaw": self.yaw,
                "raw_text": self.raw_text}

    def to_json(self) -> str:
        return to_json(self.to_dict(), ensure_ascii=False)

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> TaskIntent:
        """Build from JSON; unknown actions are refused (a typo must not become a silent no-op)."""
        action = str(d.get("action", ""))
        if action not in ACTIONS:
            raise ValueError(f"unknown action {action!r}; expected one of {', '.join(ACTIONS)}")
        return cls(action, str(d.get("target", "") or ""), float(d.get("x", 0.0) or 0.0),
                   float(d.get("y", 0.0) or 0.0), float(d.get("yaw", 0.0) or 0.0), str(d.get("raw_text", "") or ""))

    def same_as(self, other: TaskIntent, tol: float = 1e-3) -> bool:
        """Same action, target and numbers (within ``tol``); ``raw_text`` is not compared."""
        return (self.action == other.action and self.target == other.target and abs(self.x - other.x) <= tol
                and abs(self.y - other.y) <= tol and abs(self.yaw - other.yaw) <= tol)


_GESTURE_WORDS = {"wave": "Waving", "face wave": "Waving", "clap": "Clapping", "hug": "Here is a hug",
                  "high five": "High five!", "shake hand": "Let's shake hands", "hands up": "Hands up",
                  "release arm": "Lowering my arms"}


def _metres(v: float) -> str:
    v = abs(v)
    if v < 1 and round(v * 100) != 0:
        return f"{round(v * 100):g} centimetres"
    s = f"{round(v, 2):g}"
    return f"{s} metre" if s == "1" else f"{s} metres"


def confirmation(intent: TaskIntent) -> str:
    """What the robot says before acting ("Navigating to kitchen", "Turning right 90 degrees")."""
    a = intent.action
    if a == NAVIGATE:
        return f"Navigating to {intent.target}"
    if a == MOVE:
        parts = []
        if intent.x:
            parts.append(f"{'forward' if intent.x > 0 else 'back'} {_metres(intent.x)}")
        if intent.y:
            parts.append(f"{'left' if intent.y > 0 else 'right'} {_metres(intent.y)}")
        return "Moving " + " and ".join(parts) if parts else "Staying where I am"
    if a == TURN:
        deg = round(math.degrees(abs(intent.yaw)))
        return f"Turning {'left' if intent.yaw >= 0 else 'right'} {deg} degrees"
    if a == TURN_AROUND:
        return "Turning around"
    if a == PICK:
        return f"Picking up the {intent.target}"
    if a == GESTURE:
        return _GESTURE_WORDS.get(intent.target, f"Doing the {intent.target} gesture")
    if a == STOP:
        return "Stopping"
    if a == FIND:
        return f"Looking for the {intent.target}"
    return a
