"""Leaves that handle objects: ``pick`` and ``release`` (pick daemon), ``find`` (vision daemon)."""

from __future__ import annotations

from typing import Any

from ..world import KnownObject
from .base import LeafFailure, SkillLeaf


class _ObjectLeaf(SkillLeaf):
    def robot_pose(self) -> dict[str, float]:
        return self.ctx.blackboard.world.pose.to_dict()

    def remember(self, label: str, position: dict[str, Any] | None, confidence: float = 1.0,
                 source: str = "catalogue") -> None:
        if position:
            self.ctx.blackboard.world.objects[label] = KnownObject(
                label, float(position["x"]), float(position["y"]), float(position.get("z", 0.0)),
                confidence=confidence, seen_at=self.ctx.clock.now(), source=source,
            )


class Pick(_ObjectLeaf):
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


class Release(_ObjectLeaf):
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


class Find(_ObjectLeaf):
    """Look for an object (vision daemon); its position goes to the world state's known objects
    and the spatial memory's summary goes out as a ``memory`` event."""

    kind = "find"

    def command(self) -> tuple[str, dict[str, Any]]:
        return "find", {"object": str(self.param("object")), "robot_pose": self.robot_pose(),
                        "held": self.ctx.blackboard.world.held}

    def on_done(self, result: dict[str, Any]) -> None:
        label = result.get("object", str(self.param("object")))
        if result.get("in_hand"):
            return  # held: the world state already says so
        self.remember(label, result.get("position"), float(result.get("confidence", 1.0)), source="vision")
        memory = result.get("memory")
        if isinstance(memory, dict):
            self.ctx.events.publish("memory", self.spec_path, **memory)
