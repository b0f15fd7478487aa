"""The mission executor's jobs and the worker thread that runs them one at a time.

A job is a :class:`Mission`, something to :class:`Say` that is not a mission (a reply, an unknown
target, nothing to continue), or one :class:`Look` before answering a question about what the
robot sees. :class:`JobQueue` holds the queue, the job being run, the tree running it and the
mission kept for "continue"; one condition guards all of it, because ``submit`` (any thread),
the reply thread and the worker all change it. Stop, continue and replace are queue operations
here, in the order they were said.
"""

from __future__ import annotations

import itertools
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..core.events import EventStream
    from ..htn.values import TaskCall
    from ..run.executor import Executor

MAX_QUEUED_REPLIES = 2  # replies waiting to be said; a newer one pushes out the oldest
STALE_REPLY_S = 10.0  # wall seconds a reply may wait for its turn before it answers a moment long gone


@dataclass(eq=False)
class Mission:
    """One accepted command: the tasks asked for and how far they got."""

    id: int
    utterance: str
    calls: list[TaskCall]
    texts: list[str]  # what was said for each call, for explanations
    status: str = "queued"  # queued | running | stopped | replaced | succeeded | failed
    done: int = 0  # calls finished
    repairs: int = 0
    resumed: bool = False
    reason: str | None = None  # technical: the failed leaf's own reason, in the report as it always was
    said: str | None = None  # what the robot said about a failure, in words people use
    failure: dict[str, Any] | None = None  # the failure's facts: code, skill, object or place, blocked_by
    cancelled: str | None = None  # "stopped" | "replaced": asked to end while running
    stop_tick: int | None = None  # executor tick when the stop was asked for
    halt_tick: int | None = None  # executor tick count when it halted
    resume_requested: bool = False  # "continue" came while its stop was still under way

    def to_dict(self) -> dict[str, Any]:
        out = {"id": self.id, "utterance": self.utterance, "tasks": [str(c) for c in self.calls],
               "status": self.status, "done": self.done, "repairs": self.repairs, "reason": self.reason}
        return {**out, **self.explained()}

    def explained(self) -> dict[str, Any]:
        """``said`` and ``failure`` when the mission failed and the robot said why (else nothing)."""
        return {k: v for k, v in (("said", self.said), ("failure", self.failure)) if v is not None}


@dataclass
class Say:
    """Something to say that is not a mission (reply, unknown target, nothing to continue)."""

    text: str
    why: str
    made: float = field(default_factory=time.monotonic)  # wall time it was queued: old replies go unsaid


@dataclass
class Look:
    """One look with the head camera before answering ``question`` (what do you see?)."""

    question: str


Job = Mission | Say | Look


