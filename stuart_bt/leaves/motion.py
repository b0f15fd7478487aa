"""Leaves that move the base: ``navigate`` and ``turn`` (loco daemon)."""

from __future__ import annotations

import math
from typing import Any

from ..core.suggest import did_you_mean
from ..core.world import Pose
from ..maps.marker_names import UnknownMarker, find_marker
from .base import LeafFailure, SkillLeaf


class Navigate(SkillLeaf):
    """Walk to a marker, a map pose or a body-relative offset; arrival updates the world pose."""

    kind = "navigate"

    def command(self) -> tuple[str, dict[str, Any]]:
        args: dict[str, Any] = {
            "tolerance": float(self.param("tolerance")),
            "yaw_tolerance": float(self.param("yaw_tolerance")),
        }
        if self.has("marker"):
            markers = self.ctx.blackboard.world.markers
            try:  # a display name too: "$target" may hold "Electronics bench"
                name = find_marker(str(self.param("marker")), markers)
            except UnknownMarker as e:
                raise LeafFailure(str(e)) from None
            marker = markers[name]
            args["marker"] = name
            args["pose"] = marker.pose.to_dict()
        elif self.has("x") or self.has("y"):
            yaw = self.param("yaw")
            args["pose"] = {"x": float(self.param("x")), "y": float(self.param("y")),
                            "yaw": None if yaw is None else float(yaw)}
        else:
            args["relative"] = {k: float(self.param(k)) for k in ("dx", "dy", "dyaw")}
        return "navigate", args

    def on_done(self, result: dict[str, Any]) -> None:
        world = self.ctx.blackboard.world
        if "pose" in result:  # a pose that is not finite numbers raises: the leaf fails with bad_result
            world.pose = Pose.from_dict(result["pose"])
        if result.get("marker"):
            world.last_marker = result["marker"]


class Approach(Navigate):
    """Walk up to a remembered object or a point and stop with it ``standoff`` ahead and ``lateral``
    to the side (in front of a shoulder), facing it.

    The object's position is read from the world state when the leaf starts, not when the tree was
    built, so a ``find`` earlier in the tree (or a repair that looked again) is what counts. The
    daemon chooses where to stand (the sim and the robot avoid furniture on their map)."""

    kind = "approach"

    def command(self) -> tuple[str, dict[str, Any]]:
        x, y, _ = self.point()
        spot = {"x": x, "y": y, "standoff": float(self.param("standoff")), "lateral": float(self.param("lateral"))}
        return "navigate", {"approach": spot, "tolerance": float(self.param("tolerance")),
                            "yaw_tolerance": float(self.param("yaw_tolerance"))}

    def point(self) -> tuple[float, float, float]:
        """The point to walk up to: the remembered object's position now, or the given one."""
        if self.has("object"):
            label = str(self.param("object"))
            objects = self.ctx.blackboard.world.objects
            if label not in objects:
                raise LeafFailure(f"unknown_object: no remembered position for {label!r}; find it first"
                                  f"{did_you_mean(label, objects)}")
            return objects[label].x, objects[label].y, objects[label].z
        return float(self.param("x")), float(self.param("y")), float(self.param("z", 0.0))


class View(Approach):
    """Walk to where the head camera sees a remembered object or a point (the daemon chooses the
    spot: in the camera's picture and range, nothing on its map in the way), or stay when it
    sees it from here. Finding needs sight, not reach: a cup in the middle of a table is looked
    at from the table's edge, where no arm would reach it."""

    kind = "view"

    def command(self) -> tuple[str, dict[str, Any]]:
        x, y, z = self.point()
        return "navigate", {"view": {"x": x, "y": y, "z": z}, "tolerance": float(self.param("tolerance")),
                            "yaw_tolerance": float(self.param("yaw_tolerance"))}


class Turn(SkillLeaf):
    """Turn in place; ``angle`` in radians or ``degrees``, counter-clockwise positive."""

    kind = "turn"

    def command(self) -> tuple[str, dict[str, Any]]:
        angle = math.radians(float(self.param("degrees"))) if self.has("degrees") else float(self.param("angle"))
        return "turn", {"angle": angle}

    def on_done(self, result: dict[str, Any]) -> None:
        if "pose" in result:
            self.ctx.blackboard.world.pose = Pose.from_dict(result["pose"])
