"""Leaves that look (vision daemon): ``find`` one object, ``observe`` everything in view.

Both put what the camera placed into the world state's known objects (``source: "vision"``,
so ``pick`` aims there and the conversation may say it sees them) and publish the spatial
memory's summary as a ``memory`` event, the one way views and the ROS bridge learn of it.
"""

from __future__ import annotations

from typing import Any

from .manipulation import ObjectLeaf


class _LookingLeaf(ObjectLeaf):
    def publish_memory(self, result: dict[str, Any]) -> None:
        memory = result.get("memory")
        if isinstance(memory, dict):
            self.ctx.events.publish("memory", self.spec_path, **memory)


class Find(_LookingLeaf):
    """Look for an object; its position goes to the world state's known objects."""

    kind = "find"

    def command(self) -> tuple[str, dict[str, Any]]:
        return "find", {"object": str(self.param("object")), "robot_pose": self.robot_pose(),
                        "held": self.ctx.blackboard.world.held}

    def on_done(self, result: dict[str, Any]) -> None:
        label = result.get("object", str(self.param("object")))
        if result.get("in_hand"):
            return  # held: the world state already says so
        self.remember(label, result.get("position"), float(result.get("confidence", 1.0)), source="vision")
        self.publish_memory(result)


class Observe(_LookingLeaf):
    """One frame: every detection goes to the world state (the most confident one per label)."""

    kind = "observe"

    def command(self) -> tuple[str, dict[str, Any]]:
        return "look", {}

    def on_done(self, result: dict[str, Any]) -> None:
        best: dict[str, dict[str, Any]] = {}
        for d in result.get("detections") or []:
            placed = isinstance(d, dict) and isinstance(d.get("world"), list) and len(d["world"]) == 3
            if placed and (d["label"] not in best or d.get("confidence", 0) > best[d["label"]].get("confidence", 0)):
                best[d["label"]] = d
        for label, d in best.items():
            x, y, z = d["world"]
            self.remember(label, {"x": x, "y": y, "z": z}, float(d.get("confidence", 1.0)), source="vision")
        self.publish_memory(result)
