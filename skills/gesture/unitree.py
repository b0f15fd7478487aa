"""Gestures on the G1: the arm service's built-in actions, and recorded keyframes streamed on rt/arm_sdk.

Library gestures are ``G1ArmActionClient.ExecuteAction(id)`` (api 7106). Some actions hold their
end pose until "release arm" (99) and the service refuses anything else meanwhile (7401), so a
held pose is released before the next gesture starts, and on stop. Busy (7400) and unknown
(7402) fail the request with the vendor's code. The service answers at once and plays for a
while; the gesture's library duration is how long the daemon waits before the next one.

Recorded gestures (keyframes) are checked against the joint limits, then streamed as joint
targets at 50 Hz on ``rt/arm_sdk`` with the blend weight ramped in and out
(:mod:`stuart_bt.skills.arm_stream`).

Options (besides the link settings in :mod:`stuart_bt.skills.vendor`): ``ramp`` (0.5 s: the
blend weight's ramp from 0 to 1 and back).
"""

from __future__ import annotations

from typing import Any

from unitree_sdk2py.g1.arm.g1_arm_action_client import G1ArmActionClient

from stuart_bt.core import gestures
from stuart_bt.core.clock import Clock
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, DaemonError, Done, Progress
from stuart_bt.skills import vendor
from stuart_bt.skills.arm_stream import ArmStreamer

from .backend import GestureBackend, Keyframe
from .keyframes import validate_keyframes

SERVICE = "arm"
RELEASE = gestures.LIBRARY["release arm"]


class ActionSequence(Activity):
    """Built-in arm actions one after another, each given its library duration."""

    resource = "arms"

    def __init__(self, backend: UnitreeGesture, steps: list[gestures.Gesture], played: list[str]) -> None:
        self.backend = backend
        self.steps = steps
        self.played = played
        self.index = -1
        self.step_end = 0.0

    def start(self, now: float) -> dict[str, Any]:
        self.backend.playing = self
        self._next(now)
        return {"duration": round(sum(g.duration for g in self.steps), 4), "ids": [g.action_id for g in self.steps]}

    def _next(self, now: float) -> None:
        self.index += 1
        gesture = self.steps[self.index]
        self.backend.execute(gesture)
        self.step_end = now + gesture.duration

    def next_due(self) -> float:
        return self.step_end

    def poll(self, now: float) -> Progress | Done | None:
        if now < self.step_end:
            return None
        if self.index == len(self.steps) - 1:
            self.backend.playing = None
            total = sum(g.duration for g in self.steps)
            return Done({"played": self.played, "duration": round(total, 4)})
        self._next(now)
        return Progress({"gesture": self.steps[self.index].name, "index": self.index})

    def cancel(self, now: float) -> dict[str, Any]:
        self.backend.playing = None
        return {"gesture": self.steps[max(self.index, 0)].name, "index": max(self.index, 0)}


class StreamedGesture(Activity):
    """Recorded keyframes on rt/arm_sdk, ramped in and out; done when the weight is back at 0."""

    resource = "arms"

    def __init__(self, backend: UnitreeGesture, frames: list[Keyframe]) -> None:
        self.backend = backend
        self.frames = frames

    def start(self, now: float) -> dict[str, Any]:
        if self.backend.holding is not None:
            self.backend.execute(RELEASE)  # the arm service's held pose would fight the stream
        program = self.backend.streamer.play([(f.t, dict(f.joints)) for f in self.frames])
        self.backend.playing = self
        return {"duration": round(program.length, 4), "topic": "rt/arm_sdk"}

    def poll(self, now: float) -> Done | None:
        if not self.backend.streamer.finished():
            return None
        self.backend.playing = None
        return Done({"keyframes": len(self.frames), "duration": round(self.frames[-1].t, 4)})

    def cancel(self, now: float) -> dict[str, Any]:
        self.backend.streamer.ramp_out()
        self.backend.playing = None
        return {"weight": round(self.backend.streamer.weight(), 3)}


class UnitreeGesture(GestureBackend):
    name = "unitree"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        self.link = vendor.link_from(options, "gesture", ("ramp",))
        ramp = vendor.startup_option(lambda: a.number(options, "ramp", "gesture unitree options", default=0.5,
                                                      minimum=0.05))
        vendor.connect(self.link)
        self.arm = vendor.ready_client(G1ArmActionClient(), SERVICE, self.link)
        self.streamer = ArmStreamer(ramp)
        self.holding: str | None = None
        self.playing: Activity | None = None

    def execute(self, gesture: gestures.Gesture) -> None:
        """One ExecuteAction; on success remember whether the arms now hold a pose."""
        code = self.arm.ExecuteAction(gesture.action_id)
        if code == 7402:
            raise DaemonError("unknown_gesture", f"the arm service does not know {gesture.name!r} "
                              f"(action {gesture.action_id})", vendor_code=code)
        vendor.check(code, SERVICE, f"ExecuteAction({gesture.action_id}, {gesture.name})")
        self.holding = gesture.name if gesture.holds else None

    def play(self, sequence: list[gestures.Gesture]) -> Activity:
        steps = list(sequence)
        holding = self.holding is not None
        with_releases: list[gestures.Gesture] = []
        for gesture in steps:
            if holding and gesture.action_id != RELEASE.action_id:
                with_releases.append(RELEASE)  # a held pose refuses the next action (7401) until released
            with_releases.append(gesture)
            holding = gesture.holds
        return ActionSequence(self, with_releases, [g.name for g in sequence])

    def play_keyframes(self, keyframes: list[Keyframe]) -> Activity:
        problems = validate_keyframes(keyframes)
        if problems:
            raise DaemonError("bad_request", "recorded gesture rejected: " + "; ".join(problems[:5]))
        return StreamedGesture(self, keyframes)

    def stop(self) -> None:
        """Let the arms go: release a held action and ramp the stream's weight to 0."""
        self.streamer.ramp_out()
        if self.holding is not None:
            try:
                self.execute(RELEASE)
            except DaemonError:
                self.holding = None
                raise

    def state(self) -> dict[str, Any]:
        playing = None
        if isinstance(self.playing, ActionSequence):
            playing = self.playing.steps[max(self.playing.index, 0)].name
        elif isinstance(self.playing, StreamedGesture):
            playing = "recorded"
        return {"playing": playing, "holding": self.holding}

    def close(self) -> None:
        self.streamer.close()
