"""Cameras on demand and recordings in sim time.

Rendering is the simulator's most expensive operation (a CPU rasteriser on a machine without a
GPU), so the world renders only when asked: a ``render`` request, or a recording whose next
frame is due in *sim* time. A recording at 10 fps therefore shows 10 frames per sim second
whatever the world's speed, and plays back at real time.

Image conventions for the vision code: pixel (u, v) = (column, row) from the top-left; the
intrinsics are pinhole with square pixels; depth is metric distance along the optical axis
(what a RealSense reports), and the camera pose is given for the *optical* frame (x right,
y down, z forward), so a pixel at depth z is at
``position + R @ [z (u - cx) / fx, z (v - cy) / fy, z]`` in the world.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

MAX_RENDERERS = 4  # GL contexts kept (one per image size)
OPTICAL_FROM_MUJOCO = np.diag([1.0, -1.0, -1.0])  # MuJoCo cameras look along -z with y up


@dataclass
class Frame:
    rgb: np.ndarray  # (H, W, 3) uint8
    depth: np.ndarray | None  # (H, W) float32 metres along the optical axis
    intrinsics: dict[str, float]
    pose: dict[str, Any]
    labels: np.ndarray | None = None  # (H, W) int16: index into the label names, -1 for nothing labelled


def intrinsics(model: mujoco.MjModel, camera: int, width: int, height: int) -> dict[str, float]:
    """Pinhole intrinsics of a MuJoCo camera rendered at ``width`` x ``height``.

    MuJoCo fixes the vertical field of view; pixels are square, so fx = fy. The principal
    point is the image centre in pixel-index coordinates (pixel centres at integers).
    """
    fovy = math.radians(float(model.cam_fovy[camera]))
    f = 0.5 * height / math.tan(0.5 * fovy)
    return {"fx": f, "fy": f, "cx": (width - 1) / 2.0, "cy": (height - 1) / 2.0}


def camera_pose(data: mujoco.MjData, camera: int) -> dict[str, Any]:
    """World pose of the camera's optical frame: position and rotation (rows of a 3x3)."""
    rotation = data.cam_xmat[camera].reshape(3, 3) @ OPTICAL_FROM_MUJOCO
    return {"position": [round(float(v), 6) for v in data.cam_xpos[camera]],
            "rotation": [[round(float(v), 7) for v in row] for row in rotation],
            "frame": "optical (x right, y down, z forward)"}


class Cameras:
    """Offscreen rendering of the model's named cameras (one GL context per image size)."""

    def __init__(self, model: mujoco.MjModel) -> None:
        self.model = model
        self._renderers: dict[tuple[int, int], mujoco.Renderer] = {}
        self.option = mujoco.MjvOption()
        self.option.sitegroup[:] = 0  # hand points and the lidar are markers, not things to see

    def camera_id(self, camera: str | int) -> int:
        if isinstance(camera, int):
            if not 0 <= camera < self.model.ncam:
                raise KeyError(f"no camera {camera}")
            return camera
        return self.model.camera(camera).id  # KeyError when unknown

    def limits(self) -> tuple[int, int]:
        return int(self.model.vis.global_.offwidth), int(self.model.vis.global_.offheight)

    def _renderer(self, width: int, height: int) -> mujoco.Renderer:
        key = (width, height)
        renderer = self._renderers.get(key)
        if renderer is None:
            if len(self._renderers) >= MAX_RENDERERS:
                old_key = next(iter(self._renderers))
                self._renderers.pop(old_key).close()
            renderer = mujoco.Renderer(self.model, height=height, width=width)
            self._renderers[key] = renderer
        return renderer

    def render(self, data: mujoco.MjData, camera: str | int, width: int, height: int, depth: bool = False,
               geom_labels: np.ndarray | None = None) -> Frame:
        """One frame; with ``geom_labels`` (label index per geom id, -1 for none) also the
        renderer's segmentation mapped to those labels (the sim detector's ground truth pixels)."""
        cam = self.camera_id(camera)
        renderer = self._renderer(width, height)
        renderer.update_scene(data, camera=cam, scene_option=self.option)
        rgb = renderer.render().copy()
        depth_image = None
        if depth:
            renderer.enable_depth_rendering()
            try:
                renderer.update_scene(data, camera=cam, scene_option=self.option)
                depth_image = renderer.render().astype(np.float32)
            finally:
                renderer.disable_depth_rendering()
        labels = None
        if geom_labels is not None:
            renderer.enable_segmentation_rendering()
            try:
                renderer.update_scene(data, camera=cam, scene_option=self.option)
                segmentation = renderer.render()
            finally:
                renderer.disable_segmentation_rendering()
            labels = segment_labels(segmentation, geom_labels)
        return Frame(rgb, depth_image, intrinsics(self.model, cam, width, height), camera_pose(data, cam), labels)

    def close(self) -> None:
        for renderer in self._renderers.values():
            renderer.close()
        self._renderers.clear()


