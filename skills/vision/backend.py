"""What every vision backend offers: find an object, look once, report the memory.

``find`` looks from where the robot stands (the task domain turns the robot between looks when
it searches); it succeeds once the object was seen in enough frames for a steady position and
fails with ``not_found`` (saying what *was* seen) otherwise. ``held`` names what the robot holds,
which is found in the hand without looking.
"""

from __future__ import annotations

from abc import abstractmethod
from typing import Any

from stuart_bt.core.world import Pose
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, Backend, Delivered, Handler


class VisionBackend(Backend):
    family = "vision"

    @abstractmethod
    def find(self, label: str, robot_pose: Pose, held: str | None) -> Activity:
        """Look for ``label``; the result is ``{"object", "position", "distance", "detections", "memory"}``."""

    @abstractmethod
    def look(self) -> Activity:
        """One frame: ``{"detections": [...], "memory": summary}``."""

    @abstractmethod
    def memory(self) -> dict[str, Any]:
        """The spatial memory's JSON summary."""

    def commands(self) -> dict[str, Handler]:
        return {"find": self._find_command, "look": self._look_command, "memory": self._memory_command}

    def _find_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("object", "robot_pose", "held"), "find")
        label = a.string(args, "object", "find").strip()
        if not label:
            raise a.bad("find", "'object' must name an object")
        held = args.get("held")
        if held is not None and not isinstance(held, str):
            raise a.bad("find", f"'held' must be an object label or null, got {held!r}")
        return self.find(label, a.pose(args, "robot_pose", "find"), held)

    def _look_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, (), "look")
        return self.look()

    def _memory_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, (), "memory")
        return Delivered(0.0, {"memory": self.memory()})
