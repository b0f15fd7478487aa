"""One clock behind every timeout and duration.

The executor, the leaves' timeouts, the decorators and the daemons' simulated durations all ask
a :class:`Clock` for the time, never ``time.monotonic()`` directly. That is the seam that lets a
simulator run faster than real time: swap the clock and every timeout follows.

Clocks cross process boundaries as a short text spec (``wall``, ``scaled:EPOCH:FACTOR``) so a
daemon subprocess can build the same clock as the executor that started it.
"""

from __future__ import annotations

import threading
import time
from typing import Protocol


class Clock(Protocol):
    """Time source in seconds. ``now()`` is monotonic; only differences are meaningful."""

    def now(self) -> float: ...

    def sleep_until(self, t: float, wake: threading.Event | None = None, max_wall: float | None = None) -> None:
        """Block the caller until ``now() >= t`` (returns at once if already past), or sooner:
        when ``wake`` is set (a stop request) or after ``max_wall`` wall seconds (the caller has
        other duties and asks again)."""

    def spec(self) -> str:
        """Text form that :func:`clock_from_spec` turns back into an equivalent clock."""

    @property
    def factor(self) -> float:
        """Clock seconds per wall second (1.0 for real time)."""


class ScaledClock:
    """Wall time scaled by ``factor`` from a shared ``epoch`` (a ``time.time()`` value).

    Two processes given the same epoch and factor read the same time, to within their wall
    clocks' agreement, which on one machine is the same kernel clock. Factor 1 is real time.
    """

    def __init__(self, factor: float = 1.0, epoch: float | None = None) -> None:
        if factor <= 0:
            raise ValueError(f"clock factor must be positive, got {factor}")
        self._factor = float(factor)
        self._epoch = time.time() if epoch is None else float(epoch)

    @property
    def factor(self) -> float:
        return self._factor

    @property
    def epoch(self) -> float:
        return self._epoch

    def now(self) -> float:
        return (time.time() - self._epoch) * self._factor

    def sleep_until(self, t: float, wake: threading.Event | None = None, max_wall: float | None = None) -> None:
        remaining = (t - self.now()) / self._factor
        if max_wall is not None:
            remaining = min(remaining, max_wall)
        if remaining <= 0:
            return
        if wake is not None:
            wake.wait(remaining)
        else:
            time.sleep(remaining)

    def spec(self) -> str:
        return f"scaled:{self._epoch!r}:{self._factor!r}"

    def __repr__(self) -> str:
        return f"ScaledClock(factor={self._factor}, epoch={self._epoch})"


def WallClock() -> ScaledClock:  # named like a class: it reads like one at call sites
    """Real time, starting at zero now."""
    return ScaledClock(1.0)


class ManualClock:
    """A clock that only moves when told to; for tests that step time by hand.

    ``sleep_until`` advances the clock instead of blocking, so an executor driven by a manual
    clock runs as fast as the CPU allows and stays repeatable.
    """

    def __init__(self, start: float = 0.0) -> None:
        self._t = float(start)
        self._lock = threading.Lock()

    @property
    def factor(self) -> float:
        return float("inf")

    def now(self) -> float:
        return self._t

    def advance(self, dt: float) -> float:
        with self._lock:
            self._t += dt
            return self._t

    def set(self, t: float) -> None:
        with self._lock:
            self._t = max(self._t, float(t))

    def sleep_until(self, t: float, wake: threading.Event | None = None, max_wall: float | None = None) -> None:
        self.set(t)  # manual time never waits: nothing to wake from

    def spec(self) -> str:
        # A manual clock cannot be shared with another process; daemons get real time.
        return "wall"


def clock_from_spec(spec: str | None) -> Clock:
    """Build a clock from :meth:`Clock.spec` text (``None`` or ``wall`` gives real time). The
    simulator's ``sim:PATH`` clock is built by the daemons' runtime, which knows the simulator."""
    if not spec or spec == "wall":
        return WallClock()
    kind, _, rest = spec.partition(":")
    if kind == "scaled":
        epoch_text, _, factor_text = rest.partition(":")
        try:
            return ScaledClock(float(factor_text), float(epoch_text))
        except ValueError:
            pass
    raise ValueError(f"bad clock spec {spec!r} (expected 'wall', 'scaled:EPOCH:FACTOR' or 'sim:PATH')")
