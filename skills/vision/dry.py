"""Dry vision: no camera; the lab's object table (skills/objects.json) stands for what is seen.

Options: ``objects`` (``{label: {x, y, z}}``, replacing the file). It keeps the contract of
the real thing (an unknown label is ``not_found``, the held object is
found in the hand, results carry a memory summary in the same format) so dry runs of trees and
missions take the same branches they would on the robot.
"""

from __future__ import annotations

import math
from typing import Any

from stuart_bt.core.clock import Clock
from stuart_bt.core.suggest import did_you_mean
from stuart_bt.core.world import Pose
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, DaemonError, Delivered
from stuart_bt.perception.memory import Observation, SpatialMemory

from ..pick.dry import Position, load_objects, parse_objects
from .backend import VisionBackend

FIND_SECONDS = 1.5
HAND_HEIGHT = 1.0


class DryVision(VisionBackend):
    name = "dry"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        a.only_known(options, ("objects",), "vision dry options")
        self.objects: dict[str, Position] = (parse_objects(options["objects"], "vision dry options")
                                             if "objects" in options else load_objects())
        self.spatial = SpatialMemory(clock)

    def find(self, label: str, robot_pose: Pose, held: str | None) -> Activity:
        if label == held:
            spot = {"x": round(robot_pose.x, 4), "y": round(robot_pose.y, 4), "z": HAND_HEIGHT}
            return Delivered(0.0, {"object": label, "position": spot, "distance": 0.0, "in_hand": True,
                                 "detections": [], "memory": self.memory()})
        if label not in self.objects:
            known = ", ".join(sorted(self.objects)) or "none"
            raise DaemonError("not_found", f"no {label!r} known{did_you_mean(label, self.objects)} (known: {known})")
        p = self.objects[label]
        self.spatial.update([Observation(label, p.x, p.y, p.z, 1.0)])
        distance = math.hypot(p.x - robot_pose.x, p.y - robot_pose.y)
        return Delivered(FIND_SECONDS, {"object": label, "position": p.to_dict(), "distance": round(distance, 3),
                                      "detections": [{"label": label, "confidence": 1.0}], "memory": self.memory()})

    def look(self) -> Activity:
        return Delivered(0.0, {"detections": [], "memory": self.memory()})

    def memory(self) -> dict[str, Any]:
        return self.spatial.summary()

    def state(self) -> dict[str, Any]:
        return {"remembered": len(self.spatial.entries)}
