"""Python hooks of the project domain (tasks/domain.yaml): geometry and look-ups YAML cannot say.

Conditions answer a question about the state; functions compute skill arguments and predicted
poses. All read the state and never change it. Poses are ``{x, y, yaw}`` in the map frame
(REP-103: metres, radians, counter-clockwise); an object's place in ``objects`` is a marker
name, a position ``{x, y, z}``, or null (found at run time: its position is only known then).
"""

from __future__ import annotations

import math
import re
from typing import Any

from stuart_bt.core.gestures import lookup as gesture_lookup
from stuart_bt.core.world import Pose
from stuart_bt.htn.hooks import HookRegistry

HOOKS = HookRegistry()
PLACE_AHEAD = 0.4  # metres in front of the robot where a released object lands (the dry backend's figure)
TABLE_HEIGHT = 0.8  # metres: predicted height of a released object
_LABEL = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")  # what a $world.objects.<label> reference can name


# -- conditions ---------------------------------------------------------------------------------------
@HOOKS.condition
def known_gesture(state: Any, name: str) -> bool:
    """The gesture library (stuart_bt.core.gestures) knows this name, an alias or a vendor id."""
    return isinstance(name, str) and gesture_lookup(name) is not None


@HOOKS.condition
def is_marker(state: Any, value: Any) -> bool:
    """``value`` names a marker (and is not a pose)."""
    return isinstance(value, str) and value in state["markers"]


@HOOKS.condition
def object_at_marker(state: Any, obj: str) -> bool:
    """Memory places the object at a marker, not at a position: go there and look for it."""
    return is_marker(state, state["objects"].get(obj))


# -- functions ----------------------------------------------------------------------------------------
@HOOKS.function
def standoff_pose(state: Any, obj: str, side: float | None = None) -> dict[str, float] | None:
    """Where the robot is predicted to stand to reach the object: heading along the line from the
    robot (or, when its pose is unknown, the nearest marker) to the object, with the object
    ``standoff`` ahead and ``side`` (default ``reach_side``) to the left. The loco daemon may choose another side of
    the object when furniture is in the way; the prediction only feeds later steps' geometry."""
    spot = _object_xy(state, obj)
    if spot is None:
        return None
    ox, oy = spot
    origin = state["pose"] if isinstance(state["pose"], dict) else _nearest_marker(state, ox, oy)
    dx, dy = (ox - origin["x"], oy - origin["y"]) if origin else (1.0, 0.0)
    heading = math.atan2(dy, dx) if math.hypot(dx, dy) > 1e-6 else 0.0
    left = float(state["reach_side"] if side is None else side)
    stand = Pose.facing(ox, oy, heading, float(state["standoff"]), left)
    return {"x": stand.x, "y": stand.y, "yaw": heading}


@HOOKS.function
def turned(state: Any, angle: float) -> dict[str, float] | None:
    """The pose after turning in place by ``angle`` (null when the pose is unknown)."""
    pose = state["pose"]
    if not isinstance(pose, dict):
        return None
    return {"x": pose["x"], "y": pose["y"], "yaw": _wrap(pose.get("yaw", 0.0) + angle)}


@HOOKS.function
def moved(state: Any, dx: float, dy: float, dyaw: float) -> dict[str, float] | None:
    """The pose after a body-relative move: ``dx`` forward, ``dy`` left, then turn ``dyaw``."""
    pose = state["pose"]
    if not isinstance(pose, dict):
        return None
    yaw = pose.get("yaw", 0.0)
    return {"x": pose["x"] + dx * math.cos(yaw) - dy * math.sin(yaw),
            "y": pose["y"] + dx * math.sin(yaw) + dy * math.cos(yaw),
            "yaw": _wrap(yaw + dyaw)}


@HOOKS.function
def here(state: Any) -> Any:
    """Where a released object will be: ahead of the robot when its pose is known, else the
    marker it stands at, else null (known at run time)."""
    pose = state["pose"]
    if isinstance(pose, dict):
        yaw = pose.get("yaw", 0.0)
        return {"x": round(pose["x"] + PLACE_AHEAD * math.cos(yaw), 3),
                "y": round(pose["y"] + PLACE_AHEAD * math.sin(yaw), 3), "z": TABLE_HEIGHT}
    return state["at"]


# -- helpers ------------------------------------------------------------------------------------------
def _object_xy(state: Any, obj: str) -> tuple[float, float] | None:
    spot = state["objects"].get(obj)
    if isinstance(spot, dict) and "x" in spot and "y" in spot:
        return float(spot["x"]), float(spot["y"])
    return None


def _nearest_marker(state: Any, x: float, y: float) -> dict[str, float] | None:
    markers = state["markers"]
    if not markers:
        return None
    name = min(sorted(markers), key=lambda m: math.hypot(markers[m]["x"] - x, markers[m]["y"] - y))
    return markers[name]


def _wrap(angle: float) -> float:
    return math.atan2(math.sin(angle), math.cos(angle))
