"""Leaves that handle objects: ``pick`` and ``release`` (pick daemon)."""

from __future__ import annotations

from typing import Any

from ..core.world import KnownObject
from .base import LeafFailure, SkillLeaf


class ObjectLeaf(SkillLeaf):
    def robot_pose(self) -> dict[str, float]:
        return self.ctx.blackboard.world.pose.to_dict()

    def remember(self, label: str, position: dict[str, Any] | None, confidence: float = 1.0,
                 source: str = "catalogue") -> None:
        if position:
            self.ctx.blackboard.world.objects[label] = KnownObject(
                label, float(position["x"]), float(position["y"]), float(position.get("z", 0.0)),
                confidence=confidence, seen_at=self.ctx.clock.now(), source=source,
            )


class Pick(ObjectLeaf):
    """Pick up an object by label; the daemon checks reach before any motion."""

    kind = "pick"

    def command(self) -> tuple[str, dict[str, Any]]:
        world = self.ctx.blackboard.world
        label = str(self.param("object"))
        if world.held is not None:
            raise LeafFailure(f"already_holding: already holding {world.held!r}; release it first")
        args = {"object": label, "arm": self.param("arm"), "robot_pose": self.robot_pose()}
        known = world.objects.get(label)
        if known is not None and known.source == "vision":  # aim where the camera saw it
            args["position"] = {"x": known.x, "y": known.y, "z": known.z}
        return "pick", args

    def on_done(self, result: dict[str, Any]) -> None:
        world = self.ctx.blackboard.world
        world.held = result.get("object", self.param("object"))
        world.held_arm = result.get("arm")
        world.objects.pop(world.held, None)


class Release(ObjectLeaf):
    """Put down what is held; the object is known again where it was put."""

    kind = "release"

    def command(self) -> tuple[str, dict[str, Any]]:
        return "release", {"arm": self.param("arm"), "robot_pose": self.robot_pose()}

    def on_done(self, result: dict[str, Any]) -> None:
        world = self.ctx.blackboard.world
        label = result.get("object") or world.held
        if label:
            self.remember(label, result.get("position"))
        world.held = None
        world.held_arm = None
