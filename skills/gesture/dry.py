"""Dry gestures: nothing moves; a gesture lasts its library duration on the clock."""

from __future__ import annotations

from typing import Any

from stuart_bt.core import gestures
from stuart_bt.core.clock import Clock
from stuart_bt.daemon.backend import TimedActivity

from .backend import GestureBackend, Keyframe


class Playing(TimedActivity):
    """A run of steps ``(name, seconds)`` played back to back."""

    resource = "arms"

    def __init__(self, backend: DryGesture, steps: list[tuple[str, float]], result: dict[str, Any]) -> None:
        super().__init__(sum(seconds for _, seconds in steps))
        self._backend = backend
        self._steps = steps
        self._result = result

    def on_start(self, now: float) -> dict[str, Any]:
        self._backend.current = self
        return {"duration": round(self.duration, 4)}

    def step_at(self, now: float) -> tuple[int, str]:
        elapsed = now - self.started
        for index, (name, seconds) in enumerate(self._steps):
            if elapsed < seconds:
                return index, name
            elapsed -= seconds
        return len(self._steps) - 1, self._steps[-1][0]

    def report(self, now: float) -> dict[str, Any]:
        index, name = self.step_at(now)
        return {"gesture": name, "index": index, "fraction": round(self.fraction(now), 3)}

    def finish(self, now: float) -> dict[str, Any]:
        self._backend.finished(self._steps[-1][0])
        return {**self._result, "duration": round(self.duration, 4)}

    def cancel(self, now: float) -> dict[str, Any]:
        index, name = self.step_at(now)
        self._backend.finished(name)
        return {"gesture": name, "index": index}


class DryGesture(GestureBackend):
    name = "dry"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        self.current: Playing | None = None
        self.holding: str | None = None  # a gesture whose end pose stays until "release arm"

    def play(self, sequence: list[gestures.Gesture]) -> Playing:
        return Playing(self, [(g.name, g.duration) for g in sequence], {"played": [g.name for g in sequence]})

    def play_keyframes(self, keyframes: list[Keyframe]) -> Playing:
        return Playing(self, [("keyframes", keyframes[-1].t)], {"keyframes": len(keyframes)})

    def finished(self, last: str) -> None:
        """Playback ended (or was cut) in gesture ``last``."""
        self.current = None
        gesture = gestures.lookup(last)
        self.holding = gesture.name if gesture and gesture.holds else None

    def state(self) -> dict[str, Any]:
        playing = self.current.step_at(self.clock.now())[1] if self.current else None
        return {"playing": playing, "holding": self.holding}
