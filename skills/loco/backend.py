"""What every locomotion backend offers: walk to a goal, turn in place, stop, report the pose.

Arguments are parsed and checked here, once, so the dry, sim and unitree backends only ever see
well-formed goals. Frames follow REP-103: map x forward, y left, yaw counter-clockwise, radians.
"""

from __future__ import annotations

import math
from abc import abstractmethod
from dataclasses import dataclass
from typing import Any

from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, Backend, Handler
from stuart_bt.world import Pose

DEFAULT_TOLERANCE = 0.10  # metres
DEFAULT_YAW_TOLERANCE = 0.0873  # radians (5 degrees)


@dataclass(frozen=True)
class MapGoal:
    """A map pose; ``yaw`` None keeps the heading the robot arrives with."""

    x: float
    y: float
    yaw: float | None


@dataclass(frozen=True)
class RelativeGoal:
    """An offset in the robot's body frame at the moment the command starts."""

    dx: float
    dy: float
    dyaw: float


@dataclass(frozen=True)
class NavigateGoal:
    target: MapGoal | RelativeGoal
    marker: str | None
    tolerance: float
    yaw_tolerance: float


def goal_pose(start: Pose, target: MapGoal | RelativeGoal) -> tuple[float, float, float | None]:
    """Map-frame ``(x, y, yaw)`` of a goal; a relative goal is taken from ``start``'s body frame."""
    if isinstance(target, MapGoal):
        return target.x, target.y, target.yaw
    cos, sin = math.cos(start.yaw), math.sin(start.yaw)
    return (start.x + target.dx * cos - target.dy * sin, start.y + target.dx * sin + target.dy * cos,
            start.yaw + target.dyaw)


class LocoBackend(Backend):
    family = "loco"

    @abstractmethod
    def navigate(self, goal: NavigateGoal) -> Activity:
        """Walk to the goal; the activity's result is ``{"pose", "marker", "distance"}``."""

    @abstractmethod
    def turn(self, angle: float) -> Activity:
        """Turn in place by ``angle`` radians (counter-clockwise positive)."""

    @abstractmethod
    def pose(self) -> Pose:
        """Where the robot is now, in the map frame."""

    @abstractmethod
    def stop(self) -> None:
        """Zero velocity now."""

    def state(self) -> dict[str, Any]:
        return {"pose": self.pose().to_dict()}

    def commands(self) -> dict[str, Handler]:
        return {"navigate": self._navigate_command, "turn": self._turn_command}

    def _navigate_command(self, args: dict[str, Any]) -> Activity:
        cmd = "navigate"
        a.only_known(args, ("pose", "relative", "marker", "tolerance", "yaw_tolerance"), cmd)
        if a.one_of(args, ("pose", "relative"), cmd) == "pose":
            pose = a.mapping(args, "pose", cmd)
            a.only_known(pose, ("x", "y", "yaw"), "navigate pose")
            target: MapGoal | RelativeGoal = MapGoal(
                a.number(pose, "x", "navigate pose"), a.number(pose, "y", "navigate pose"),
                a.optional_number(pose, "yaw", "navigate pose"),
            )
        else:
            rel = a.mapping(args, "relative", cmd)
            a.only_known(rel, ("dx", "dy", "dyaw"), "navigate relative")
            target = RelativeGoal(*(a.number(rel, k, "navigate relative", default=0.0) for k in ("dx", "dy", "dyaw")))
        marker = args.get("marker")
        if marker is not None:
            marker = a.string(args, "marker", cmd)
        return self.navigate(NavigateGoal(
            target,
            marker,
            a.number(args, "tolerance", cmd, default=DEFAULT_TOLERANCE, minimum=0.0),
            a.number(args, "yaw_tolerance", cmd, default=DEFAULT_YAW_TOLERANCE, minimum=0.0),
        ))

    def _turn_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("angle",), "turn")
        return self.turn(a.number(args, "angle", "turn"))
