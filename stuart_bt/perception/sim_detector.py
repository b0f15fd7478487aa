"""A detector for the simulator that fails the way a real one does.

It starts from the renderer's segmentation (which pixels show which object) and turns each
connected blob into a box, then behaves like a trained detector looking at those pixels: a small
or far object gets a low confidence, a blob cut by the image border is clipped and less certain,
a partly hidden object is less certain than a whole one. Below the threshold it is missed.
Two objects of one class are two blobs, hence two detections.

Confidence = size term (saturating at ``full_pixels`` pixels) x border penalty x occlusion
term (visible pixels / pixels of the blob's own filled box, a hidden part leaves holes).
"""

from __future__ import annotations

import cv2
import numpy as np

from .detect import DEFAULT_THRESHOLD, Detection, Detector
from .frames import Frame

MIN_PIXELS = 12  # below this a blob is noise, not an object
FULL_PIXELS = 400  # a blob this big (about 20 x 20 px) is seen as well as it can be
BORDER_PENALTY = 0.8  # a box touching the image border
FILL_FLOOR = 0.35  # the box fill ratio at which occlusion alone drops confidence to zero


class SimDetector(Detector):
    name = "sim"

    def __init__(self, threshold: float = DEFAULT_THRESHOLD, full_pixels: int = FULL_PIXELS,
                 min_pixels: int = MIN_PIXELS) -> None:
        super().__init__(threshold)
        self.full_pixels = full_pixels
        self.min_pixels = min_pixels

    def candidates(self, frame: Frame) -> list[Detection]:
        if frame.labels is None:
            raise ValueError("the sim detector needs the renderer's segmentation (render with labels)")
        out: list[Detection] = []
        height, width = frame.labels.shape
        for index, label in enumerate(frame.label_names):
            mask = (frame.labels == index).astype(np.uint8)
            if not mask.any():
                continue
            count, blobs, stats, _ = cv2.connectedComponentsWithStats(mask, connectivity=8)
            for blob in range(1, count):
                u0, v0, w, h, pixels = (int(v) for v in stats[blob])
                if pixels < self.min_pixels:
                    continue
                box = (u0, v0, u0 + w, v0 + h)
                out.append(Detection(label, self._confidence(pixels, box, width, height), box, blobs == blob))
        return out

    def _confidence(self, pixels: int, box: tuple[int, int, int, int], width: int, height: int) -> float:
        u0, v0, u1, v1 = box
        size = min(1.0, (pixels / self.full_pixels) ** 0.5)
        border = BORDER_PENALTY if u0 <= 0 or v0 <= 0 or u1 >= width or v1 >= height else 1.0
        fill = pixels / max(1, (u1 - u0) * (v1 - v0))
        occlusion = min(1.0, max(0.0, (fill - FILL_FLOOR) / (0.7 - FILL_FLOOR)))  # a disc fills ~0.79
        return round(0.5 + 0.5 * size * border * occlusion, 4)
