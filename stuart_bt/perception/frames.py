"""One RGB-D frame and the interface every camera source implements.

A frame carries what projection needs and nothing else: colour, metric depth, the pinhole
intrinsics, the time it was taken (on the shared clock) and the robot's localised pose at that
time, so a frame can be projected to the world long after it was taken (replay, tests).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core.errors import StuartError
from ..core.world import Pose


@dataclass(frozen=True)
class Intrinsics:
    """Pinhole intrinsics, pixels (u, v) = (column, row) from the top-left pixel's centre."""

    fx: float
    fy: float
    cx: float
    cy: float
    width: int
    height: int

    @classmethod
    def from_fov(cls, width: int, height: int, fovy_deg: float) -> Intrinsics:
        """Square pixels, principal point at the image centre (what the sim renders)."""
        import math

        f = 0.5 * height / math.tan(math.radians(fovy_deg) / 2)
        return cls(f, f, (width - 1) / 2.0, (height - 1) / 2.0, width, height)

    def to_dict(self) -> dict[str, float]:
        return {"fx": self.fx, "fy": self.fy, "cx": self.cx, "cy": self.cy, "width": self.width, "height": self.height}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Intrinsics:
        return cls(float(d["fx"]), float(d["fy"]), float(d["cx"]), float(d["cy"]), int(d["width"]), int(d["height"]))


@dataclass
class Frame:
    rgb: np.ndarray  # (H, W, 3) uint8
    depth: np.ndarray  # (H, W) float32 metres along the optical axis; 0 = no reading
    intrinsics: Intrinsics
    t: float = 0.0  # clock time the frame was taken
    robot_pose: Pose = field(default_factory=Pose)  # localised base pose at t (map frame)
    labels: np.ndarray | None = None  # (H, W) int16 label index per pixel, -1 none (sim / recorded only)
    label_names: tuple[str, ...] = ()

    @property
    def size(self) -> tuple[int, int]:
        return int(self.rgb.shape[1]), int(self.rgb.shape[0])


class CameraSource(ABC):
    """Where frames come from: the sim head camera, a RealSense, a folder of recorded frames."""

    name = "camera"

    @abstractmethod
    def read(self) -> Frame:
        """The next frame (blocks until there is one); raises :class:`CameraError` on failure."""

    def close(self) -> None:  # noqa: B027 - a hook: sources with a device override it
        """Release the device or connection."""

    def __enter__(self) -> CameraSource:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class CameraError(StuartError, RuntimeError):
    """A camera that cannot give frames (missing device, file, driver): one clear sentence."""
