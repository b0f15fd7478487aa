"""The robot's head camera: an Intel RealSense D435i through ``pyrealsense2`` (extra ``realsense``).

Depth is aligned to the colour stream so one pixel means one place in both. The robot's pose at
each frame comes from a callable the caller provides (the localisation), since the camera knows
nothing of the map.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable

import numpy as np

from ..core.world import Pose
from .frames import CameraError, CameraSource, Frame, Intrinsics


class RealSenseCamera(CameraSource):
    name = "realsense"

    def __init__(self, width: int = 424, height: int = 240, fps: int = 30,
                 pose: Callable[[], Pose] = Pose, clock: Callable[[], float] | None = None) -> None:
        try:
            import pyrealsense2 as rs
        except ImportError:
            raise CameraError("the RealSense camera needs pyrealsense2: pip install 'stuart-bt[realsense]'") from None
        self._rs = rs
        self.pose = pose
        self.clock = clock
        self.pipeline = rs.pipeline()
        config = rs.config()
        config.enable_stream(rs.stream.color, width, height, rs.format.rgb8, fps)
        config.enable_stream(rs.stream.depth, width, height, rs.format.z16, fps)
        try:
            profile = self.pipeline.start(config)
        except RuntimeError as e:
            raise CameraError(f"no RealSense at {width}x{height}@{fps}: {e}") from None
        self.depth_scale = profile.get_device().first_depth_sensor().get_depth_scale()
        self.align = rs.align(rs.stream.color)
        k = profile.get_stream(rs.stream.color).as_video_stream_profile().get_intrinsics()
        self.intrinsics = Intrinsics(k.fx, k.fy, k.ppx, k.ppy, k.width, k.height)

    def read(self) -> Frame:
        frames = self.align.process(self.pipeline.wait_for_frames())
        colour, depth = frames.get_color_frame(), frames.get_depth_frame()
        if not colour or not depth:
            raise CameraError("RealSense gave an incomplete frame")
        t = self.clock() if self.clock else frames.get_timestamp() / 1000.0
        return Frame(np.asanyarray(colour.get_data()).copy(),
                     np.asanyarray(depth.get_data()).astype(np.float32) * self.depth_scale,
                     self.intrinsics, t, self.pose())

    def close(self) -> None:
        with contextlib.suppress(RuntimeError):
            self.pipeline.stop()
