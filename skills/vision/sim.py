"""Simulated vision: the sim head camera through the whole perception pipeline.

While a ``find`` or ``look`` runs, this daemon asks the world for a frame at the camera's rate
in *sim* time (``rate``, default 15 Hz), detects, projects and remembers; at any other time it
renders nothing, so a run that needs no vision keeps the sim's full speed.

Options: ``world`` (socket path, required), ``resolution`` (424x240 | 640x480), ``rate`` (Hz),
``threshold`` (0.75), ``sightings`` (frames that must see the object before find succeeds, 3),
``max_frames`` (frames find looks before it gives up, 12), ``depth_noise`` (sigma at 1 m, m),
``dropout`` (fraction), ``seed``, and the memory's ``match_radius``, ``smoothing``,
``decay_after``, ``decay_rate``, ``drop_below``.
"""

from __future__ import annotations

import math
from typing import Any

from stuart_bt.clock import Clock
from stuart_bt.daemon.backend import Activity, DaemonError, Done, Progress
from stuart_bt.perception.memory import MemoryConfig, SpatialMemory
from stuart_bt.perception.pipeline import Located, Perception
from stuart_bt.perception.projection import CameraMount
from stuart_bt.perception.sim_camera import DepthNoise, SimCamera, parse_resolution
from stuart_bt.perception.sim_detector import SimDetector
from stuart_bt.perception.frames import CameraError
from stuart_bt.sim.world.client import WorldClient, WorldError
from stuart_bt.world import Pose

from .activities import Instant
from .backend import VisionBackend

MEMORY_KEYS = ("match_radius", "smoothing", "decay_after", "decay_rate", "drop_below")


class SimVision(VisionBackend):
    name = "sim"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        if "world" not in options:
            raise ValueError("the sim vision backend needs the world's socket path (option 'world')")
        self.world = WorldClient(options["world"])
        width, height = parse_resolution(str(options.get("resolution", "424x240")))
        noise = DepthNoise(float(options.get("depth_noise", 0.0)), float(options.get("dropout", 0.0)))
        self.camera = SimCamera(self.world, width, height, noise, seed=int(options.get("seed", 0)))
        self.period = 1.0 / float(options.get("rate", 15.0))
        self.sightings = int(options.get("sightings", 3))
        self.max_frames = int(options.get("max_frames", 12))
        self.spatial = SpatialMemory(clock, MemoryConfig(**{k: float(options[k]) for k in MEMORY_KEYS if k in options}))
        self.perception = Perception(SimDetector(float(options.get("threshold", 0.75))), CameraMount.sim(), self.spatial)
        self.frames = 0
        self.last: list[dict[str, Any]] = []
        self._warm_up()

    def _warm_up(self) -> None:
        """One frame before READY: the world's first render creates its GL context (~2 s), which
        belongs to start-up, not to the first find (a run without vision never pays it)."""
        try:
            self.camera.read()
        except CameraError as e:
            raise RuntimeError(f"the sim camera does not work: {e}") from None

    def frame(self) -> list[Located]:
        """One frame through the pipeline (the memory is updated)."""
        try:
            frame = self.camera.read()
        except CameraError as e:
            raise DaemonError("backend_error", str(e)) from None
        located, _ = self.perception.process(frame)
        self.frames += 1
        self.last = [describe(p, frame.robot_pose) for p in located]
        return located

    def find(self, label: str, robot_pose: Pose, held: str | None) -> Activity:
        if label == held:
            try:
                state = self.world.call("state")
            except WorldError as e:
                raise DaemonError("backend_error", f"world state: {e}") from None
            side = next((s for s, v in state.get("held", {}).items() if v == label), None)
            if side is not None:
                x, y, z = state["hand_points"][side]
                return Instant(0.0, {"object": label, "position": {"x": x, "y": y, "z": z}, "distance": 0.0,
                                     "in_hand": True, "detections": [], "memory": self.memory()})
        return Search(self, label)

    def look(self) -> Activity:
        return Look(self)

    def memory(self) -> dict[str, Any]:
        return self.spatial.summary()

    def state(self) -> dict[str, Any]:
        return {"frames": self.frames, "remembered": len(self.spatial.entries),
                "seeing": sorted({d["label"] for d in self.last})}

    def close(self) -> None:
        self.camera.close()
        self.world.close()


def describe(p: Located, pose: Pose) -> dict[str, Any]:
    """A detection for results and the conversation: label, confidence, box, depth, positions."""
    return {**p.to_dict(), "distance": round(math.hypot(p.world[0] - pose.x, p.world[1] - pose.y), 3)}


class Search(Activity):
    """Frames at the camera rate until the object was seen ``sightings`` times, or give up."""

    resource = "camera"

    def __init__(self, backend: SimVision, label: str) -> None:
        self.backend = backend
        self.label = label
        self.frames = 0
        self.seen = 0
        self.entry_id: str | None = None
        self.due = 0.0
        self.labels_seen: set[str] = set()

    def start(self, now: float) -> dict[str, Any]:
        self.due = now
        return {"rate": round(1.0 / self.backend.period, 3)}

    def next_due(self) -> float:
        return self.due

    def poll(self, now: float) -> Progress | Done | None:
        if now < self.due:
            return None
        self.due = now + self.backend.period
        located = self.backend.frame()
        self.frames += 1
        self.labels_seen |= {p.detection.label for p in located}
        mine = [p for p in located if p.detection.label == self.label]
        if mine:
            self.seen += 1
        if self.seen >= self.backend.sightings:
            return Done(self._result(mine))
        if self.frames >= self.backend.max_frames:
            if self.seen:  # seen, but not often enough for a steady fix: report what there is
                return Done(self._result(mine))
            saw = ", ".join(sorted(self.labels_seen)) or "nothing"
            raise DaemonError("not_found", f"no {self.label} in view after {self.frames} frames (saw: {saw})",
                              data={"memory": self.backend.memory()})
        return Progress({"frame": self.frames, "seen": self.seen, "detections": self.backend.last})

    def _result(self, mine: list[Located]) -> dict[str, Any]:
        pose = self.backend.camera.last_pose
        entry = self.backend.spatial.nearest(self.label, pose.x, pose.y)
        if entry is None:  # forgotten within the search: cannot happen with sane settings
            raise DaemonError("not_found", f"the {self.label} was seen but is not remembered")
        position = {"x": round(entry.x, 4), "y": round(entry.y, 4), "z": round(entry.z, 4)}
        return {"object": self.label, "id": entry.id, "position": position,
                "confidence": round(self.backend.spatial.confidence(entry), 3),
                "distance": round(math.hypot(entry.x - pose.x, entry.y - pose.y), 3), "frames": self.frames,
                "detections": self.backend.last, "memory": self.backend.memory()}

    def cancel(self, now: float) -> dict[str, Any]:
        return {"frames": self.frames}


class Look(Activity):
    """One frame now: what is in view, and the memory."""

    resource = "camera"

    def __init__(self, backend: SimVision) -> None:
        self.backend = backend

    def poll(self, now: float) -> Done:
        self.backend.frame()
        return Done({"detections": self.backend.last, "memory": self.backend.memory()})

    def cancel(self, now: float) -> dict[str, Any]:
        return {}
