"""Vision on a real camera stream, whatever the camera: frames at the camera rate through the
perception pipeline while a ``find`` or ``look`` runs, nothing in between.

:class:`CameraVision` holds the loop; the sim and unitree backends give it a camera, a detector
and a mount. Options every camera backend takes: ``rate`` (Hz of clock time, 15), ``threshold``
(0.75), ``sightings`` (frames that must see the object before find succeeds, 3), ``max_frames``
(frames find looks before it gives up, 12), and the memory's ``match_radius``, ``smoothing``,
``decay_after``, ``decay_rate``, ``drop_below``.
"""

from __future__ import annotations

import math
from typing import Any

from stuart_bt.core.clock import Clock
from stuart_bt.core.world import Pose
from stuart_bt.daemon.backend import Activity, DaemonError, Delivered, Done, Progress
from stuart_bt.perception.detect import Detector
from stuart_bt.perception.frames import CameraError, CameraSource
from stuart_bt.perception.memory import MemoryConfig, SpatialMemory
from stuart_bt.perception.pipeline import Located, Perception
from stuart_bt.perception.projection import CameraMount

from .backend import VisionBackend

MEMORY_KEYS = ("match_radius", "smoothing", "decay_after", "decay_rate", "drop_below")
LOOP_KEYS = ("rate", "threshold", "sightings", "max_frames", *MEMORY_KEYS)
HAND_HEIGHT = 1.0  # where a held object is, above the floor, when the backend cannot say


class CameraVision(VisionBackend):
    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        self.period = 1.0 / float(options.get("rate", 15.0))
        self.threshold = float(options.get("threshold", 0.75))
        self.sightings = int(options.get("sightings", 3))
        self.max_frames = int(options.get("max_frames", 12))
        self.spatial = SpatialMemory(clock, MemoryConfig(**{k: float(options[k]) for k in MEMORY_KEYS if k in options}))
        self.camera: CameraSource | None = None
        self.perception: Perception | None = None
        self.frames = 0
        self.last: list[dict[str, Any]] = []
        self.last_pose = Pose()

    def attach(self, camera: CameraSource, detector: Detector, mount: CameraMount) -> None:
        self.camera = camera
        self.perception = Perception(detector, mount, self.spatial)

    def frame(self) -> list[Located]:
        """One frame through the pipeline (the memory is updated)."""
        assert self.camera is not None and self.perception is not None
        try:
            frame = self.camera.read()
        except CameraError as e:
            raise DaemonError("backend_error", str(e)) from None
        located, _ = self.perception.process(frame)
        self.frames += 1
        self.last_pose = frame.robot_pose
        self.last = [describe(p, frame.robot_pose) for p in located]
        return located

    def in_hand(self, label: str, robot_pose: Pose) -> dict[str, float]:
        """Where the held object is (backends that know the hand say better)."""
        return {"x": round(robot_pose.x, 4), "y": round(robot_pose.y, 4), "z": HAND_HEIGHT}

    def find(self, label: str, robot_pose: Pose, held: str | None) -> Activity:
        if label == held:
            return Delivered(0.0, {"object": label, "position": self.in_hand(label, robot_pose), "distance": 0.0,
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
        if self.camera is not None:
            self.camera.close()


def describe(p: Located, pose: Pose) -> dict[str, Any]:
    """A detection for results and the conversation: label, confidence, box, depth, positions."""
    return {**p.to_dict(), "distance": round(math.hypot(p.world[0] - pose.x, p.world[1] - pose.y), 3)}


class Search(Activity):
    """Frames at the camera rate until the object was seen ``sightings`` times, or give up."""

    resource = "camera"

    def __init__(self, backend: CameraVision, label: str) -> None:
        self.backend = backend
        self.label = label
        self.frames = 0
        self.seen = 0
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
        if any(p.detection.label == self.label for p in located):
            self.seen += 1
        if self.seen >= self.backend.sightings:
            return Done(self._result())
        if self.frames >= self.backend.max_frames:
            if self.seen:  # seen, but not often enough for a steady fix: report what there is
                return Done(self._result())
            saw = ", ".join(sorted(self.labels_seen)) or "nothing"
            raise DaemonError("not_found", f"no {self.label} in view after {self.frames} frames (saw: {saw})",
                              data={"memory": self.backend.memory(), "saw": sorted(self.labels_seen)})
        return Progress({"frame": self.frames, "seen": self.seen, "detections": self.backend.last})

    def _result(self) -> dict[str, Any]:
        pose = self.backend.last_pose
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

    def __init__(self, backend: CameraVision) -> None:
        self.backend = backend

    def poll(self, now: float) -> Done:
        self.backend.frame()
        return Done({"detections": self.backend.last, "memory": self.backend.memory()})

    def cancel(self, now: float) -> dict[str, Any]:
        return {}
