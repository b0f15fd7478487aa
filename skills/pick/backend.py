"""What every manipulation backend offers: pick an object, release it (finding it is the vision daemon's).

The robot's pose comes with every request (the loco daemon owns it; this daemon does not move
the base), so reach checks happen here before any arm moves.
"""

from __future__ import annotations

from abc import abstractmethod
from typing import Any

from stuart_bt.core.world import Pose
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, Backend, Handler

ARMS = ("auto", "left", "right")


class PickBackend(Backend):
    family = "pick"

    @abstractmethod
    def pick(self, label: str, arm: str, robot_pose: Pose, position: dict[str, float] | None = None) -> Activity:
        """Grasp and lift the object (at ``position``, map frame, when perception placed it;
        else where the backend knows it to be); the result is ``{"object", "arm", "position"}``."""

    @abstractmethod
    def release(self, arm: str, robot_pose: Pose) -> Activity:
        """Put down what ``arm`` ('auto': whichever) holds; the result says where it went."""

    def commands(self) -> dict[str, Handler]:
        return {"pick": self._pick_command, "release": self._release_command}

    def _pick_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("object", "arm", "robot_pose", "position"), "pick")
        position = None
        if args.get("position") is not None:
            spot = args["position"]
            if not isinstance(spot, dict):
                raise a.bad("pick", f"'position' must be {{x, y, z}}, got {spot!r}")
            position = {k: a.number(spot, k, "pick position") for k in ("x", "y", "z")}
        return self.pick(_label(args, "pick"), a.string(args, "arm", "pick", default="auto", choices=ARMS),
                         a.pose(args, "robot_pose", "pick"), position)

    def _release_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("arm", "robot_pose"), "release")
        return self.release(a.string(args, "arm", "release", default="auto", choices=ARMS),
                            a.pose(args, "robot_pose", "release"))


def _label(args: dict[str, Any], cmd: str) -> str:
    label = a.string(args, "object", cmd).strip()
    if not label:
        raise a.bad(cmd, "'object' must name an object")
    return label
