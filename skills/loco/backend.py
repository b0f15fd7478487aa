"""What every locomotion backend offers: walk to a goal, turn in place, stop, report the pose.

Arguments are parsed and checked here, once, so the dry, sim and unitree backends only ever see
well-formed goals. Frames follow REP-103: map x forward, y left, yaw counter-clockwise, radians.
"""

from __future__ import annotations

import math
from abc import abstractmethod
from dataclasses import dataclass
from typing import Any

from stuart_bt.core.world import Pose
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, Backend, DaemonError, Handler
from stuart_bt.maps.viewpoints import CameraView

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
class ApproachGoal:
    """Stand so that the point (x, y) is ``standoff`` metres ahead of the robot's base and
    ``lateral`` metres to its left (negative: right), i.e. in front of one shoulder, where an arm
    reaches furthest: how the robot walks up to an object to pick it (to look at it, see
    :class:`ViewGoal`). A backend may mirror ``lateral`` when that side is blocked. Backends turn
    it into a :class:`MapGoal` before walking (:meth:`LocoBackend.approach_pose`); the sim and the
    robot pick a free spot on their map."""

    x: float
    y: float
    standoff: float
    lateral: float = 0.0


@dataclass(frozen=True)
class ViewGoal:
    """Stand where the head camera sees the point (x, y, z): in its picture and range, with
    nothing on the map in between; how the robot walks up to an object to look at it, which
    needs no arm's reach (a cup in the middle of a table is seen from its edge). Backends turn
    it into a :class:`MapGoal` (:meth:`LocoBackend.view_pose`); the robot stays, or only turns,
    when it sees the point from where it stands."""

    x: float
    y: float
    z: float


def approach_stand(goal: ApproachGoal, heading: float, lateral: float | None = None) -> MapGoal:
    """The base pose with heading ``heading`` that puts the point at (standoff, lateral) in the body frame."""
    spot = Pose.facing(goal.x, goal.y, heading, goal.standoff, goal.lateral if lateral is None else lateral)
    return MapGoal(spot.x, spot.y, heading)


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


def standoff_on_line(here: Pose, goal: ApproachGoal) -> MapGoal:
    """The stand-off on the side of the point that faces ``here``: heading along the line from
    ``here`` to the point (straight on when the robot stands on the point itself)."""
    dx, dy = goal.x - here.x, goal.y - here.y
    heading = math.atan2(dy, dx) if math.hypot(dx, dy) > 1e-6 else here.yaw
    return approach_stand(goal, heading)


def unreachable_data(goal: str, x: float, y: float, blocked_by: list[str], **more: Any) -> dict[str, Any]:
    """The data of an ``unreachable`` error, so what is said about it can be built from facts:
    which kind of ``goal`` (``reach``: an approach, ``view``: a viewpoint, ``pose``: a map pose,
    ``relative``: a body-relative move), the point, and ``blocked_by``: the names of the
    furniture in the way, most to blame first (empty when the map knows no names)."""
    return {"goal": goal, "x": round(x, 3), "y": round(y, 3), "blocked_by": blocked_by,
            **{k: round(v, 3) if isinstance(v, float) else v for k, v in more.items()}}


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

    def approach_pose(self, goal: ApproachGoal) -> MapGoal:
        """Where to stand for an approach. Without a map: on the side of the point that faces the
        robot (:func:`standoff_on_line`). Map-aware backends override this."""
        here = self.pose()
        return standoff_on_line(here, goal)

    @property
    def camera(self) -> CameraView:
        """The head camera, for choosing where to look from (imported here: only walks that
        look need the perception package)."""
        from stuart_bt.perception.projection import head_camera_view

        return head_camera_view()

    def view_pose(self, goal: ViewGoal) -> MapGoal:
        """Where to stand to see a point. Without a map: here, when the camera sees it from here
        (turning to face it if that is needed), else on the line from the robot to the point, at
        the distance that puts it in the middle of the picture. Map-aware backends override this
        and also keep furniture out of the line of sight."""
        here = self.pose()
        camera = self.camera
        target = (goal.x, goal.y, goal.z)
        facing = standoff_on_line(here, ApproachGoal(goal.x, goal.y, 0.0)).yaw
        assert facing is not None
        for yaw in (here.yaw, facing):
            if camera.miss((here.x, here.y, yaw), target) is None:
                return MapGoal(here.x, here.y, yaw)
        centred = camera.centred(goal.z)
        if centred is None:
            raise DaemonError("unreachable", f"the camera sees no point at height {goal.z:.2f} m from any distance",
                              data=unreachable_data("view", goal.x, goal.y, [], z=goal.z))
        return approach_stand(ApproachGoal(goal.x, goal.y, centred + camera.ahead, camera.left), facing)

    def commands(self) -> dict[str, Handler]:
        return {"navigate": self._navigate_command, "turn": self._turn_command}

    def _navigate_command(self, args: dict[str, Any]) -> Activity:
        cmd = "navigate"
        a.only_known(args, ("pose", "relative", "approach", "view", "marker", "tolerance", "yaw_tolerance"), cmd)
        form = a.one_of(args, ("pose", "relative", "approach", "view"), cmd)
        if form == "view":
            spot = a.mapping(args, "view", cmd)
            a.only_known(spot, ("x", "y", "z"), "navigate view")
            target: MapGoal | RelativeGoal = self.view_pose(ViewGoal(
                a.number(spot, "x", "navigate view"), a.number(spot, "y", "navigate view"),
                a.number(spot, "z", "navigate view", default=0.0)))
        elif form == "approach":
            spot = a.mapping(args, "approach", cmd)
            a.only_known(spot, ("x", "y", "standoff", "lateral"), "navigate approach")
            target = self.approach_pose(ApproachGoal(
                a.number(spot, "x", "navigate approach"), a.number(spot, "y", "navigate approach"),
                a.number(spot, "standoff", "navigate approach", minimum=0.0),
                a.number(spot, "lateral", "navigate approach", default=0.0),
            ))
        elif form == "pose":
            pose = a.mapping(args, "pose", cmd)
            a.only_known(pose, ("x", "y", "yaw"), "navigate pose")
            target = MapGoal(
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
