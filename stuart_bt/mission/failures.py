"""What went wrong, in words people use: a failed leaf's facts turned into one spoken clause.

A leaf fails with a technical reason ("unreachable: no free spot to stand within 0.39 m of
(4.35, 1.85)") that belongs in the report and the events. The robot should say "I can't get close
enough to the apple - the kitchen table is in the way" instead, so the clause is built from the
failure's facts, never from its wording: the error code, the skill that failed and its arguments
(which object, which place, which gesture), and the data the daemon sent with the error (what kind
of goal could not be reached, the names of the furniture in the way when the map knows them,
what the camera saw instead).

Every error code of the daemon protocol (:data:`stuart_bt.daemon.protocol.ERROR_CODES`) and every
code a leaf makes itself has a clause here; ``tests/test_mission_failures.py`` fails when a code
has none.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from ..conversation.facts import listing, with_article
from ..leaves import failure_code

PARTS = {"loco": "legs", "pick": "arms", "gesture": "arms", "vision": "camera", "tts": "voice"}
FAMILY_OF = {"navigate": "loco", "approach": "loco", "view": "loco", "turn": "loco", "pick": "pick",
             "release": "pick", "gesture": "gesture", "find": "vision", "observe": "vision", "speak": "tts"}
LEAF_CODES = {  # failures a leaf makes itself, without a daemon error code: how its reason starts
    "timed out after": "timed_out", "unknown marker": "unknown_marker", "unknown gesture": "unknown_gesture",
    "no daemons are running": "daemon_down", "gesture file not found": "bad_gesture_file",
    "bad gesture file": "bad_gesture_file", "nothing to say": "nothing_to_say",
    "blackboard has no key": "missing_value",
}
MAX_NAMED = 2  # pieces of furniture named in one sentence


@dataclass(frozen=True)
class Failure:
    """The facts of one failed leaf: its technical ``reason`` (as the report has it), the
    daemon's error ``code``, the leaf's ``skill`` and ``args``, and the error's ``detail`` data."""

    reason: str
    code: str | None = None
    skill: str | None = None
    args: Mapping[str, Any] = field(default_factory=dict)
    detail: Mapping[str, Any] = field(default_factory=dict)

    @property
    def kind(self) -> str:
        """The code to speak about: the daemon's, the one the reason starts with, or the leaf's own."""
        if self.code and self.code != "error":
            return self.code
        code = failure_code(self.reason)
        if code:
            return code
        return next((kind for start, kind in LEAF_CODES.items() if self.reason.startswith(start)), "other")

    @property
    def label(self) -> str | None:
        value = self.args.get("object")
        return str(value) if value is not None else None

    def to_dict(self) -> dict[str, Any]:
        """For the report and the mission events: the facts, next to the unchanged reason."""
        out: dict[str, Any] = {"code": self.kind, "skill": self.skill, "reason": self.reason}
        for key in ("object", "marker", "play"):
            if self.args.get(key) is not None:
                out[key] = self.args[key]
        if self.detail.get("blocked_by"):
            out["blocked_by"] = list(self.detail["blocked_by"])
        if self.detail.get("goal"):
            out["goal"] = self.detail["goal"]
        return out


@dataclass(frozen=True)
class Words:
    """How to name things in a sentence: ``asked`` is what the person said (an object named there
    is "it" afterwards), ``places`` the spoken name of each marker, ``held`` what is in hand."""

    asked: str = ""
    places: Mapping[str, str] = field(default_factory=dict)
    held: str | None = None

    def thing(self, label: str | None) -> str:
        if not label:
            return "it"
        name = label.replace("_", " ")
        return "it" if f" {name} " in f" {self.asked.lower()} " else f"the {name}"

    def place(self, marker: Any) -> str:
        name = str(marker)
        return "the " + self.places.get(name, name.replace("_", " "))

    def part(self, skill: str | None) -> str:
        return "my " + PARTS.get(FAMILY_OF.get(skill or "", ""), "controller")


def in_words(failure: Failure, words: Words) -> str:
    """One clause for a failure, without the apology ("I can't get close enough to it - the
    kitchen table is in the way"); a failure of a kind not known here gets a general one."""
    say = SAYINGS.get(failure.kind, _other)
    return say(failure, words)


# -- the clauses, one per code --------------------------------------------------------------------------
def _unreachable(f: Failure, w: Words) -> str:
    goal = f.detail.get("goal") or {"approach": "reach", "view": "view", "turn": "relative"}.get(f.skill or "")
    if f.skill == "pick":
        return f"{w.thing(f.label)} is out of my arm's reach"
    if goal == "reach":
        said = f"I can't get close enough to {w.thing(f.label)}"
    elif goal == "view":
        said = f"I can't find a spot where I can see {w.thing(f.label)}"
    elif goal == "relative" or f.skill == "navigate" and "marker" not in f.args and "x" not in f.args:
        said = "I can't move that way"
    elif f.args.get("marker") is not None:
        said = f"I can't find a way to {w.place(f.args['marker'])}"
    else:
        said = "I can't find a way there"
    return said + _in_the_way(f.detail.get("blocked_by"))


