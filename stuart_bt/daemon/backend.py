"""What a daemon backend is made of: a command table, activities, and typed errors.

A backend (dry, sim, unitree) plugs into the shared daemon loop (:mod:`stuart_bt.skills.runtime`)
through this small surface, so the loop knows nothing about robots and a backend knows nothing
about pipes. A command first *validates* (its handler returns an :class:`Activity` or raises
:class:`DaemonError` with no side effects), then the loop preempts whatever held the same
resource, then it *starts* the activity. That order means a rejected command never disturbs
the motion already running.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar

from ..core.clock import Clock
from ..core.errors import CodedError, StuartError


class DaemonError(CodedError):
    """A command failed with a protocol error code (see :data:`protocol.ERROR_CODES`)."""

    def __init__(
        self, code: str, reason: str, vendor_code: int | None = None, data: dict[str, Any] | None = None
    ) -> None:
        super().__init__(code, reason)
        self.vendor_code = vendor_code
        self.data = data


class StartupError(StuartError):
    """A backend cannot start for a reason the operator can fix (the robot's service does not
    answer, a wrong network interface): the daemon prints this one message, no traceback."""


@dataclass(frozen=True)
class Progress:
    """An activity has news but is not finished."""

    data: dict[str, Any]


@dataclass(frozen=True)
class Done:
    """An activity finished successfully with this result."""

    result: dict[str, Any] = field(default_factory=dict)


class Activity(ABC):
    """One accepted command, running until it is done, fails, or is cancelled.

    ``resource`` names what the activity occupies ("motion", "voice", "arms"); a newer activity
    on the same resource preempts it. ``None`` means it shares with everything.
    """

    resource: ClassVar[str | None] = None

    def start(self, now: float) -> dict[str, Any] | None:
        """Begin (after validation and preemption); the dict goes into the ``accepted`` reply."""
        return None

    @abstractmethod
    def poll(self, now: float) -> Progress | Done | None:
        """Advance; ``None`` when there is nothing to report. Raise :class:`DaemonError` to fail."""

    @abstractmethod
    def cancel(self, now: float) -> dict[str, Any] | None:
        """Stop at once; the dict (e.g. where the robot froze) goes into the error reply."""

    def next_due(self) -> float | None:
        """Clock time of the next poll this activity needs (None: poll it often).

        Lets the loop sleep exactly until something is due, however fast the clock runs."""
        return None


class TimedActivity(Activity):
    """An activity of a known clock duration that reports progress every ``interval`` seconds.

    Subclasses say what the progress and the result are; the timing lives here once.
    """

    interval: ClassVar[float] = 0.5

    def __init__(self, duration: float) -> None:
        self.duration = max(0.0, duration)
        self.started = 0.0
        self._next_report = 0.0

    def start(self, now: float) -> dict[str, Any] | None:
        self.started = now
        self._next_report = now + self.interval
        return self.on_start(now)

    def poll(self, now: float) -> Progress | Done | None:
        if now >= self.started + self.duration:
            return Done(self.finish(now))
        if now >= self._next_report:
            while self._next_report <= now:  # keep the cadence; skip reports a late poll missed
                self._next_report += self.interval
            return Progress(self.report(now))
        return None

    def next_due(self) -> float:
        return min(self._next_report, self.started + self.duration)

    def fraction(self, now: float) -> float:
        """How much of the duration has passed, 0..1."""
        if self.duration <= 0:
            return 1.0
        return min(1.0, max(0.0, (now - self.started) / self.duration))

    def on_start(self, now: float) -> dict[str, Any] | None:
        return None

    @abstractmethod
    def report(self, now: float) -> dict[str, Any]: ...

    @abstractmethod
    def finish(self, now: float) -> dict[str, Any]: ...


class Delivered(TimedActivity):
    """A result known when the command arrives, delivered after ``seconds`` of clock time (0: at
    the first poll): a dry search, a confirmation, a memory read-out."""

    resource: ClassVar[str | None] = None

    def __init__(self, seconds: float, result: dict[str, Any]) -> None:
        super().__init__(seconds)
        self._result = result

    def report(self, now: float) -> dict[str, Any]:
        return {"fraction": round(self.fraction(now), 3)}

    def finish(self, now: float) -> dict[str, Any]:
        return self._result

    def cancel(self, now: float) -> dict[str, Any]:
        return {}


Handler = Callable[[dict[str, Any]], Activity]


class Backend(ABC):
    """One family's way of doing things (dry, sim, unitree). Built once per daemon process."""

    family: ClassVar[str]
    name: ClassVar[str]

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        self.clock = clock
        self.options = options

    @abstractmethod
    def commands(self) -> dict[str, Handler]:
        """The family's commands: name -> handler that validates args and returns an activity."""

    @abstractmethod
    def state(self) -> dict[str, Any]:
        """Small JSON-able state sent in every heartbeat (so keep it small)."""

    def stop(self) -> None:  # noqa: B027 - a hook: backends with hardware override it
        """Halt the hardware now. Every activity was already cancelled; a vendor backend still
        sends its own stop in case something moves that no activity knew about."""

    def take_logs(self) -> list[tuple[str, str]]:
        """(level, message) pairs a backend's own threads want sent as ``log`` lines since the
        last call (a malformed sample from the robot is worth a warning, not a failed command)."""
        return []

    def close(self) -> None:  # noqa: B027 - a hook: backends with connections override it
        """Release connections before the process exits."""
