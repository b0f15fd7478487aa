"""One frame through the whole pipeline: detect, project each box, remember.

Kept free of any process or clock loop so the vision daemon, ``stuart-bt perceive``, the tests
and the benchmark all run the very same steps.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .centre import SHAPES, Shape, centre_from_points, mask_points
from .detect import Detection, Detector
from .frames import Frame
from .memory import Observation, Remembered, SpatialMemory
from .projection import CameraMount, back_project, box_centre, median_depth, to_centre, torso_to_world

BOX_SHRINK = 0.5  # median depth over the central half of the box
MIN_POINTS = 20  # fewer masked pixels with depth than this: keep the median-depth estimate


@dataclass
class Located:
    detection: Detection
    depth: float  # metres, median in the shrunk box
    pixel: tuple[float, float]  # the pixel projected (box centre, or the mask's centroid)
    torso: np.ndarray  # object centre, torso_link frame
    world: np.ndarray  # object centre, map frame

    def to_dict(self) -> dict[str, Any]:
        return {**self.detection.to_dict(), "depth": round(self.depth, 4),
                "torso": [round(float(v), 4) for v in self.torso], "world": [round(float(v), 4) for v in self.world]}


@dataclass
class Perception:
    detector: Detector
    mount: CameraMount
    memory: SpatialMemory | None = None
    shapes: dict[str, Shape] = field(default_factory=lambda: dict(SHAPES))
    box_shrink: float = BOX_SHRINK

    def locate(self, frame: Frame, detection: Detection) -> Located | None:
        """Place one detection; None when its box has no depth reading."""
        depth = median_depth(frame.depth, detection.box, self.box_shrink, detection.mask)
        if depth is None:
            return None
        u, v = box_centre(detection.box)
        surface = self.mount.to_torso(back_project(u, v, depth, frame.intrinsics))
        shape = self.shapes.get(detection.label)
        torso = to_centre(surface, self.mount, shape.radius) if shape else surface
        if shape is not None and detection.mask is not None:
            points = mask_points(detection.mask, frame.depth, frame.intrinsics, self.mount)
            if len(points) >= MIN_POINTS:
                torso = centre_from_points(points, surface, shape, self.mount, detection.box, frame.size)
        return Located(detection, depth, (u, v), torso, torso_to_world(torso, frame.robot_pose))

    def process(self, frame: Frame) -> tuple[list[Located], list[Remembered]]:
        """Detect, locate and (with a memory) remember; returns the located detections and the
        memory entries they touched."""
        located = [p for d in self.detector.detect(frame) if (p := self.locate(frame, d)) is not None]
        touched: list[Remembered] = []
        if self.memory is not None:
            observations = [Observation(p.detection.label, *_xyz(p.world), p.detection.confidence) for p in located]
            touched = self.memory.update(observations, frame.t)
        return located, touched


def _xyz(world: Any) -> tuple[float, float, float]:
    x, y, z = (float(v) for v in world)
    return x, y, z