def segment_labels(segmentation: np.ndarray, geom_labels: np.ndarray) -> np.ndarray:
    """MuJoCo's segmentation image (object id, object type per pixel) -> a label index image:
    pixels showing a labelled geom get its label's index, everything else -1."""
    ids, types = segmentation[:, :, 0], segmentation[:, :, 1]
    is_geom = (types == int(mujoco.mjtObj.mjOBJ_GEOM)) & (ids >= 0) & (ids < len(geom_labels))
    labels = np.full(ids.shape, -1, dtype=np.int16)
    labels[is_geom] = geom_labels[ids[is_geom]]
    return labels


def save_png(rgb: np.ndarray, path: str | Path) -> Path:
    from PIL import Image

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(rgb).save(path)
    return path


class Recorder:
    """Frames of one camera at ``fps`` of sim time, into an mp4 (ffmpeg via imageio-ffmpeg) or
    a gif (Pillow, written when the recording stops)."""

    def __init__(self, path: str | Path, fps: float, cameras: Cameras, camera: str = "chase",
                 width: int | None = None, height: int | None = None, start: float = 0.0) -> None:
        self.path = Path(path)
        suffix = self.path.suffix.lower()
        if suffix not in (".mp4", ".gif"):
            raise ValueError(f"record to .mp4 or .gif, not {self.path.name!r}")
        if not fps > 0:
            raise ValueError(f"fps must be positive, got {fps}")
        self.gif = suffix == ".gif"
        self.fps = float(fps)
        self.cameras = cameras
        self.camera = cameras.camera_id(camera)
        default = (400, 300) if self.gif else (640, 480)
        self.width = int(width or default[0])
        self.height = int(height or default[1])
        self.frames = 0
        self.next_t = start
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._gif_frames: list[Any] = []
        self._writer: Any = None
        if not self.gif:
            import imageio.v2 as imageio

            self._writer = imageio.get_writer(str(self.path), format="FFMPEG", mode="I", fps=self.fps,
                                              codec="libx264", quality=7, macro_block_size=16,
                                              ffmpeg_log_level="error")

    def due(self, t: float) -> bool:
        return t >= self.next_t

    def capture(self, data: mujoco.MjData, t: float) -> None:
        """Add one frame (call when :meth:`due`); a world too slow for the frame rate skips
        frames rather than bunching them."""
        rgb = self.cameras.render(data, self.camera, self.width, self.height).rgb
        if self.gif:
            from PIL import Image

            self._gif_frames.append(Image.fromarray(rgb).quantize(colors=128, method=Image.Quantize.FASTOCTREE))
        else:
            self._writer.append_data(rgb)
        self.frames += 1
        period = 1.0 / self.fps
        self.next_t += period
        if self.next_t <= t:
            self.next_t = t + period

    def close(self) -> dict[str, Any]:
        if self.gif:
            if self._gif_frames:
                first, rest = self._gif_frames[0], self._gif_frames[1:]
                first.save(self.path, save_all=True, append_images=rest, duration=max(20, round(1000 / self.fps)),
                           loop=0, optimize=False)
            self._gif_frames = []
        elif self._writer is not None:
            self._writer.close()
            self._writer = None
        return {"path": str(self.path), "frames": self.frames, "fps": self.fps}
