"""Dry manipulation: no arms, no camera; objects are points in a table, moved symbolically.

It still enforces what the real robot would refuse (an unknown object, one out of reach, a
second object while one is held, releasing nothing) so trees fail in a dry run for the same
reasons they would fail on the robot.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from stuart_bt.core.clock import Clock
from stuart_bt.core.suggest import did_you_mean
from stuart_bt.core.world import Pose
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, DaemonError, TimedActivity

from .backend import PickBackend

OBJECTS_FILE = Path(__file__).resolve().parent.parent / "objects.json"
REACH = 1.2  # metres from the robot's base to an object it can pick
PICK_PHASES = ("pre_grasp", "descend", "close", "lift")
PICK_SECONDS = 6.0
RELEASE_PHASES = ("lower", "open", "retract")
RELEASE_SECONDS = 3.0
PLACE_AHEAD = 0.4  # metres in front of the robot where a released object lands


@dataclass(frozen=True)
class Position:
    x: float
    y: float
    z: float

    def to_dict(self) -> dict[str, float]:
        return {"x": round(self.x, 4), "y": round(self.y, 4), "z": round(self.z, 4)}

    def distance_from(self, pose: Pose) -> float:
        return math.hypot(self.x - pose.x, self.y - pose.y)


def parse_objects(entries: Any, where: str) -> dict[str, Position]:
    """``{label: {"x", "y", "z"}}`` (extra keys such as ``on`` are descriptions, ignored)."""
    if not isinstance(entries, dict):
        raise a.bad(where, f"objects must be a mapping of label to {{x, y, z}}, got {entries!r}")
    objects = {}
    for label, spot in entries.items():
        if not isinstance(spot, dict):
            raise a.bad(where, f"object {label!r} must be {{x, y, z}}, got {spot!r}")
        objects[label] = Position(a.number(spot, "x", f"{where} {label}"), a.number(spot, "y", f"{where} {label}"),
                                  a.number(spot, "z", f"{where} {label}", default=0.0))
    return objects


def load_objects(path: Path = OBJECTS_FILE) -> dict[str, Position]:
    return parse_objects(json.loads(path.read_text(encoding="utf-8"))["objects"], str(path))


class Phased(TimedActivity):
    """A timed arm motion that reports which of its equal-length phases it is in."""

    resource = "arms"

    def __init__(self, duration: float, phases: tuple[str, ...]) -> None:
        super().__init__(duration)
        self._phases = phases

    def report(self, now: float) -> dict[str, Any]:
        index = min(int(self.fraction(now) * len(self._phases)), len(self._phases) - 1)
        return {"phase": self._phases[index], "fraction": round(self.fraction(now), 3)}

    def cancel(self, now: float) -> dict[str, Any]:
        return self.report(now)


class Grasp(Phased):
    def __init__(self, backend: DryPick, label: str, arm: str) -> None:
        super().__init__(PICK_SECONDS, PICK_PHASES)
        self._backend, self._label, self._arm = backend, label, arm

    def finish(self, now: float) -> dict[str, Any]:
        position = self._backend.take(self._label, self._arm)
        return {"object": self._label, "arm": self._arm, "position": position.to_dict()}


class Place(Phased):
    def __init__(self, backend: DryPick, robot_pose: Pose) -> None:
        super().__init__(RELEASE_SECONDS, RELEASE_PHASES)
        self._backend, self._robot_pose = backend, robot_pose

    def finish(self, now: float) -> dict[str, Any]:
        label, arm, position = self._backend.put_down(self._robot_pose)
        return {"object": label, "arm": arm, "position": position.to_dict()}


class DryPick(PickBackend):
    name = "dry"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        a.only_known(options, ("objects",), "pick dry options")
        if "objects" in options:
            self.objects = parse_objects(options["objects"], "pick dry options")
        else:
            self.objects = load_objects()
        self.held: str | None = None
        self.held_arm: str | None = None
        self._held_from: Position | None = None  # where the held object was picked up

    def pick(self, label: str, arm: str, robot_pose: Pose, position: dict[str, float] | None = None) -> Activity:
        if self.held is not None:
            raise DaemonError("already_holding", f"already holding the {self.held} ({self.held_arm} arm); "
                                                 "release it first")
        at = self._aim(label, position)
        distance = at.distance_from(robot_pose)
        if distance > REACH:
            raise DaemonError("unreachable", f"{label} is {distance:.1f} m away; reach is {REACH} m",
                              data={"distance": round(distance, 4), "reach": REACH})
        if arm == "auto":
            arm = "left" if _lateral(robot_pose, at) >= 0 else "right"
        return Grasp(self, label, arm)

    def release(self, arm: str, robot_pose: Pose) -> Activity:
        if self.held is None or arm not in ("auto", self.held_arm):
            raise DaemonError("not_holding", f"the {'robot' if arm == 'auto' else arm + ' arm'} holds nothing")
        return Place(self, robot_pose)

    def take(self, label: str, arm: str) -> Position:
        """A grasp succeeded: the object leaves its table for the hand."""
        self._held_from = self.objects.pop(label)
        self.held, self.held_arm = label, arm
        return self._held_from

    def put_down(self, robot_pose: Pose) -> tuple[str, str, Position]:
        """A release succeeded: the held object lands in front of the robot at the height it
        was picked from."""
        assert self.held is not None and self.held_arm is not None and self._held_from is not None
        label, arm = self.held, self.held_arm
        position = Position(robot_pose.x + PLACE_AHEAD * math.cos(robot_pose.yaw),
                            robot_pose.y + PLACE_AHEAD * math.sin(robot_pose.yaw), self._held_from.z)
        self.objects[label] = position
        self.held = self.held_arm = self._held_from = None
        return label, arm, position

    def state(self) -> dict[str, Any]:
        return {"held": self.held, "arm": self.held_arm,
                "objects": {label: p.to_dict() for label, p in self.objects.items()}}

    def _aim(self, label: str, seen: dict[str, float] | None) -> Position:
        """Where to grasp: where perception saw the object (it then stands there in the table),
        else where the table has it."""
        if seen is not None:
            self.objects[label] = Position(seen["x"], seen["y"], seen["z"])
        return self._known(label)

    def _known(self, label: str) -> Position:
        if label not in self.objects:
            known = ", ".join(sorted(self.objects)) or "none"
            raise DaemonError("not_found", f"no {label!r} known{did_you_mean(label, self.objects)} (known: {known})")
        return self.objects[label]


def _lateral(robot_pose: Pose, position: Position) -> float:
    """How far the object is to the robot's left (negative: right)."""
    dx, dy = position.x - robot_pose.x, position.y - robot_pose.y
    return -math.sin(robot_pose.yaw) * dx + math.cos(robot_pose.yaw) * dy
