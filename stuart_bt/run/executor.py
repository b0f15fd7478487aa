"""The executor: ticks a py_trees tree at a steady rate on the shared clock.

It owns timing and status bookkeeping only. Each tick it runs the pre-tick hooks (the runner
adds "poll the daemons" and "copy the robot pose into the world state"), ticks the tree once, and
publishes a ``status`` event for every node whose status changed, so that views and reports never
need to reach into the tree. Deadlines advance by a fixed period (no drift); a tick that overruns
its period publishes a rate-limited ``warning`` and the schedule re-synchronises.

Holding is for a pause a person asks for ("stop" during a tour, then "continue"):
:meth:`hold` stops the running leaves and the motion but keeps the tree's place; :meth:`resume`
goes on from there.

Stopping is cooperative and bounded: :meth:`request_stop` (from a signal handler, another thread,
a ``stop`` utterance) is honoured at the start of the next tick: the tree is halted (running
leaves cancel their daemon commands) and the ``on_halt`` hooks run (the runner sends ``stop`` to
every daemon).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field

import py_trees
from py_trees.common import Status

from ..core.clock import Clock
from ..core.events import EventStream

Hook = Callable[[], None]
FINISHED = (Status.SUCCESS, Status.FAILURE)
WAITING_DUTY_PERIOD = 0.25  # wall seconds: how often a tick waiting on sim time does its other duties


@dataclass
class RunOutcome:
    status: str  # SUCCESS | FAILURE | STOPPED | TIMEOUT | ERROR (the run could not go on: its world died)
    started: float
    ended: float
    ticks: int
    reason: str | None = None

    @property
    def duration(self) -> float:
        return self.ended - self.started


@dataclass
class Executor:
    root: py_trees.behaviour.Behaviour
    clock: Clock
    events: EventStream
    rate: float = 20.0
    pre_tick: list[Hook] = field(default_factory=list)
    on_halt: list[Hook] = field(default_factory=list)
    while_waiting: list[Hook] = field(default_factory=list)  # run every WAITING_DUTY_PERIOD in long sim waits
    overrun_warning_interval: float = 1.0  # clock seconds between two overrun warnings

    def __post_init__(self) -> None:
        if self.rate <= 0:
            raise ValueError(f"tick rate must be positive, got {self.rate}")
        self.tree = py_trees.trees.BehaviourTree(self.root)
        self._nodes: list[py_trees.behaviour.Behaviour] = list(preorder(self.root))
        self._paths = [getattr(n, "spec_path", n.name) for n in self._nodes]
        self._last = [n.status for n in self._nodes]
        self._stop = threading.Event()
        self._hold = threading.Event()  # "stop" said during a tour: paused, "continue" goes on
        self._hold_reason = ""
        self._holding = False  # the loop has paused the tree (read on the tick thread only)
        self._stop_reason: str | None = None
        self._stop_status = "STOPPED"
        self._last_overrun_warning = float("-inf")
        self.ticks = 0
        self.overruns = 0

    @property
    def period(self) -> float:
        return 1.0 / self.rate

    def request_stop(self, reason: str = "stop requested", status: str = "STOPPED") -> None:
        """Ask the loop to halt the tree at the start of the next tick (any thread; from a signal,
        through :mod:`stuart_bt.core.interrupts`, never inside the handler itself).
        ``status`` is the outcome's: STOPPED when someone asked, ERROR when the run cannot go on."""
        if not self._stop.is_set():
            self._stop_status = status
        self._stop_reason = reason
        self._stop.set()

    def hold(self, reason: str = "hold requested") -> None:
        """Pause the tree at the start of the next tick (any thread): the running leaves are
        stopped, so their daemons stop the motion, and the ``on_halt`` hooks run; the composites
        keep their place, so :meth:`resume` goes on from the step that was interrupted (which
        starts again) instead of from the beginning. Stopping always wins over a hold."""
        self._hold_reason = reason
        self._hold.set()

    def resume(self) -> None:
        """Go on after :meth:`hold` (any thread)."""
        self._hold.clear()

    @property
    def held(self) -> bool:
        """A hold was asked for (it takes effect at the next tick)."""
        return self._hold.is_set()

    @property
    def hold_reason(self) -> str | None:
        """Why the tree is held (what the web view shows), or None when it is not."""
        return self._hold_reason if self._hold.is_set() else None

    @property
    def paused(self) -> bool:
        """The tree is paused: its running leaves and the motion were stopped (tick thread)."""
        return self._holding

    def _pause(self) -> None:
        """On the tick thread, once per hold: stop every running leaf and the daemons' motion."""
        self.events.publish("hold", reason=self._hold_reason)
        for node in self._nodes:
            if not node.children and node.status == Status.RUNNING:
                node.stop(Status.INVALID)
        self.publish_status_changes()
        for hook in self.on_halt:
            hook()

    def _held_tick(self) -> bool:
        """True while held (the duties run, the tree does not tick); publishes ``resume`` once the
        hold is lifted."""
        if self._hold.is_set():
            if not self._holding:
                self._holding = True
                self._pause()
            for hook in self.pre_tick:
                hook()
            return True
        if self._holding:
            self._holding = False
            self.events.publish("resume")
        return False

    def tick_once(self) -> Status:
        for hook in self.pre_tick:
            hook()
        self.tree.tick()
        self.ticks += 1
        self.publish_status_changes()
        return self.root.status

    def publish_status_changes(self) -> None:
        last = self._last
        for i, node in enumerate(self._nodes):
            status = node.status
            if status is not last[i]:
                self.events.publish("status", self._paths[i], old=last[i].value, new=status.value)
                last[i] = status

    def halt(self, reason: str) -> None:
        """Stop the tree now: running leaves cancel their commands; halt hooks stop the daemons."""
        self.events.publish("halt", reason=reason)
        self.root.stop(Status.INVALID)
        self.publish_status_changes()
        for hook in self.on_halt:
            hook()

    def run(self, max_duration: float | None = None) -> RunOutcome:
        """Tick until the root finishes, a stop is requested, or ``max_duration`` clock seconds pass."""
        started = self.clock.now()
        deadline = self.clock.now()
        period = self.period
        status_text: str | None = None
        reason: str | None = None
        while True:
            if self._stop.is_set():
                status_text, reason = self._stop_status, self._stop_reason
                self.halt(reason or "stop requested")
                break
            if self._held_tick():
                started += self.period  # time on hold is not run time (--max-duration)
                deadline += self.period
                self._sleep_until(deadline)
                continue
            status = self.tick_once()
            if status in FINISHED:
                status_text = status.value
                break
            now = self.clock.now()
            if max_duration is not None and now - started >= max_duration:
                status_text, reason = "TIMEOUT", f"run exceeded {max_duration:g} s"
                self.halt(reason)
                break
            deadline += period
            if now > deadline:
                self._overrun(now - deadline + period, period)
                deadline = now
            self._sleep_until(deadline)
        return RunOutcome(status_text, started, self.clock.now(), self.ticks, reason)

    def _sleep_until(self, deadline: float) -> None:
        factor = getattr(self.clock, "factor", 1.0)
        remaining = deadline - self.clock.now()
        if remaining <= 0:
            return
        if factor == float("inf"):  # a sim clock driver: time moves only while it waits
            while not self._stop.is_set() and self.clock.now() < deadline:
                self.clock.sleep_until(deadline, wake=self._stop, max_wall=WAITING_DUTY_PERIOD)
                for hook in self.while_waiting:  # a frozen world must not look like a frozen tree
                    hook()
        else:  # wake early on a stop request
            self._stop.wait(remaining / factor)

    def _overrun(self, took: float, period: float) -> None:
        self.overruns += 1
        now = self.clock.now()
        if now - self._last_overrun_warning >= self.overrun_warning_interval:
            self._last_overrun_warning = now
            self.events.publish(
                "warning",
                message=f"tick overrun: a tick took {took * 1000:.1f} ms of a {period * 1000:.1f} ms period",
                overruns=self.overruns,
            )


def preorder(node: py_trees.behaviour.Behaviour):
    """Parents before children (py_trees' own ``iterate`` visits children first)."""
    yield node
    for child in node.children:
        yield from preorder(child)
