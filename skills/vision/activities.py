"""Small activities the vision backends share."""

from __future__ import annotations

from typing import Any

from stuart_bt.daemon.backend import TimedActivity


class Instant(TimedActivity):
    """A result known at once, delivered after ``seconds`` of clock time (a dry camera's look)."""

    resource = None

    def __init__(self, seconds: float, result: dict[str, Any]) -> None:
        super().__init__(seconds)
        self._result = result

    def report(self, now: float) -> dict[str, Any]:
        return {"fraction": round(self.fraction(now), 3)}

    def finish(self, now: float) -> dict[str, Any]:
        return self._result

    def cancel(self, now: float) -> dict[str, Any]:
        return {}
