"""Pixels to places: median depth in a box, pinhole back-projection, camera -> torso -> world.

Frames (REP-103): the camera's *optical* frame has x right, y down, z forward (what depth
images and intrinsics use); the torso frame is torso_link (x forward, y left, z up); the world is
the map frame. The head camera is fixed on torso_link, pitched down (no yaw or roll), so the
mount is four numbers. The waist is held at zero while walking and perceiving, so torso_link
sits straight above the base at a fixed height and the localised base pose carries it to the map.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.world import Pose
from ..maps.viewpoints import CameraView
from ..sim.robot import description as desc
from .frames import Intrinsics

TORSO_HEIGHT = desc.PELVIS_HEIGHT + desc.WAIST_HEIGHT  # torso_link above the floor, standing, waist at zero
BODY_FROM_OPTICAL = np.array([[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])  # optical axes in x-forward terms
THESIS_THETA = math.radians(48.0)  # the original system's camera -> torso transform
THESIS_D = 0.04764
THESIS_H = 0.46268

Box = tuple[int, int, int, int]  # u0, v0, u1, v1: columns u0..u1-1, rows v0..v1-1


@dataclass(frozen=True)
class CameraMount:
    """Where the camera's optical centre sits on torso_link and how far it is pitched down."""

    x: float
    y: float
    z: float
    pitch: float  # radians, positive = looking down

    @classmethod
    def sim(cls) -> CameraMount:
        """The simulated G1's RealSense, from the robot description the sim model is built from."""
        x, y, z = desc.HEAD_CAMERA_XYZ
        return cls(x, y, z, desc.HEAD_CAMERA_PITCH)

    @classmethod
    def thesis(cls, theta: float = THESIS_THETA, d: float = THESIS_D, h: float = THESIS_H) -> CameraMount:
        """The original system's transform: the optical centre d ahead of and h above the torso
        origin, on the centre line, pitched theta down."""
        return cls(d, 0.0, h, theta)

    @property
    def rotation(self) -> np.ndarray:
        """Optical-frame vectors -> torso-frame vectors."""
        c, s = math.cos(self.pitch), math.sin(self.pitch)
        pitch_down = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
        return pitch_down @ BODY_FROM_OPTICAL

    @property
    def position(self) -> np.ndarray:
        return np.array([self.x, self.y, self.z])

    def to_torso(self, p_optical: np.ndarray) -> np.ndarray:
        return self.rotation @ np.asarray(p_optical, dtype=float) + self.position

    def to_optical(self, p_torso: np.ndarray) -> np.ndarray:
        return self.rotation.T @ (np.asarray(p_torso, dtype=float) - self.position)


def back_project(u: float, v: float, depth: float, k: Intrinsics) -> np.ndarray:
    """Pixel (u, v) at ``depth`` metres along the optical axis -> a point in the optical frame."""
    return np.array([depth * (u - k.cx) / k.fx, depth * (v - k.cy) / k.fy, depth])


def project(p_optical: np.ndarray, k: Intrinsics) -> tuple[float, float]:
    """The inverse: an optical-frame point in front of the camera -> pixel (u, v)."""
    x, y, z = p_optical
    return k.cx + k.fx * x / z, k.cy + k.fy * y / z


def shrink(box: Box, factor: float) -> Box:
    """The central part of a box (``factor`` of its width and height, at least one pixel): a
    detector's box is loose, its rim is table and wall, its centre is the object."""
    u0, v0, u1, v1 = box
    cu, cv = (u0 + u1) / 2, (v0 + v1) / 2
    hw, hh = max(0.5, (u1 - u0) * factor / 2), max(0.5, (v1 - v0) * factor / 2)
    return int(math.floor(cu - hw)), int(math.floor(cv - hh)), int(math.ceil(cu + hw)), int(math.ceil(cv + hh))


def median_depth(depth: np.ndarray, box: Box, factor: float = 0.5, mask: np.ndarray | None = None) -> float | None:
    """Median of the valid (> 0, finite) depths in the shrunk box, restricted to ``mask`` when
    the detector gives one; None when nothing there has a reading (dropouts, glare)."""
    u0, v0, u1, v1 = shrink(box, factor)
    h, w = depth.shape
    u0, v0, u1, v1 = max(0, u0), max(0, v0), min(w, u1), min(h, v1)
    patch = depth[v0:v1, u0:u1]
    valid = np.isfinite(patch) & (patch > 0)
    if mask is not None:
        valid &= mask[v0:v1, u0:u1]
    values = patch[valid]
    return float(np.median(values)) if values.size else None


def box_centre(box: Box) -> tuple[float, float]:
    """Pixel-centre coordinates of a box's middle (columns u0..u1-1 -> (u0 + u1 - 1) / 2)."""
    u0, v0, u1, v1 = box
    return (u0 + u1 - 1) / 2.0, (v0 + v1 - 1) / 2.0


def torso_to_world(p_torso: np.ndarray, pose: Pose) -> np.ndarray:
    c, s = math.cos(pose.yaw), math.sin(pose.yaw)
    x, y, z = p_torso
    return np.array([pose.x + c * x - s * y, pose.y + s * x + c * y, z + TORSO_HEIGHT])


def world_to_torso(p_world: np.ndarray, pose: Pose) -> np.ndarray:
    c, s = math.cos(pose.yaw), math.sin(pose.yaw)
    dx, dy = p_world[0] - pose.x, p_world[1] - pose.y
    return np.array([c * dx + s * dy, -s * dx + c * dy, p_world[2] - TORSO_HEIGHT])


def to_centre(surface: np.ndarray, mount: CameraMount, radius: float) -> np.ndarray:
    """A depth camera sees an object's near surface; its centre lies ``radius`` further away,
    horizontally, along the line of sight (upright objects: bottles, cups, fruit)."""
    if radius <= 0:
        return surface
    away = surface[:2] - mount.position[:2]
    norm = float(np.hypot(*away))
    if norm < 1e-9:
        return surface
    out = surface.copy()
    out[:2] += away / norm * radius
    return out


def head_camera_view(far: float = 2.0, margin: float = 0.8) -> CameraView:
    """The head camera as the loco daemon needs it to choose where to look from: the simulated
    G1's mount, standing, and the D435's narrower picture (4:3, 640x480: ~54 x 42 degrees), so a
    spot chosen for it sees the point in either of the modes the vision daemon may use."""
    half_v = math.radians(desc.HEAD_CAMERA_FOVY) / 2
    half_h = math.atan(math.tan(half_v) * 4 / 3)
    x, y, z = desc.HEAD_CAMERA_XYZ
    return CameraView(height=TORSO_HEIGHT + z, ahead=x, left=y, pitch=desc.HEAD_CAMERA_PITCH,
                      hfov=2 * half_h, vfov=2 * half_v, far=far, margin=margin)