class JobQueue:
    """The jobs waiting, the one running and the worker thread that runs them in turn."""

    def __init__(self, events: EventStream) -> None:
        self.events = events
        self.cond = threading.Condition()
        self.queue: deque[Job] = deque()
        self.current: Job | None = None
        self.executor: Executor | None = None  # the tree running now, to stop it
        self.closing = False
        self.worker: threading.Thread | None = None
        self.missions: list[Mission] = []
        self.halted: Mission | None = None
        self.pending_replies = 0  # questions being thought about on the reply thread
        self.asides: deque[str] = deque(maxlen=MAX_QUEUED_REPLIES)  # said between a mission's own speech
        self._ids = itertools.count(1)

    # -- the worker -----------------------------------------------------------------------------
    def start(self, run: Callable[[Job], None]) -> None:
        """Run every job with ``run`` on a worker thread of its own."""
        self.worker = threading.Thread(target=self._work, args=(run,), name="missions", daemon=True)
        self.worker.start()

    def close(self) -> None:
        """Drop what is queued, stop the running tree and wait for the worker to end."""
        with self.cond:
            self.closing = True
            self.queue.clear()
            if self.executor is not None:
                self.executor.request_stop("shutting down")
            self.cond.notify_all()
        if self.worker is not None:
            self.worker.join(timeout=30)

    @property
    def busy(self) -> bool:
        with self.cond:
            return self.current is not None or bool(self.queue) or self.pending_replies > 0

    def wait_idle(self, timeout: float | None = None) -> bool:
        """Wait (wall time) until nothing is queued, running or being answered."""
        with self.cond:
            return self.cond.wait_for(lambda: not (self.current or self.queue or self.pending_replies),
                                      timeout=timeout)

    def _work(self, run: Callable[[Job], None]) -> None:
        while True:
            with self.cond:
                self.cond.wait_for(lambda: self.queue or self.closing)
                if self.closing:
                    return
                job = self.current = self.queue.popleft()
            try:
                run(job)
            except Exception as e:  # noqa: BLE001 - a bug in one mission must not deafen the robot
                self.events.publish("warning", message=f"mission worker: {type(e).__name__}: {e}")
                if isinstance(job, Mission):
                    job.status, job.reason = "failed", str(e)
            finally:
                with self.cond:
                    self.current = None
                    self.executor = None
                    while self.asides:  # the mission ended before a reply found a pause: say it now
                        self.queue_reply(Say(self.asides.popleft(), "reply"))
                    self.cond.notify_all()

    # -- the tree running now ----------------------------------------------------------------------
    def attach(self, executor: Executor, mission: Mission | None) -> None:
        """The tree about to run; a stop said while it was being built reaches it."""
        with self.cond:
            self.executor = executor
            if mission is not None and mission.cancelled is not None:
                executor.request_stop(mission.cancelled)
            elif self.closing:  # close() came while this tree was being built: it must not run on
                executor.request_stop("shutting down")

    def detach(self) -> None:
        with self.cond:
            self.executor = None

    # -- what is said -------------------------------------------------------------------------------
    def say_first(self, say: Say) -> None:
        """Say this before anything queued."""
        with self.cond:
            self.queue.appendleft(say)
            self.cond.notify_all()

    def queue_reply(self, say: Say) -> None:
        """Queue a reply first in line, keeping at most MAX_QUEUED_REPLIES: the oldest goes
        unsaid (``cond`` held). Replies go before missions, so the queue of them stays short."""
        queued = [job for job in self.queue if isinstance(job, Say) and job.why == "reply"]
        for old in queued[: max(0, len(queued) - MAX_QUEUED_REPLIES + 1)]:
            self.queue.remove(old)
            self.events.publish("log", level="info",
                                message=f"reply dropped unsaid (newer talk came): {old.text[:60]!r}")
        self.queue.appendleft(say)

    def stale(self, job: Say) -> bool:
        """A reply that waited longer than STALE_REPLY_S answers a moment that has passed."""
        waited = time.monotonic() - job.made
        if job.why != "reply" or waited <= STALE_REPLY_S:
            return False
        self.events.publish("log", level="info", message=f"reply dropped unsaid after waiting {waited:.1f} s: "
                            f"{job.text[:60]!r}")
        return True

    # -- missions: queued, stopped, continued, replaced -----------------------------------------------
    def add(self, utterance: str, calls: list[TaskCall], texts: list[str], replace: bool) -> Mission:
        """A new mission, queued last, or first when it replaces the one running."""
        with self.cond:
            mission = Mission(next(self._ids), utterance, calls, texts)
            self.missions.append(mission)
            current = self.current
            if replace and isinstance(current, Mission) and current.status == "running":
                if current.cancelled is None:
                    self._cancel(current, "replaced", "replaced")
                self.queue.appendleft(mission)
            else:
                self.queue.append(mission)
            self.events.publish("mission", id=mission.id, phase="queued", tasks=[str(c) for c in calls],
                                replace=replace)
            self.cond.notify_all()
        return mission

    def stop(self, text: str, replace: bool) -> None:
        """Halt the running tree and clear the queue; ``replace``: new tasks follow the stop."""
        with self.cond:
            dropped = [j for j in self.queue if isinstance(j, Mission)]
            self.queue.clear()
            self.asides.clear()
            for m in dropped:
                m.status, m.reason = "stopped", "stop requested"
                self.events.publish("mission", id=m.id, phase="stopped", reason="queue cleared")
            current = self.current
            if isinstance(current, Mission):
                current.resume_requested = False  # a stop after "continue" wins over it
            if isinstance(current, Mission) and current.cancelled is None:
                self._cancel(current, "replaced" if replace else "stopped", text)
            elif self.executor is not None:
                self.executor.request_stop(text)
            if not isinstance(current, Mission) and dropped and not replace:
                self.halted = dropped[0]  # stopped before it started: "continue" starts it

    def _cancel(self, mission: Mission, how: str, reason: str) -> None:
        """Ask the running ``mission`` to end (``cond`` held)."""
        mission.cancelled = how
        if self.executor is not None:
            mission.stop_tick = self.executor.ticks
            self.executor.request_stop(reason)

    def continue_(self) -> None:
        """Resume the stopped mission, in the order things were said: a "continue" that arrives
        while the stop before it is still halting the tree resumes the mission as soon as the
        halt is done, instead of finding nothing to continue."""
        with self.cond:
            current = self.current
            if self.halted is None and isinstance(current, Mission) and current.cancelled == "stopped":
                current.resume_requested = True
                return
            mission, self.halted = self.halted, None
            if mission is None:
                self.queue.appendleft(Say("There is nothing to continue.", "continue"))
            else:
                self._resume(mission)
            self.cond.notify_all()

    def _resume(self, mission: Mission) -> None:
        """Queue a stopped mission first, to go on where it stopped (``cond`` held)."""
        mission.resumed, mission.cancelled, mission.status = True, None, "queued"
        self.queue.appendleft(mission)
        self.events.publish("mission", id=mission.id, phase="resumed", done=mission.done)

    def hold(self, m: Mission, halt_tick: int, reason: str | None) -> None:
        """The mission stopped part way: kept for "continue" (or resumed at once when "continue"
        was already said while the stop was halting the tree)."""
        m.halt_tick = halt_tick
        self.finish(m, "stopped", reason)
        with self.cond:
            m.cancelled = None
            if m.resume_requested:
                m.resume_requested = False
                self._resume(m)
            else:
                self.halted = m

    def finish(self, m: Mission, status: str, reason: str | None) -> None:
        m.status, m.reason = status, reason
        self.events.publish("mission", id=m.id, phase="stopped" if status == "stopped" else
                            "replaced" if status == "replaced" else "finished", status=status, reason=reason,
                            repairs=m.repairs, **m.explained())