def _in_the_way(names: Any) -> str:
    if not isinstance(names, list) or not names:
        return ""
    named = [f"the {n}" for n in names[:MAX_NAMED]]
    return f" - {' and '.join(named)} {'is' if len(named) == 1 else 'are'} in the way"


def _not_found(f: Failure, w: Words) -> str:
    if f.skill == "find":
        saw = [s for s in f.detail.get("saw") or [] if s != f.label]
        seen = f" - I only see {listing([with_article(s) for s in saw])}" if saw else ""
        return f"I looked, but I can't see {w.thing(f.label)}{seen}"
    if f.skill in ("pick", "approach", "view"):
        return f"I can't find {w.thing(f.label)} where I thought it was"
    if f.skill == "navigate" and f.args.get("marker") is not None:
        return f"I don't know where {w.place(f.args['marker'])} is"
    return "I can't find what I needed for that"


def _blocked(f: Failure, w: Words) -> str:
    where = f" on the way to {w.place(f.args['marker'])}" if f.args.get("marker") is not None else ""
    return f"something stayed in my way{where}, so I stopped"


def _timed_out(f: Failure, w: Words) -> str:
    return f"{_doing(f, w)} took too long, so I gave up"


def _doing(f: Failure, w: Words) -> str:
    """What the skill was doing, as a gerund phrase."""
    thing = w.thing(f.label)
    marker = f.args.get("marker")
    phrases = {
        "navigate": f"walking to {w.place(marker)}" if marker is not None else "walking there",
        "approach": f"walking up to {thing}", "view": f"getting a look at {thing}", "turn": "turning",
        "pick": f"picking up {thing}", "release": "putting it down", "find": f"looking for {thing}",
        "observe": "looking around", "speak": "speaking", "gesture": "the gesture",
    }
    return phrases.get(f.skill or "", "that")


def _unknown_gesture(f: Failure, w: Words) -> str:
    name = f.args.get("play")
    return f"I don't know the gesture {name}" if isinstance(name, str) else "I don't know that gesture"


def _already_holding(f: Failure, w: Words) -> str:
    return f"my hands are full - I am holding the {w.held.replace('_', ' ')}" if w.held else "my hands are full"


def _unknown_object(f: Failure, w: Words) -> str:
    return f"I don't know where {w.thing(f.label)} is"


def _unknown_marker(f: Failure, w: Words) -> str:
    marker = f.args.get("marker")
    return f"I don't know where {w.place(marker)} is" if marker is not None else "I don't know that place"


def _part_said(template: str) -> Callable[[Failure, Words], str]:
    """A clause about the part of the robot whose controller (daemon) failed."""
    def say(f: Failure, w: Words) -> str:
        return template.format(part=w.part(f.skill))
    return say


def _fixed(text: str) -> Callable[[Failure, Words], str]:
    def say(f: Failure, w: Words) -> str:
        return text
    return say


def _other(f: Failure, w: Words) -> str:
    return f"something went wrong while {_doing(f, w)}" if f.skill in FAMILY_OF else "something went wrong"


SAYINGS: dict[str, Callable[[Failure, Words], str]] = {
    # the daemon protocol's codes (stuart_bt.daemon.protocol.ERROR_CODES)
    "unreachable": _unreachable,
    "not_found": _not_found,
    "blocked": _blocked,
    "unknown_gesture": _unknown_gesture,
    "not_holding": _fixed("I am not holding anything"),
    "already_holding": _already_holding,
    "preempted": _part_said("something else took over {part}"),
    "stopped": _fixed("I was told to stop"),
    "cancelled": _fixed("it was called off"),
    "watchdog": _fixed("I lost touch with my controller for a moment, so I stopped"),
    "bad_request": _part_said("{part} could not follow what I asked"),
    "unknown_command": _part_said("{part} could not do what I asked"),
    "backend_error": _part_said("{part} reported a fault"),
    "daemon_died": _part_said("the controller of {part} stopped working"),
    "daemon_hung": _part_said("the controller of {part} stopped answering"),
    "daemon_faulty": _part_said("the controller of {part} is not making sense"),
    "daemon_down": _part_said("the controller of {part} is not running"),
    "out_of_range": _part_said("that is beyond what {part} can do"),
    "busy": _part_said("{part} had something else to do"),
    "disconnected": _part_said("I lost the connection to {part}"),
    "timeout": _part_said("{part} did not answer in time"),
    "start_failed": _part_said("{part} did not start"),
    # codes leaves make themselves
    "unknown_object": _unknown_object,
    "unknown_marker": _unknown_marker,
    "timed_out": _timed_out,
    "bad_result": _part_said("{part} gave an answer I could not use"),
    "bad_gesture_file": _fixed("I could not read that gesture's recording"),
    "nothing_to_say": _fixed("I had nothing to say"),
    "missing_value": _fixed("I was missing something I needed to know"),
}
