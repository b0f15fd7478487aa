"""Dry locomotion: no world, no physics; the pose moves along a plausible path on the clock.

A walk is turn-to-face, a straight line at 0.5 m/s, then a turn to the goal heading at
0.8 rad/s, so durations and intermediate poses look like the robot's and a stop freezes the
robot somewhere believable between start and goal.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from stuart_bt.core.clock import Clock
from stuart_bt.core.world import Pose
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import TimedActivity

from .backend import LocoBackend, NavigateGoal, goal_pose

WALK_SPEED = 0.5  # m/s
TURN_RATE = 0.8  # rad/s


def wrap(angle: float) -> float:
    """The same heading in [-pi, pi)."""
    return (angle + math.pi) % (2 * math.pi) - math.pi


@dataclass(frozen=True)
class Segment:
    """One piece of a path: a turn in place (``turn`` radians, signed) or a straight walk."""

    phase: str
    start: Pose
    end: Pose
    duration: float
    turn: float = 0.0

    def at(self, fraction: float) -> Pose:
        if self.turn:
            return Pose(self.start.x, self.start.y, wrap(self.start.yaw + self.turn * fraction))
        return Pose(self.start.x + (self.end.x - self.start.x) * fraction,
                    self.start.y + (self.end.y - self.start.y) * fraction, self.start.yaw)


def turn_segment(phase: str, start: Pose, angle: float) -> Segment:
    end = Pose(start.x, start.y, wrap(start.yaw + angle))
    return Segment(phase, start, end, abs(angle) / TURN_RATE, angle)


def plan_navigate(start: Pose, goal: NavigateGoal) -> list[Segment]:
    """Segments from ``start`` to the goal, skipping moves already within tolerance."""
    gx, gy, gyaw = goal_pose(start, goal.target)
    segments: list[Segment] = []
    here = start
    distance = math.hypot(gx - start.x, gy - start.y)
    if distance > goal.tolerance:
        face = wrap(math.atan2(gy - start.y, gx - start.x) - start.yaw)
        if face:
            segments.append(turn_segment("turn", here, face))
            here = segments[-1].end
        walk_end = Pose(gx, gy, here.yaw)
        segments.append(Segment("walk", here, walk_end, distance / WALK_SPEED))
        here = walk_end
    if gyaw is not None and abs(wrap(gyaw - here.yaw)) > goal.yaw_tolerance:
        segments.append(turn_segment("final_turn", here, wrap(gyaw - here.yaw)))
    return segments


class Motion(TimedActivity):
    """A walk or turn along planned segments; it owns the pose while it runs."""

    resource = "motion"

    def __init__(self, backend: DryLoco, plan: Callable[[Pose], list[Segment]], extra: dict[str, Any]) -> None:
        super().__init__(0.0)
        self._backend = backend
        self._plan = plan  # planned when the motion starts, from the pose it starts at
        self._extra = extra
        self._segments: list[Segment] = []
        self._start = Pose()

    def on_start(self, now: float) -> dict[str, Any]:
        self._start = self._backend.pose()
        self._segments = self._plan(self._start)
        self.duration = sum(s.duration for s in self._segments)
        self._backend.motion = self
        return {"duration": round(self.duration, 4)}

    def pose_at(self, now: float) -> Pose:
        elapsed = now - self.started
        for segment in self._segments:
            if elapsed < segment.duration:
                return segment.at(elapsed / segment.duration)
            elapsed -= segment.duration
        return self._segments[-1].end if self._segments else self._start

    def _phase_at(self, now: float) -> str:
        elapsed = now - self.started
        for segment in self._segments:
            if elapsed < segment.duration:
                return segment.phase
            elapsed -= segment.duration
        return "arrived"

    def report(self, now: float) -> dict[str, Any]:
        return {"pose": self.pose_at(now).to_dict(), "phase": self._phase_at(now),
                "time_left": round(max(0.0, self.started + self.duration - now), 4)}

    def finish(self, now: float) -> dict[str, Any]:
        pose = self._settle(now)
        walked = sum(s.start.distance_to(s.end) for s in self._segments)
        return {"pose": pose.to_dict(), **self._extra, "distance": round(walked, 4)}

    def cancel(self, now: float) -> dict[str, Any]:
        return {"pose": self._settle(now).to_dict()}

    def _settle(self, now: float) -> Pose:
        """Leave the robot where the motion has it now and hand the pose back to the backend."""
        pose = self.pose_at(now)
        self._backend.rest(pose)
        return pose


class DryLoco(LocoBackend):
    name = "dry"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        a.only_known(options, ("start_pose",), "loco dry options")
        self._pose = a.pose(options, "start_pose", "loco dry options") if "start_pose" in options else Pose()
        self.motion: Motion | None = None

    def navigate(self, goal: NavigateGoal) -> Motion:
        return Motion(self, lambda start: plan_navigate(start, goal), {"marker": goal.marker})

    def turn(self, angle: float) -> Motion:
        return Motion(self, lambda start: [turn_segment("turn", start, angle)], {"angle": angle})

    def pose(self) -> Pose:
        return self.motion.pose_at(self.clock.now()) if self.motion else self._pose

    def rest(self, pose: Pose) -> None:
        """The running motion ended with the robot at ``pose``."""
        self._pose = pose
        self.motion = None

    def stop(self) -> None:
        """Nothing to halt: cancelling the motion already froze the pose."""

    def state(self) -> dict[str, Any]:
        return {**super().state(), "moving": self.motion is not None}
