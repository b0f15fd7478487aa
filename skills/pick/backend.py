"""What every manipulation backend offers: pick an object, release it, find it.

The robot's pose comes with every request (the loco daemon owns it; this daemon does not move
the base), so reach checks happen here before any arm moves.
"""

from __future__ import annotations

from abc import abstractmethod
from typing import Any

from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, Backend, Handler
from stuart_bt.world import Pose

ARMS = ("auto", "left", "right")


class PickBackend(Backend):
    family = "pick"

    @abstractmethod
    def pick(self, label: str, arm: str, robot_pose: Pose) -> Activity:
        """Grasp and lift the object; the result is ``{"object", "arm", "position"}``."""

    @abstractmethod
    def release(self, arm: str, robot_pose: Pose) -> Activity:
        """Put down what ``arm`` ('auto': whichever) holds; the result says where it went."""

    @abstractmethod
    def find(self, label: str, robot_pose: Pose) -> Activity:
        """Locate an object; the result is ``{"object", "position", "distance"}``."""

    def commands(self) -> dict[str, Handler]:
        return {"pick": self._pick_command, "release": self._release_command, "find": self._find_command}

    def _pick_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("object", "arm", "robot_pose"), "pick")
        return self.pick(_label(args, "pick"), a.string(args, "arm", "pick", default="auto", choices=ARMS),
                         a.pose(args, "robot_pose", "pick"))

    def _release_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("arm", "robot_pose"), "release")
        return self.release(a.string(args, "arm", "release", default="auto", choices=ARMS),
                            a.pose(args, "robot_pose", "release"))

    def _find_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("object", "robot_pose"), "find")
        return self.find(_label(args, "find"), a.pose(args, "robot_pose", "find"))


def _label(args: dict[str, Any], cmd: str) -> str:
    label = a.string(args, "object", cmd).strip()
    if not label:
        raise a.bad(cmd, "'object' must name an object")
    return label
