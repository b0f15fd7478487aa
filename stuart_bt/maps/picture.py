"""The map picture: the occupancy map with what happened on it, for people to look at.

Drawn for the world server's ``--map-out`` and ``map`` command, a run's report and
``stuart-bt perceive``; it needs Pillow (the ``sim`` extra), imported only when drawing.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..core.world import Marker
from .grid import OccupancyGrid


def draw_map_png(grid: OccupancyGrid, markers: Mapping[str, Marker],
                 path_points: Sequence[tuple[float, float]], objects: Mapping[str, Mapping[str, float]],
                 out_path: str | Path, scale: int = 4, memory: Sequence[Mapping[str, Any]] = ()) -> Path:
    """The map with what happened on it: obstacles (and their inflation), named markers with
    their headings, the driven path (start green, end red), the objects where they are, and the
    spatial memory (``memory``: entries of a memory summary, drawn as rings sized by their
    confidence, so where the robot *believes* things are can be compared with where they are)."""
    from PIL import Image, ImageDraw, ImageFont

    rows, cols = grid.shape
    rgb = np.full((rows, cols, 3), 255, dtype=np.uint8)
    rgb[grid.inflated] = (225, 228, 235)
    if grid.known is not None:
        rgb[~grid.known] = (190, 190, 190)
    rgb[grid.occupied] = (60, 60, 70)
    big = np.repeat(np.repeat(rgb, scale, axis=0), scale, axis=1)
    free = (big == 255).all(axis=2)
    for k in range(math.ceil(grid.origin[0]), math.floor(grid.origin[0] + cols * grid.resolution) + 1):
        c = int(round((k - grid.origin[0]) / grid.resolution * scale))  # a light 1 m grid on free space
        if 0 <= c < big.shape[1]:
            big[free[:, c], c] = (232, 236, 242)
    for k in range(math.ceil(grid.origin[1]), math.floor(grid.origin[1] + rows * grid.resolution) + 1):
        row = int(round((k - grid.origin[1]) / grid.resolution * scale))
        if 0 <= row < big.shape[0]:
            big[row, free[row, :]] = (232, 236, 242)
    image = Image.fromarray(np.flipud(big).copy())
    draw = ImageDraw.Draw(image)
    try:
        font = ImageFont.load_default(size=max(10, 3 * scale))
    except TypeError:  # Pillow < 10.1
        font = ImageFont.load_default()

    def px(x: float, y: float) -> tuple[float, float]:
        return ((x - grid.origin[0]) / grid.resolution * scale, (rows - (y - grid.origin[1]) / grid.resolution) * scale)

    metre = scale / grid.resolution
    if len(path_points) >= 2:
        draw.line([px(x, y) for x, y in path_points], fill=(30, 110, 230), width=max(2, scale // 2))
    if path_points:
        for (x, y), colour in ((path_points[0], (40, 170, 60)), (path_points[-1], (220, 40, 40))):
            cx, cy = px(x, y)
            r = 0.08 * metre
            draw.ellipse([cx - r, cy - r, cx + r, cy + r], fill=colour)
    for name, m in markers.items():
        cx, cy = px(m.x, m.y)
        r = 0.1 * metre
        draw.ellipse([cx - r, cy - r, cx + r, cy + r], outline=(200, 120, 0), width=2)
        tip = px(m.x + 0.3 * math.cos(m.yaw), m.y + 0.3 * math.sin(m.yaw))
        draw.line([(cx, cy), tip], fill=(200, 120, 0), width=2)
        draw.text((cx + r + 2, cy - r - 2), name, fill=(140, 80, 0), font=font, stroke_width=2,
                  stroke_fill=(255, 255, 255))
    for label, o in objects.items():
        cx, cy = px(float(o["x"]), float(o["y"]))
        r = 0.05 * metre
        draw.rectangle([cx - r, cy - r, cx + r, cy + r], fill=(200, 30, 120))
        draw.text((cx + r + 2, cy + 1), label, fill=(150, 20, 90), font=font, stroke_width=2,
                  stroke_fill=(255, 255, 255))
    for entry in memory:
        cx, cy = px(float(entry["x"]), float(entry["y"]))
        r = (0.06 + 0.08 * max(0.0, min(1.0, float(entry.get("confidence", 1.0))))) * metre
        draw.ellipse([cx - r, cy - r, cx + r, cy + r], outline=(0, 150, 170), width=max(2, scale // 2))
        draw.text((cx + r + 2, cy - r - 2 * scale), f"{entry.get('id', entry.get('label', '?'))} "
                  f"{float(entry.get('confidence', 1.0)):.2f}", fill=(0, 110, 130), font=font, stroke_width=2,
                  stroke_fill=(255, 255, 255))
    out_path = Path(out_path)
    out_path.parent.mkdir(parents=True, exist_ok=True)
    image.save(out_path)
    return out_path
