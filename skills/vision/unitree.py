"""Vision on the G1: the head RealSense D435i, a YOLO ONNX detector, the robot's localisation.

The camera is read through ``pyrealsense2`` (extra ``realsense``); detections come from a local
YOLO export (option ``weights``, nothing is downloaded); each frame is placed in the map with the
localised pose heard on ``rt/unitree/slam_relocation/odom`` at that moment (the vendor SDK's DDS,
in this process only), not with the pose the request was sent with.

Options (besides the link settings in :mod:`stuart_bt.skills.vendor` and the camera loop's in
:mod:`.looking`): ``weights`` (required), ``names`` (class names file, default beside the
weights), ``resolution`` (424x240 | 640x480), ``fps`` (30), ``mount`` (sim: the URDF's numbers,
the default | thesis: theta 48 deg, d 0.04764 m, h 0.46268 m).
"""

from __future__ import annotations

import math
import threading
from typing import Any

from unitree_sdk2py.idl.nav_msgs.msg.dds_ import Odometry_

from stuart_bt.core.clock import Clock
from stuart_bt.core.world import Pose
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import StartupError
from stuart_bt.perception.frames import CameraError
from stuart_bt.perception.projection import CameraMount
from stuart_bt.perception.sim_camera import parse_resolution
from stuart_bt.skills import vendor

from .looking import LOOP_KEYS, CameraVision

ODOM_TOPIC = "rt/unitree/slam_relocation/odom"
OWN_OPTIONS = ("weights", "names", "resolution", "fps", "mount", *LOOP_KEYS)


class UnitreeVision(CameraVision):
    name = "unitree"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, {k: v for k, v in options.items() if k in LOOP_KEYS})
        self.options = options
        self.link = vendor.link_from(options, "vision", OWN_OPTIONS)
        where = "vision unitree options"
        mount_name = vendor.startup_option(lambda: a.string(options, "mount", where, default="sim",
                                                            choices=("sim", "thesis")))
        self._lock = threading.Lock()
        self._pose = Pose()
        vendor.connect(self.link)
        self._odometry = vendor.subscribe(ODOM_TOPIC, Odometry_, self._on_odometry)
        from stuart_bt.perception.realsense import RealSenseCamera
        from stuart_bt.perception.yolo import DetectorConfigError, YoloDetector

        try:
            width, height = parse_resolution(str(options.get("resolution", "424x240")))
            detector = YoloDetector(options.get("weights"), options.get("names"), self.threshold)
            camera = RealSenseCamera(width, height, int(options.get("fps", 30)), pose=self.pose, clock=clock.now)
        except (ValueError, DetectorConfigError, CameraError) as e:
            raise StartupError(f"vision unitree: {e}") from None
        self.attach(camera, detector, CameraMount.thesis() if mount_name == "thesis" else CameraMount.sim())

    def _on_odometry(self, msg: Odometry_) -> None:
        q = msg.pose.pose.orientation
        yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
        with self._lock:
            self._pose = Pose(float(msg.pose.pose.position.x), float(msg.pose.pose.position.y), yaw)

    def pose(self) -> Pose:
        with self._lock:
            return self._pose
