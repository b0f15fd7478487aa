"""The simulated head camera: RGB, depth and segmentation rendered by the world on request.

Rendering is the simulator's bottleneck, so nothing renders unless a frame is read. Frames come
back through raw ``.npy`` files in a private scratch directory under /dev/shm (no PNG encoding,
no pixels in JSON). The RealSense's imperfections are optional: depth noise growing with the
square of the distance (a stereo camera's error model) and random dropouts (pixels with no
reading, which the projection must skip).
"""

from __future__ import annotations

import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from ..core.world import Pose
from .frames import CameraError, CameraSource, Frame, Intrinsics

RESOLUTIONS = {"424x240": (424, 240), "640x480": (640, 480)}  # the D435's usual modes


class WorldCaller(Protocol):
    """What the camera needs of the simulator: one request, one reply."""

    def call(self, cmd: str, **args: Any) -> dict[str, Any]: ...


@dataclass(frozen=True)
class DepthNoise:
    """sigma(z) = ``sigma_at_1m`` x z^2 metres; ``dropout`` = fraction of pixels with no reading."""

    sigma_at_1m: float = 0.0
    dropout: float = 0.0

    @property
    def active(self) -> bool:
        return self.sigma_at_1m > 0 or self.dropout > 0

    def apply(self, depth: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        out = depth.astype(np.float32, copy=True)
        if self.sigma_at_1m > 0:
            out += (rng.standard_normal(out.shape) * self.sigma_at_1m * out * out).astype(np.float32)
        if self.dropout > 0:
            out[rng.random(out.shape) < self.dropout] = 0.0
        return out


def parse_resolution(text: str) -> tuple[int, int]:
    if text not in RESOLUTIONS:
        from ..core.suggest import did_you_mean

        raise ValueError(f"unknown resolution {text!r}{did_you_mean(text, RESOLUTIONS)}; "
                         f"valid: {', '.join(RESOLUTIONS)}")
    return RESOLUTIONS[text]


class SimCamera(CameraSource):
    name = "sim"

    def __init__(self, world: WorldCaller, width: int = 424, height: int = 240, noise: DepthNoise | None = None,
                 seed: int = 0, far: float = 10.0) -> None:
        """``world`` is a :class:`~stuart_bt.sim.world.client.WorldClient` (or anything with its
        ``call``); depths beyond ``far`` metres (walls far away, the sky) read as no reading."""
        self.world = world
        self.width, self.height = width, height
        self.noise = noise or DepthNoise()
        self.rng = np.random.default_rng(seed)
        self.far = far
        self.last_pose = Pose()  # the localised pose of the latest frame
        self._dir = Path(tempfile.mkdtemp(prefix="stuart_cam_", dir="/dev/shm" if Path("/dev/shm").is_dir() else None))

    def read(self) -> Frame:
        from ..sim.world.client import WorldError

        try:
            reply = self.world.call("render", camera="head_camera", width=self.width, height=self.height, depth=True,
                                    labels=True, path=str(self._dir / "rgb.npy"))
        except WorldError as e:
            raise CameraError(f"sim camera: {e}") from None
        depth = np.load(reply["depth_path"])
        depth[~np.isfinite(depth) | (depth > self.far)] = 0.0
        if self.noise.active:
            depth = self.noise.apply(depth, self.rng)
        k = reply["intrinsics"]
        self.last_pose = Pose.from_dict(reply["base"])
        return Frame(
            rgb=np.load(reply["path"]), depth=depth,
            intrinsics=Intrinsics(k["fx"], k["fy"], k["cx"], k["cy"], self.width, self.height),
            t=float(reply["t"]), robot_pose=self.last_pose,
            labels=np.load(reply["labels_path"]), label_names=tuple(reply["label_names"]),
        )

    def close(self) -> None:
        shutil.rmtree(self._dir, ignore_errors=True)
