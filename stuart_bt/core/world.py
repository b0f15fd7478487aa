"""The world state the planner and the leaves share: pose, held object, known objects, markers.

It lives on the blackboard under the key ``world`` (see :mod:`stuart_bt.core.blackboard`), so tree
expressions can read it (``world.held == 'bottle'``) and every leaf updates it from its daemon's
results (navigate -> pose, pick -> held). Units and frames follow REP-103: metres, radians, map
frame x forward / y left, yaw counter-clockwise. Marker files are read and written by
:mod:`stuart_bt.maps.markers`.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

from .errors import StuartError
from .jsonfile import is_finite_number


@dataclass
class Pose:
    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0

    def distance_to(self, other: Pose) -> float:
        return math.hypot(other.x - self.x, other.y - self.y)

    def to_dict(self) -> dict[str, float]:
        return {"x": round(self.x, 4), "y": round(self.y, 4), "yaw": round(self.yaw, 4)}

    @classmethod
    def from_dict(cls, d: Any) -> Pose:
        """A pose from daemon or file data; an absent (or null) axis is 0. A present one that is
        not a finite number (a string, a bool, NaN, infinity) raises :class:`PoseError` naming the
        field, so a bad number never becomes the robot's pose."""
        if not isinstance(d, dict):
            raise PoseError(f"a pose must be an object with x, y and yaw, got {type(d).__name__}")
        return cls(_finite(d, "x"), _finite(d, "y"), _finite(d, "yaw"))

    @classmethod
    def facing(cls, x: float, y: float, heading: float, ahead: float, left: float = 0.0) -> Pose:
        """The pose with ``heading`` from which the map point (x, y) is ``ahead`` metres in front
        and ``left`` metres to the left (REP-103): where to stand to reach or look at it."""
        cos, sin = math.cos(heading), math.sin(heading)
        return cls(x - ahead * cos + left * sin, y - ahead * sin - left * cos, heading)


class PoseError(StuartError, ValueError):
    """Pose data that is not three finite numbers."""


def _finite(d: dict[str, Any], axis: str) -> float:
    value = d.get(axis)
    if value is None:
        return 0.0
    if not is_finite_number(value):
        raise PoseError(f"pose {axis!r} must be a finite number, got {value!r:.40}")
    return float(value)


@dataclass(frozen=True)
class Marker:
    name: str
    x: float
    y: float
    yaw: float = 0.0
    display_name: str = ""

    @property
    def pose(self) -> Pose:
        return Pose(self.x, self.y, self.yaw)

    @property
    def label(self) -> str:
        return self.display_name or self.name.replace("_", " ")


@dataclass
class KnownObject:
    label: str
    x: float
    y: float
    z: float = 0.0
    confidence: float = 1.0
    seen_at: float = 0.0
    source: str = "catalogue"  # "vision": placed by perception (pick then aims at this position)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


@dataclass
class WorldState:
    pose: Pose = field(default_factory=Pose)
    held: str | None = None  # label of the object in hand
    held_arm: str | None = None
    objects: dict[str, KnownObject] = field(default_factory=dict)
    markers: dict[str, Marker] = field(default_factory=dict)
    last_marker: str | None = None  # the marker most recently arrived at

    @property
    def holding(self) -> bool:
        return self.held is not None

    def to_dict(self) -> dict[str, Any]:
        return {
            "pose": self.pose.to_dict(),
            "held": self.held,
            "held_arm": self.held_arm,
            "objects": {k: v.to_dict() for k, v in self.objects.items()},
            "markers": sorted(self.markers),
            "last_marker": self.last_marker,
        }
