"""The picture a person looks at: the camera image with each detection's box, label,
confidence and depth, and where it was placed in the map."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import cv2
import numpy as np

from .pipeline import Located

BOX_COLOUR = (255, 200, 0)  # RGB
TEXT_COLOUR = (255, 255, 255)
SHADOW = (0, 0, 0)


def annotate(rgb: np.ndarray, located: Sequence[Located]) -> np.ndarray:
    """A copy of ``rgb`` with the detections drawn on it: the box, a cross at the pixel that was
    projected, and two lines on a dark band (label, confidence, depth; the map position)."""
    image = np.ascontiguousarray(rgb.copy())
    scale = 0.35 if image.shape[0] < 400 else 0.55
    thick = 1 if image.shape[0] < 400 else 2
    font = cv2.FONT_HERSHEY_SIMPLEX
    for p in located:
        u0, v0, u1, v1 = p.detection.box
        cv2.rectangle(image, (u0, v0), (u1 - 1, v1 - 1), BOX_COLOUR, thick)
        cv2.drawMarker(image, (int(round(p.pixel[0])), int(round(p.pixel[1]))), BOX_COLOUR, cv2.MARKER_CROSS, 8, 1)
        lines = [f"{p.detection.label} {p.detection.confidence:.2f} {p.depth:.2f}m",
                 f"({p.world[0]:.2f},{p.world[1]:.2f},{p.world[2]:.2f})"]
        sizes = [cv2.getTextSize(t, font, scale, 1)[0] for t in lines]
        line_h = max(h for _, h in sizes) + 4
        band_w, band_h = max(w for w, _ in sizes) + 4, line_h * len(lines) + 2
        top = v1 + 1 if v1 + band_h < image.shape[0] else max(0, v0 - band_h - 1)
        left = min(max(0, u0), max(0, image.shape[1] - band_w))
        cv2.rectangle(image, (left, top), (left + band_w, top + band_h), SHADOW, -1)
        for i, text in enumerate(lines):
            cv2.putText(image, text, (left + 2, top + (i + 1) * line_h - 2), font, scale, TEXT_COLOUR, 1, cv2.LINE_AA)
    return image


def save_annotated(rgb: np.ndarray, located: Sequence[Located], path: str | Path) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if not cv2.imwrite(str(path), cv2.cvtColor(annotate(rgb, located), cv2.COLOR_RGB2BGR)):
        raise OSError(f"could not write {path} (use .png or .jpg)")
    return path
