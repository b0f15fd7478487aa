"""Simulated gestures: library gestures and recorded keyframes played on the sim's arms.

Library gestures become joint keyframe trajectories (:mod:`.keyframes`), concatenated for a
sequence, each starting from where the previous one ended (so "hands up" then "release arm"
releases from the raised pose). Recorded keyframes are checked against the joint limits before
anything moves. The world plays the trajectory in sim time; cancel and stop hold the arms where
they are, like the vendor's arm service.

Options: ``world`` (socket path, required).
"""

from __future__ import annotations

from typing import Any

from stuart_bt.core import gestures
from stuart_bt.core.clock import Clock
from stuart_bt.daemon.backend import Activity, DaemonError, Done, Progress
from stuart_bt.sim.world.client import WorldClient, WorldError

from .backend import GestureBackend, Keyframe
from .keyframes import GESTURE_JOINTS, keyframes, validate_keyframes

BLEND_THRESHOLD = 0.05  # rad: farther than this from a gesture's first frame, blend into it
BLEND_SECONDS = 0.6


class Trajectory(Activity):
    """One arm trajectory in the world, done when its last keyframe time has passed and the
    world says the arms are idle."""

    resource = "arms"
    report_every = 0.5

    def __init__(self, backend: SimGesture, frames: list[Keyframe], steps: list[tuple[str, float]],
                 result: dict[str, Any]) -> None:
        self.backend = backend
        self.frames = frames
        self.steps = steps  # (name, end time) for progress reports
        self.result = result
        self.duration = frames[-1].t
        self.started = 0.0
        self._next_report = 0.0

    def start(self, now: float) -> dict[str, Any]:
        points = [{"t": f.t, "joints": f.joints} for f in self.frames]
        name = self.result.get("gesture", "keyframes")
        self.backend.call("arm_trajectory", points=points, id=" + ".join(name) if isinstance(name, list) else name)
        self.started = now
        self._next_report = now + self.report_every
        self.backend.playing = str(name)
        return {"duration": round(self.duration, 4)}

    def next_due(self) -> float:
        return min(self._next_report, self.started + self.duration)

    def poll(self, now: float) -> Progress | Done | None:
        elapsed = now - self.started
        if elapsed >= self.duration:
            busy = self.backend.call("state").get("arm_busy", {})
            if not any(busy.values()):
                self.backend.finished(self.frames[-1].joints)
                return Done({**self.result, "duration": round(self.duration, 4)})
            return None
        if now >= self._next_report:
            self._next_report = now + self.report_every
            name = next((n for n, end in self.steps if elapsed < end), self.steps[-1][0])
            return Progress({"gesture": name, "fraction": round(elapsed / self.duration, 3)})
        return None

    def cancel(self, now: float) -> dict[str, Any]:
        self.backend.call("arm_stop")
        self.backend.finished(None)
        return {"elapsed": round(now - self.started, 3)}


class SimGesture(GestureBackend):
    name = "sim"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        if "world" not in options:
            raise ValueError("the sim gesture backend needs the world's socket path (option 'world')")
        self.world = WorldClient(options["world"])
        self.playing: str | None = None
        self.pose: dict[str, float] | None = None  # where the last gesture left the arms

    def call(self, cmd: str, **args: Any) -> dict[str, Any]:
        try:
            return self.world.call(cmd, **args)
        except WorldError as e:
            raise DaemonError("backend_error", f"world {cmd}: {e}") from None

    def current_pose(self) -> dict[str, float]:
        joints = self.call("state").get("joints", {})
        return {name: float(joints[name]) for name in GESTURE_JOINTS if name in joints}

    def play(self, sequence: list[gestures.Gesture]) -> Activity:
        frames: list[Keyframe] = []
        steps: list[tuple[str, float]] = []
        pose = self.current_pose()
        offset = 0.0
        first = keyframes(sequence[0].name, start=pose)[0].joints
        if max((abs(first[j] - pose.get(j, first[j])) for j in first), default=0.0) > BLEND_THRESHOLD:
            frames.append(Keyframe(0.0, pose))  # the arms are elsewhere (a held gesture): blend in
            offset = BLEND_SECONDS
        for gesture in sequence:
            part = keyframes(gesture.name, start=pose)
            frames += [Keyframe(offset + f.t, f.joints) for f in part if not (frames and frames[-1].t >= offset + f.t)]
            offset += part[-1].t
            steps.append((gesture.name, offset))
            pose = dict(part[-1].joints)
        names = [g.name for g in sequence]
        result = {"gesture": names[0] if len(names) == 1 else names, "ids": [g.action_id for g in sequence]}
        return Trajectory(self, frames, steps, result)

    def play_keyframes(self, frames: list[Keyframe]) -> Activity:
        problems = validate_keyframes(frames)
        if problems:
            raise DaemonError("bad_request", "recorded gesture rejected: " + "; ".join(problems[:5]))
        if frames[0].t > 0.0:  # blend from the current pose into the first frame
            frames = [Keyframe(0.0, self.current_pose()), *frames]
        return Trajectory(self, frames, [("recorded", frames[-1].t)], {"gesture": "recorded"})

    def finished(self, pose: dict[str, float] | None) -> None:
        self.playing = None
        if pose is not None:
            self.pose = pose

    def stop(self) -> None:
        self.call("arm_stop")

    def state(self) -> dict[str, Any]:
        return {"playing": self.playing}

    def close(self) -> None:
        self.world.close()
