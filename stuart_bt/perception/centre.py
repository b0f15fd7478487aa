"""From the surface a depth camera sees to the centre of the object behind it.

A depth camera sees the near side and the top of an object, and a box cut by the image border
sees even less, so the median-depth point (the original system's estimate) sits a few
centimetres in front of and above the object's centre. With the detector's mask, every masked
pixel becomes a 3D point in the torso frame and the centre is rebuilt from the parts of the
outline that are really visible, using the object's known shape:

- along the line of sight: the nearest visible surface (a low percentile) plus the radius;
- across it: the middle of the visible extent, or one visible edge plus the radius when the
  box is cut by the left or right border;
- height: the visible top minus the centre-to-top height, or (top cut off by the border) the
  visible bottom plus the base-to-centre height.

A label with no known shape keeps the median-depth point.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .frames import Intrinsics
from .projection import Box, CameraMount

EDGE_PERCENTILE = 1.0  # robust extremes of the point cloud (a stray pixel is not an edge)


@dataclass(frozen=True)
class Shape:
    """An upright object: horizontal radius, and how far its centre is above its base and
    below its top (the 'centre' is the point the world reports: the sim body's origin)."""

    radius: float
    base_to_centre: float
    centre_to_top: float


# The lab's objects (sim/scenes/lab.xml; the real ones were measured the same way).
SHAPES: dict[str, Shape] = {
    "bottle": Shape(0.035, 0.105, 0.125),
    "cup": Shape(0.04, 0.05, 0.05),
    "apple": Shape(0.04, 0.04, 0.04),
    "book": Shape(0.075, 0.016, 0.016),
}


def mask_points(mask: np.ndarray, depth: np.ndarray, k: Intrinsics, mount: CameraMount) -> np.ndarray:
    """Torso-frame points (N, 3) of the masked pixels that have a depth reading."""
    rows, cols = np.nonzero(mask)
    z = depth[rows, cols]
    ok = np.isfinite(z) & (z > 0)
    rows, cols, z = rows[ok], cols[ok], z[ok].astype(float)
    optical = np.stack([(cols - k.cx) / k.fx * z, (rows - k.cy) / k.fy * z, z], axis=1)
    return optical @ mount.rotation.T + mount.position


def centre_from_points(points: np.ndarray, rough: np.ndarray, shape: Shape, mount: CameraMount, box: Box,
                       size: tuple[int, int]) -> np.ndarray:
    """The object's centre in the torso frame from its visible surface points (see above);
    ``rough`` (the median-depth point) gives the line of sight."""
    width, height = size
    u0, v0, u1, v1 = box
    eye = mount.position[:2]
    ray = rough[:2] - eye
    ray = ray / max(1e-9, float(np.hypot(*ray)))
    side = np.array([-ray[1], ray[0]])  # to the left of the line of sight
    flat = points[:, :2] - eye
    along, across = flat @ ray, flat @ side
    lo, hi = EDGE_PERCENTILE, 100 - EDGE_PERCENTILE
    distance = float(np.percentile(along, lo)) + shape.radius
    if u0 <= 0 and u1 < width:  # left part cut off: the right edge (smallest 'across') is real
        lateral = float(np.percentile(across, lo)) + shape.radius
    elif u1 >= width and u0 > 0:
        lateral = float(np.percentile(across, hi)) - shape.radius
    else:
        lateral = 0.5 * float(np.percentile(across, lo) + np.percentile(across, hi))
    if v0 <= 0 < v1 < height:  # top cut off: trust the bottom
        z = float(np.percentile(points[:, 2], lo)) + shape.base_to_centre
    else:
        z = float(np.percentile(points[:, 2], hi)) - shape.centre_to_top
    xy = eye + distance * ray + lateral * side
    return np.array([xy[0], xy[1], z])
