"""Simulated vision: the sim head camera through the whole perception pipeline.

While a ``find`` or ``look`` runs, this daemon asks the world for a frame at the camera's rate
in *sim* time, detects, projects and remembers (:mod:`.looking`); at any other time it renders
nothing, so a run that needs no vision keeps the sim's full speed.

Options: ``world`` (socket path, required), ``resolution`` (424x240 | 640x480),
``depth_noise`` (sigma at 1 m, m), ``dropout`` (fraction), ``seed``, and the camera loop's
(:mod:`.looking`).
"""

from __future__ import annotations

from typing import Any

from stuart_bt.core.clock import Clock
from stuart_bt.core.world import Pose
from stuart_bt.daemon.backend import DaemonError
from stuart_bt.perception.frames import CameraError
from stuart_bt.perception.projection import CameraMount
from stuart_bt.perception.sim_camera import DepthNoise, SimCamera, parse_resolution
from stuart_bt.perception.sim_detector import SimDetector
from stuart_bt.sim.world.client import WorldClient, WorldError

from .looking import CameraVision


class SimVision(CameraVision):
    name = "sim"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        if "world" not in options:
            raise ValueError("the sim vision backend needs the world's socket path (option 'world')")
        self.world = WorldClient(options["world"])
        width, height = parse_resolution(str(options.get("resolution", "424x240")))
        noise = DepthNoise(float(options.get("depth_noise", 0.0)), float(options.get("dropout", 0.0)))
        camera = SimCamera(self.world, width, height, noise, seed=int(options.get("seed", 0)))
        self.attach(camera, SimDetector(self.threshold), CameraMount.sim())
        self._warm_up(camera)

    @staticmethod
    def _warm_up(camera: SimCamera) -> None:
        """One frame before READY: the world's first render creates its GL context (~2 s), which
        belongs to start-up, not to the first find (a run without vision never pays it)."""
        try:
            camera.read()
        except CameraError as e:
            raise RuntimeError(f"the sim camera does not work: {e}") from None

    def in_hand(self, label: str, robot_pose: Pose) -> dict[str, float]:
        try:
            state = self.world.call("state")
        except WorldError as e:
            raise DaemonError("backend_error", f"world state: {e}") from None
        side = next((s for s, v in state.get("held", {}).items() if v == label), None)
        if side is None:
            return super().in_hand(label, robot_pose)
        x, y, z = state["hand_points"][side]
        return {"x": x, "y": y, "z": z}

    def close(self) -> None:
        super().close()
        self.world.close()
