"""What a detector returns and the interface every detector implements.

A detection is a label, a confidence in 0..1 and a box in pixels; sim detectors may add a mask
(the pixels they are sure of), which projection then prefers. The confidence threshold (0.75,
the original system's) is applied here, once, for every detector.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any

import numpy as np

from .frames import Frame
from .projection import Box

DEFAULT_THRESHOLD = 0.75


@dataclass
class Detection:
    label: str
    confidence: float
    box: Box  # u0, v0, u1, v1 (u1, v1 exclusive)
    mask: np.ndarray | None = None  # (H, W) bool, optional

    def to_dict(self) -> dict[str, Any]:
        return {"label": self.label, "confidence": round(self.confidence, 3), "box": [int(v) for v in self.box]}


class Detector(ABC):
    name = "detector"

    def __init__(self, threshold: float = DEFAULT_THRESHOLD) -> None:
        if not 0.0 <= threshold <= 1.0:
            raise ValueError(f"confidence threshold must be in 0..1, got {threshold}")
        self.threshold = threshold

    @abstractmethod
    def candidates(self, frame: Frame) -> list[Detection]:
        """Every detection, whatever its confidence."""

    def detect(self, frame: Frame) -> list[Detection]:
        """Detections at or above the threshold, most confident first."""
        kept = [d for d in self.candidates(frame) if d.confidence >= self.threshold]
        return sorted(kept, key=lambda d: -d.confidence)
