"""Our own py_trees decorators for timeout, delay and guard.

py_trees' ``Timeout`` reads ``time.monotonic()``; ours read the injected :class:`Clock` so a
simulator running faster than real time (or a test stepping a ManualClock) moves them too.
When one of them cuts its child off it stops the child (``stop(INVALID)``) so a running skill
is cancelled, and says why in ``failure_reason`` for logs and reports.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Any

from py_trees import behaviour, decorators
from py_trees.common import Status

from ..core.clock import Clock
from ..core.expr import ExprError, Expression


class _ReasonedDecorator(decorators.Decorator):
    """Reflects the child's status and keeps ``failure_reason`` ('' while nothing failed)."""

    def __init__(self, name: str, child: behaviour.Behaviour) -> None:
        super().__init__(name=name, child=child)
        self.failure_reason = ""

    def initialise(self) -> None:
        self.failure_reason = ""

    def update(self) -> Status:
        if self.decorated.status == Status.FAILURE:
            self.failure_reason = f"{self.decorated.name} failed"
        return self.decorated.status

    def _cut_off(self, reason: str) -> Iterator[behaviour.Behaviour]:
        """Stop the child (if running), fail with ``reason`` and end this tick."""
        if self.decorated.status == Status.RUNNING:
            self.decorated.stop(Status.INVALID)
        self.stop(Status.FAILURE)
        self.failure_reason = reason
        self.feedback_message = reason
        yield self


class Timeout(_ReasonedDecorator):
    """Fail, stopping the child, once it has run ``seconds`` of clock time."""

    def __init__(self, name: str, child: behaviour.Behaviour, clock: Clock, seconds: float) -> None:
        super().__init__(name, child)
        self.clock = clock
        self.seconds = float(seconds)
        self.deadline = 0.0

    def initialise(self) -> None:
        super().initialise()
        self.deadline = self.clock.now() + self.seconds

    def tick(self) -> Iterator[behaviour.Behaviour]:
        if self.status == Status.RUNNING and self._expired():
            yield from self._cut_off(self._reason())
            return
        yield from super().tick()

    def update(self) -> Status:
        if self.decorated.status == Status.RUNNING and self._expired():
            self.decorated.stop(Status.INVALID)
            self.failure_reason = self.feedback_message = self._reason()
            return Status.FAILURE
        return super().update()

    def _expired(self) -> bool:
        return self.clock.now() >= self.deadline

    def _reason(self) -> str:
        return f"timed out after {self.seconds:g} s"


class Delay(_ReasonedDecorator):
    """Stay RUNNING for ``seconds`` of clock time without ticking the child, then run it."""

    def __init__(self, name: str, child: behaviour.Behaviour, clock: Clock, seconds: float) -> None:
        super().__init__(name, child)
        self.clock = clock
        self.seconds = float(seconds)
        self.start_at = 0.0

    def initialise(self) -> None:
        super().initialise()
        self.start_at = self.clock.now() + self.seconds

    def tick(self) -> Iterator[behaviour.Behaviour]:
        if self.status != Status.RUNNING:
            self.initialise()
            self.status = Status.RUNNING  # the wait has begun; the base tick must not initialise again
        if self.clock.now() < self.start_at:
            self.feedback_message = f"waiting {self.start_at - self.clock.now():g} s more"
            yield self
            return
        yield from super().tick()


class Guard(_ReasonedDecorator):
    """Tick the child only while ``expression`` holds on the blackboard; otherwise stop it and fail.

    The expression is evaluated every tick, before the child, through ``lookup`` (the
    blackboard's ``get``); an evaluation error fails the guard with that error as the reason.
    """

    def __init__(self, name: str, child: behaviour.Behaviour, expression: Expression,
                 lookup: Callable[[str], Any]) -> None:
        super().__init__(name, child)
        self.expression = expression
        self.lookup = lookup

    def tick(self) -> Iterator[behaviour.Behaviour]:
        try:
            holds = bool(self.expression.evaluate(self.lookup))
        except ExprError as e:
            yield from self._cut_off(f"guard '{self.expression}' could not be evaluated: {e.message}")
            return
        if not holds:
            when = "no longer holds" if self.status == Status.RUNNING else "does not hold"
            yield from self._cut_off(f"guard '{self.expression}' {when}")
            return
        yield from super().tick()
