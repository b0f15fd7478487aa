"""Leaves that move the base: ``navigate`` and ``turn`` (loco daemon)."""

from __future__ import annotations

import math
from typing import Any

from ..suggest import did_you_mean
from ..world import Pose
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
            name = str(self.param("marker"))
            markers = self.ctx.blackboard.world.markers
            if name not in markers:
                raise LeafFailure(f"unknown marker {name!r}{did_you_mean(name, markers)}")
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
        if "pose" in result:
            world.pose = Pose.from_dict(result["pose"])
        if result.get("marker"):
            world.last_marker = result["marker"]


class Turn(SkillLeaf):
    """Turn in place; ``angle`` in radians or ``degrees``, counter-clockwise positive."""

    kind = "turn"

    def command(self) -> tuple[str, dict[str, Any]]:
        if self.has("degrees"):
            angle = math.radians(float(self.param("degrees")))
        else:
            angle = float(self.param("angle"))
        return "turn", {"angle": angle}

    def on_done(self, result: dict[str, Any]) -> None:
        if "pose" in result:
            self.ctx.blackboard.world.pose = Pose.from_dict(result["pose"])
