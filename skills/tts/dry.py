"""Dry speech: nothing is heard; an utterance lasts as long as saying it would take."""

from __future__ import annotations

from collections import deque
from typing import Any

from stuart_bt.core.clock import Clock
from stuart_bt.daemon.backend import TimedActivity

from .backend import TtsBackend

BASE_SECONDS = 0.4
SECONDS_PER_WORD = 0.36
KEEP_SPOKEN = 20  # texts kept in the state (it goes out in every heartbeat)


def speaking_time(text: str) -> float:
    return BASE_SECONDS + SECONDS_PER_WORD * len(text.split())


class Utterance(TimedActivity):
    resource = "voice"

    def __init__(self, backend: DryTts, text: str) -> None:
        super().__init__(speaking_time(text))
        self._backend = backend
        self.text = text

    def on_start(self, now: float) -> dict[str, Any]:
        self._backend.speaking = self.text
        return {"duration": round(self.duration, 4)}

    def report(self, now: float) -> dict[str, Any]:
        return {"fraction": round(self.fraction(now), 3)}

    def finish(self, now: float) -> dict[str, Any]:
        self._backend.finished(self.text, spoken=True)
        return {"text": self.text, "duration": round(self.duration, 4)}

    def cancel(self, now: float) -> dict[str, Any]:
        self._backend.finished(self.text, spoken=False)
        return {"text": self.text, "fraction": round(self.fraction(now), 3)}


class DryTts(TtsBackend):
    name = "dry"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        self.speaking: str | None = None
        self.spoken: deque[str] = deque(maxlen=KEEP_SPOKEN)
        self.spoken_total = 0

    def say(self, text: str) -> Utterance:
        return Utterance(self, text)

    def finished(self, text: str, spoken: bool) -> None:
        """The current utterance ended, fully ``spoken`` or cut short."""
        self.speaking = None
        if spoken:
            self.spoken.append(text)
            self.spoken_total += 1

    def state(self) -> dict[str, Any]:
        return {"speaking": self.speaking, "spoken": list(self.spoken), "spoken_total": self.spoken_total}
