"""The mission executor: a long-running robot that takes utterances and runs missions one by one.

One :class:`MissionExecutor` owns one set of skill daemons (and, on the sim backend, the MuJoCo
world) for its whole life, through a :class:`~stuart_bt.run.session.Session`; each mission is planned
from the world state *when it starts*, compiled (:mod:`.compiler`) and ticked by its own
:class:`~stuart_bt.run.executor.Executor` on the session's clock, so daemons are never restarted
between missions.

``submit(utterance)`` is thread-safe (the ROS bridge and the web view call it from their own
threads) and returns at once; a worker thread runs the queue:

- tasks while busy wait in the queue, or replace the current mission when they say so;
- ``stop`` asks the running executor to stop (honoured at the start of the next tick: the tree
  halts, every daemon receives stop) and clears the queue; ``continue`` re-plans the halted
  mission's remaining tasks from the current world state;
- a failed leaf is repaired by re-planning the lowest failed compound task that still plans from
  the current state (an object that was not where memory said is forgotten first, so the robot
  looks for it again), at most ``max_repairs`` times; then the robot says why, in one sentence;
- an unknown place or object is said ("I don't know where the garage is") and nothing moves;
- conversation goes to a :class:`~.commands.Conversation` on a separate thread; its reply is
  spoken.

Everything the robot says goes through the speak leaf of a small tree, so speech is on the same
event stream and report as the missions. Events: ``utterance``, ``reply`` and ``mission``
(``phase``: queued, started, replaced, stopped, resumed, repaired, finished).
"""

from __future__ import annotations

import itertools
import threading
import time
from collections import deque
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from importlib.resources import files
from pathlib import Path
from typing import Any, Self

from py_trees.common import Status

from ..conversation.reply import Conversation
from ..htn import Planner, PlanningBudgetExceeded, PlanningFailed, TaskArgumentError, TaskNode
from ..htn.domain import Domain
from ..htn.state import lab_world
from ..htn.values import TaskCall
from ..language import Parser, Resolver, TaskIntent
from ..leaves import failure_code
from ..run.executor import Executor, RunOutcome
from ..run.session import RunOptions, Session
from ..tasks import project_domain
from ..tree.spec import Location, NodeSpec, TreeSpec
from .commands import CONTINUE, CONVERSATION, IGNORE, STOP, Command, interpret
from .compiler import CompiledMission, compile_plan

SESSION_HISTORY = 5000  # events a mission session keeps for its report: it may run all day
MAX_PENDING_REPLIES = 2  # questions being thought about at once; more talk meanwhile goes unanswered
MAX_QUEUED_REPLIES = 2  # replies waiting to be said; a newer one pushes out the oldest
STALE_REPLY_S = 10.0  # wall seconds a reply may wait for its turn before it answers a moment long gone
WATCHDOG_SENTENCE = "I stopped: I lost touch with my controller for a moment. Say continue when it is safe to go on."
OBJECT_FAULTS = ("not_found", "unreachable")  # failures that mean: the object is not where memory says


@dataclass
class MissionOptions:
    backend: str = "dry"
    rate: float = 20.0
    speed: float | None = None  # dry: clock seconds per wall second
    start: str | None = None  # marker the robot starts at (default entrance)
    require_wake: bool = True
    max_repairs: int = 2  # per mission
    max_duration: float | None = None  # clock seconds per tree run
    daemon_options: dict[str, dict[str, Any]] = field(default_factory=dict)
    log: Path | None = None
    report: Path | None = None
    seed: int = 0
    conversation: str = "none"  # none | llama | openai (stuart_bt.conversation.make_conversation)
    conversation_options: dict[str, Any] = field(default_factory=dict)  # e.g. {"base_url": ..., "seed": 0}
    propose_tasks: bool = False  # a request the grammar misses may get a model's task proposal, run after a yes


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
    reason: str | None = None
    cancelled: str | None = None  # "stopped" | "replaced": asked to end while running
    stop_tick: int | None = None  # executor tick when the stop was asked for
    halt_tick: int | None = None  # executor tick count when it halted
    resume_requested: bool = False  # "continue" came while its stop was still under way

    def to_dict(self) -> dict[str, Any]:
        return {"id": self.id, "utterance": self.utterance, "tasks": [str(c) for c in self.calls],
                "status": self.status, "done": self.done, "repairs": self.repairs, "reason": self.reason}


@dataclass
class _Say:
    """Something to say that is not a mission (reply, unknown target, nothing to continue)."""

    text: str
    why: str
    made: float = field(default_factory=time.monotonic)  # wall time it was queued: old replies go unsaid


@dataclass
class _Look:
    """One look with the head camera before answering ``question`` (what do you see?)."""

    question: str


class MissionExecutor:
    """Utterances in, missions out. Use as a context manager (daemons always shut down)."""

    def __init__(self, options: MissionOptions | None = None, *, conversation: Conversation | None = None,
                 domain: Domain | None = None, name: str = "Stuart") -> None:
        self.options = options or MissionOptions()
        self.parser = Parser(name, require_wake=self.options.require_wake)
        self.domain = domain or project_domain()
        if conversation is None:  # imported here: the factory imports this package's commands module
            from ..conversation import make_conversation

            conversation = make_conversation(self.options.conversation, **self.options.conversation_options)
        self.conversation = conversation
        markers = Path(str(files("stuart_bt.sim").joinpath("maps/lab_markers.json")))
        self.markers_file = markers
        self.lab = lab_world(markers, start=self.options.start or "entrance")
        self.resolver = Resolver(self.lab.markers, tuple(self.lab.objects))
        self.session = Session(_all_families_spec(str(markers)), RunOptions(
            backend=self.options.backend, rate=self.options.rate, speed=self.options.speed,
            start=self.options.start, log=self.options.log, daemon_options=self.options.daemon_options,
            seed=self.options.seed, history=SESSION_HISTORY))
        self.missions: list[Mission] = []
        self.halted: Mission | None = None
        self._queue: deque[Mission | _Say | _Look] = deque()
        self._current: Mission | _Say | _Look | None = None
        self._executor: Executor | None = None
        self._cond = threading.Condition()
        self._closing = False
        self._ids = itertools.count(1)
        self._worker: threading.Thread | None = None
        self._talk = ThreadPoolExecutor(max_workers=1, thread_name_prefix="conversation")
        self._pending_replies = 0
        self._asides: deque[str] = deque(maxlen=MAX_QUEUED_REPLIES)  # said between a mission's own speech
        self._unanswered = 0  # utterances let go while too many replies were pending
        self._last_unanswered_warning = float("-inf")
        self._proposal: tuple[str, list[TaskIntent]] | None = None  # (request, intents) awaiting a yes

    # -- life cycle ---------------------------------------------------------------------------------
    def start(self) -> Self:
        self.session.start()
        self.world.objects = dict(self.lab.objects)  # the robot's memory of where things are
        self._worker = threading.Thread(target=self._work, name="missions", daemon=True)
        self._worker.start()
        return self

    def __enter__(self) -> Self:
        try:
            return self.start()
        except BaseException:
            self.close()
            raise

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        with self._cond:
            self._closing = True
            self._queue.clear()
            if self._executor is not None:
                self._executor.request_stop("shutting down")
            self._cond.notify_all()
        if self._worker is not None:
            self._worker.join(timeout=30)
        self._talk.shutdown(wait=False, cancel_futures=True)
        if self.options.report:
            from ..run.report import write_report
            write_report(self.report(), self.options.report)
        self.session.close()

    @property
    def events(self):
        return self.session.events

    @property
    def world(self):
        return self.session.blackboard.world

    @property
    def busy(self) -> bool:
        with self._cond:
            return self._current is not None or bool(self._queue) or self._pending_replies > 0

    def wait_idle(self, timeout: float | None = None) -> bool:
        """Wait (wall time) until nothing is queued, running or being answered."""
        with self._cond:
            return self._cond.wait_for(lambda: not (self._current or self._queue or self._pending_replies),
                                       timeout=timeout)

    def report(self) -> dict[str, Any]:
        report = self.session.recorder.build(
            status=self._overall_status(), reason=None, tree="<missions>", backend=self.options.backend,
            ticks=0, final_pose=self.world.pose.to_dict(), held=self.world.held)
        report["missions"] = [m.to_dict() for m in self.missions]
        return report

    def _overall_status(self) -> str:
        if not self.missions:
            return "NOT_RUN"
        last = self.missions[-1].status
        return {"succeeded": "SUCCESS", "stopped": "STOPPED"}.get(last, "FAILURE")

    # -- input --------------------------------------------------------------------------------------
    def submit(self, utterance: str, woken: bool = False) -> Command:
        """Take one utterance (any thread); returns at once with what it was understood as.
        ``woken``: treat it as if the wake phrase had been said (an input that filtered it already).
        The ``utterance`` event's ``parsed`` holds every intent the grammar found (the
        ``stuart-bt parse`` intents, a leading ``stop`` included); ``intents`` the ones to plan."""
        command = interpret(self.parser, utterance, woken)
        self.events.publish("utterance", text=utterance, kind=command.kind, replace=command.replace,
                            intents=[i.to_dict() for i in command.intents],
                            parsed=[i.to_dict() for i in command.parse.intents])
        if self._answer_proposal(command):
            return command
        if command.kind == IGNORE:
            return command
        if command.kind == STOP:
            self._stop(command)
        elif command.kind == CONTINUE:
            self._continue()
        elif command.kind == CONVERSATION:
            self._converse(command.text)
        if command.intents:
            self._accept(utterance, command.intents, replace=command.replace)
        return command

    def daemon_request(self, family: str, cmd: str, args: dict[str, Any] | None = None) -> bool:
        """Send one command to a skill daemon from the tick thread (the supervisor belongs to it),
        before the running tree's next tick: e.g. ``("pick", "confirm")`` for the pick
        confirmation gate. False (and nothing is sent) when no tree is running: a command kept for
        a later tree could confirm a pick nobody has seen yet."""
        with self._cond:
            executor = self._executor
            if executor is None or self.session.supervisor is None:
                return False
            supervisor = self.session.supervisor
            if family not in supervisor.families:
                raise ValueError(f"no {family!r} daemon; the daemons are {', '.join(supervisor.families)}")
            sent: list[bool] = []

            def send() -> None:  # once; it stays in the list (removing it mid-iteration skips a hook)
                if not sent:
                    sent.append(True)
                    supervisor.client(family).request(cmd, args or {})

            executor.pre_tick.append(send)
            return True

    def _stop(self, command: Command) -> None:
        with self._cond:
            dropped = [j for j in self._queue if isinstance(j, Mission)]
            self._queue.clear()
            self._asides.clear()
            for m in dropped:
                m.status, m.reason = "stopped", "stop requested"
                self.events.publish("mission", id=m.id, phase="stopped", reason="queue cleared")
            current = self._current
            if isinstance(current, Mission):
                current.resume_requested = False  # a stop after "continue" wins over it
            if isinstance(current, Mission) and current.cancelled is None:
                current.cancelled = "replaced" if command.replace else "stopped"
                if self._executor is not None:
                    current.stop_tick = self._executor.ticks
                    self._executor.request_stop(command.text)
            elif self._executor is not None:
                self._executor.request_stop(command.text)
            if not isinstance(current, Mission) and dropped and not command.replace:
                self.halted = dropped[0]  # stopped before it started: "continue" starts it

    def _continue(self) -> None:
        """Resume the stopped mission, in the order things were said: a "continue" that arrives
        while the stop before it is still halting the tree resumes the mission as soon as the
        halt is done, instead of finding nothing to continue."""
        with self._cond:
            current = self._current
            if self.halted is None and isinstance(current, Mission) and current.cancelled == "stopped":
                current.resume_requested = True
                return
            mission, self.halted = self.halted, None
            if mission is None:
                self._queue.appendleft(_Say("There is nothing to continue.", "continue"))
            else:
                self._resume(mission)
            self._cond.notify_all()

    def _resume(self, mission: Mission) -> None:
        """Queue a stopped mission first, to go on where it stopped (``_cond`` held)."""
        mission.resumed, mission.cancelled, mission.status = True, None, "queued"
        self._queue.appendleft(mission)
        self.events.publish("mission", id=mission.id, phase="resumed", done=mission.done)

    def _converse(self, text: str) -> None:
        """Answer in the conversation thread; a question about what the robot sees, asked while
        it is idle, first gets one fresh look (an ``observe`` tree) so the answer is current.
        A robot answers one question at a time: while MAX_PENDING_REPLIES are being thought
        about, more talk is let go (a warning, at most one a second, counts it) instead of piling
        up replies that would keep the next command waiting."""
        from ..conversation.prompt import is_vision_question

        with self._cond:
            if self._pending_replies >= MAX_PENDING_REPLIES:
                self._unanswered += 1
                now = time.monotonic()
                if now - self._last_unanswered_warning >= 1.0:
                    self._last_unanswered_warning = now
                    self.events.publish("warning", message=f"too much talk at once: {self._unanswered} "
                                        f"utterance(s) not answered so far (latest: {text[:60]!r})")
                return
            self._pending_replies += 1
            look_first = (is_vision_question(text) and self._current is None and not self._queue
                          and self.session.supervisor is not None and "vision" in self.session.supervisor.families)
            if look_first:
                self._queue.appendleft(_Look(text))
                self._cond.notify_all()
        if not look_first:
            self._answer(text)

    def _answer(self, text: str) -> None:
        """Reply from the world state as it is now (the reply thread; ``_pending_replies`` was
        counted by :meth:`_converse`)."""
        from ..perception.context import seen_objects  # no cv2 or numpy: plain world-state reading

        busy = self._current is not None and not isinstance(self._current, _Look)
        context = {"held": self.world.held, "at": self.world.last_marker, "busy": busy,
                   "detections": seen_objects(self.world, self.session.clock.now())}

        def answer() -> None:
            try:
                if self._propose(text):
                    return
                reply = self.conversation.reply(text, context)
                self.events.publish("reply", text=reply.text, gestures=list(reply.gestures), to=text)
                with self._cond:
                    if isinstance(self._current, Mission) and self._executor is not None:
                        self._asides.append(reply.text)  # said at the mission's next pause in speech
                    else:
                        self._queue_reply(_Say(reply.text, "reply"))
            finally:
                with self._cond:
                    self._pending_replies -= 1
                    self._cond.notify_all()

        self._talk.submit(answer)

    def _queue_reply(self, say: _Say) -> None:
        """Queue a reply first in line, keeping at most MAX_QUEUED_REPLIES: the oldest goes
        unsaid (``_cond`` held). Replies go before missions, so the queue of them stays short."""
        queued = [job for job in self._queue if isinstance(job, _Say) and job.why == "reply"]
        for old in queued[: max(0, len(queued) - MAX_QUEUED_REPLIES + 1)]:
            self._queue.remove(old)
            self.events.publish("log", level="info",
                                message=f"reply dropped unsaid (newer talk came): {old.text[:60]!r}")
        self._queue.appendleft(say)

    def _stale(self, job: _Say) -> bool:
        """A reply that waited longer than STALE_REPLY_S answers a moment that has passed."""
        waited = time.monotonic() - job.made
        if job.why != "reply" or waited <= STALE_REPLY_S:
            return False
        self.events.publish("log", level="info", message=f"reply dropped unsaid after waiting {waited:.1f} s: "
                            f"{job.text[:60]!r}")
        return True

    # -- task proposals (stuart_bt.mission.proposals) --------------------------------------------------
    def _propose(self, text: str) -> bool:
        """On the reply thread: a request the grammar missed may get a model's proposal. Only one
        that resolves and plans-checks is offered ("Shall I ...?"); it waits for a yes."""
        from . import proposals

        if not self.options.propose_tasks or proposals.is_question(text) or \
                not isinstance(self.conversation, proposals.Proposer):
            return False
        from ..core.gestures import LIBRARY

        prompt = proposals.messages(text, sorted(self.lab.markers), sorted(self.lab.objects), sorted(LIBRARY))
        try:
            intents = proposals.parse(self.conversation.propose(prompt, proposals.schema()))
        except Exception as e:  # noqa: BLE001 - a failing model must leave the plain reply
            self.events.publish("warning", message=f"task proposal failed: {type(e).__name__}: {e}")
            return False
        checked, _, unknown = self._resolve(intents or [])
        if not checked or unknown:  # a proposal that would not resolve or plan is not offered
            return False
        question = f"Shall I {proposals.describe(checked)}? Say yes to go ahead."
        with self._cond:
            self._proposal = (text, checked)
            self._queue.appendleft(_Say(question, "proposal"))
            self._cond.notify_all()
        self.events.publish("proposal", phase="offered", to=text, intents=[i.to_dict() for i in checked])
        return True

    def _answer_proposal(self, command: Command) -> bool:
        """A yes runs the offered proposal, a no drops it (no wake phrase needed for either: the
        robot just asked); anything else drops it and is handled as usual."""
        from .proposals import NO, YES

        with self._cond:
            pending, self._proposal = self._proposal, None
        if pending is None:
            return False
        text = command.parse.command if command.parse.wake else command.parse.utterance
        if YES.match(text or ""):
            self.events.publish("proposal", phase="confirmed", to=pending[0])
            self._accept(pending[0], pending[1], replace=False)
            return True
        if NO.match(text or ""):
            self.events.publish("proposal", phase="declined", to=pending[0])
            with self._cond:
                self._queue.appendleft(_Say("OK, I won't.", "proposal"))
                self._cond.notify_all()
            return True
        self.events.publish("proposal", phase="dropped", to=pending[0])
        return False

    def _resolve(self, intents: list[TaskIntent]) -> tuple[list[TaskIntent], list[TaskCall], list[str]]:
        """Targets resolved against the map, objects and gestures, and each intent made a domain
        call; the sentences to say for those that would not (an unknown place, a bad argument)."""
        resolved: list[TaskIntent] = []
        calls: list[TaskCall] = []
        unknown: list[str] = []
        for intent in intents:
            resolution = self.resolver.resolve(intent) if intent.action != "gesture" else None
            if resolution is not None and not resolution.ok:
                unknown.append(resolution.say())
                continue
            if resolution is not None:
                intent = TaskIntent(**{**intent.to_dict(), "target": resolution.name})
            try:
                calls.append(self.domain.to_call(intent.to_dict()))
            except TaskArgumentError as e:
                unknown.append(f"I cannot do that: {e}.")
                continue
            resolved.append(intent)
        return resolved, calls, unknown

    def _accept(self, utterance: str, intents: list[TaskIntent], replace: bool) -> None:
        _, calls, unknown = self._resolve(intents)
        with self._cond:
            if unknown:  # say so; nothing of this command moves the robot
                self._queue.appendleft(_Say(" ".join(unknown), "unknown"))
                self._cond.notify_all()
                return
            mission = Mission(next(self._ids), utterance, calls, [i.raw_text or i.action for i in intents])
            self.missions.append(mission)
            current = self._current
            if replace and isinstance(current, Mission) and current.status == "running":
                if current.cancelled is None:
                    current.cancelled = "replaced"
                    if self._executor is not None:
                        current.stop_tick = self._executor.ticks
                        self._executor.request_stop("replaced")
                self._queue.appendleft(mission)
            else:
                self._queue.append(mission)
            self.events.publish("mission", id=mission.id, phase="queued", tasks=[str(c) for c in calls],
                                replace=replace)
            self._cond.notify_all()

    # -- the worker ---------------------------------------------------------------------------------
    def _work(self) -> None:
        while True:
            with self._cond:
                self._cond.wait_for(lambda: self._queue or self._closing)
                if self._closing:
                    return
                job = self._current = self._queue.popleft()
            try:
                if isinstance(job, _Say):
                    if not self._stale(job):
                        self._say(job.text)
                elif isinstance(job, _Look):
                    self._look_then_answer(job.question)
                else:
                    self._run_mission(job)
            except Exception as e:  # noqa: BLE001 - a bug in one mission must not deafen the robot
                self.events.publish("warning", message=f"mission worker: {type(e).__name__}: {e}")
                if isinstance(job, Mission):
                    job.status, job.reason = "failed", str(e)
            finally:
                with self._cond:
                    self._current = None
                    self._executor = None
                    while self._asides:  # the mission ended before a reply found a pause: say it now
                        self._queue_reply(_Say(self._asides.popleft(), "reply"))
                    self._cond.notify_all()

    def _look_then_answer(self, question: str) -> None:
        try:
            spec = TreeSpec(NodeSpec("observe", "look", "look", _where(), {}), "<look>")
            self._run_tree(spec, None)  # a failed look leaves the memory as it was: still answer
        finally:
            self._answer(question)

    def _say(self, text: str) -> RunOutcome:
        spec = TreeSpec(NodeSpec("speak", "say", "say", _where(), {"text": text, "timeout": 120.0}), "<say>")
        outcome, _, _ = self._run_tree(spec, None)
        return outcome

    def _run_mission(self, m: Mission) -> None:
        if self.halted is not None and self.halted is not m:
            self.halted = None  # a new mission: the halted one is not resumed any more
        m.status = "running"
        self.events.publish("mission", id=m.id, phase="started", tasks=[str(c) for c in m.calls[m.done:]],
                            resumed=m.resumed)
        if self.session.lost is not None:  # the world is gone: nothing can run any more
            self._finish(m, "failed", self.session.lost)
            return
        compiled, index, unplannable = self._plan_remaining(m)
        while compiled is not None:
            outcome, succeeded, failed_path = self._run_tree(compiled.spec, m)
            m.done = max(m.done, _calls_done(compiled, index, succeeded))
            if outcome.status == "SUCCESS":
                break
            if outcome.status == "ERROR":  # no repair can help: the run itself could not go on
                self._finish(m, "failed", outcome.reason)
                return
            if m.cancelled == "replaced" or self._closing:
                self._finish(m, "replaced", "replaced by a new command")
                return
            if outcome.status == "STOPPED" or m.cancelled == "stopped":
                self._hold(m, outcome, outcome.reason)
                return
            reason = self._failure_reason(failed_path, outcome)
            if self._leaf_outcome(failed_path).get("code") == "watchdog":
                # this process froze and a daemon stopped the robot: it moves again only when told to
                self._hold(m, outcome, reason)
                if self.halted is m:
                    self._say(WATCHDOG_SENTENCE)
                return
            if m.repairs >= self.options.max_repairs or failed_path is None:
                self._explain_failure(m, compiled, failed_path, reason)
                return
            m.repairs += 1
            compiled, index = self._repair(m, compiled, index, failed_path)
            if compiled is None:
                self._explain_failure(m, None, failed_path, reason)
                return
            self.events.publish("mission", id=m.id, phase="repaired", failed=failed_path, reason=reason,
                                repairs=m.repairs, tasks=[compiled.tasks[p].call for p in compiled.top])
        if unplannable is not None:
            self._say(unplannable)
            self._finish(m, "failed", unplannable)
            return
        self._finish(m, "succeeded", None)

    def _hold(self, m: Mission, outcome: RunOutcome, reason: str | None) -> None:
        """The mission stopped part way: kept for "continue" (or resumed at once when "continue"
        was already said while the stop was halting the tree)."""
        m.halt_tick = outcome.ticks
        self._finish(m, "stopped", reason)
        with self._cond:
            m.cancelled = None
            if m.resume_requested:
                m.resume_requested = False
                self._resume(m)
            else:
                self.halted = m

    def _finish(self, m: Mission, status: str, reason: str | None) -> None:
        m.status, m.reason = status, reason
        self.events.publish("mission", id=m.id, phase="stopped" if status == "stopped" else
                            "replaced" if status == "replaced" else "finished", status=status, reason=reason,
                            repairs=m.repairs)

    # -- planning -----------------------------------------------------------------------------------
    def _state(self):
        return self.domain.initial_state(self.world)

    def _plan_remaining(self, m: Mission) -> tuple[CompiledMission | None, list[int], str | None]:
        """Plan the calls not done yet. When the whole list cannot be planned, the longest prefix
        that can is run and the reason for the next call is said afterwards."""
        calls = m.calls[m.done:]
        planner = Planner(self.domain, acks=not m.resumed)
        preface = "Carrying on." if m.resumed else None
        first_error: str | None = None
        for k in range(len(calls), 0, -1):
            try:
                plan = planner.plan(calls[:k], self._state())
            except (PlanningFailed, PlanningBudgetExceeded, TaskArgumentError) as e:
                if first_error is None:
                    first_error = _sentence(m.texts[m.done + k - 1] if m.done + k - 1 < len(m.texts) else "",
                                            calls[k - 1], e)
                continue
            compiled = compile_plan(plan, preface=preface, markers_file=str(self.markers_file))
            return compiled, list(range(m.done, m.done + k)), first_error
        if first_error is None:
            first_error = "I have nothing to do."
        return None, [], first_error

    def _repair(self, m: Mission, compiled: CompiledMission, index: list[int],
                failed_path: str) -> tuple[CompiledMission | None, list[int]]:
        """Re-plan the lowest failed compound task that plans from the current state, followed by
        what was left after it at every level, then the mission's remaining calls."""
        leaf = compiled.task_at(failed_path)
        top_path = next((p for p in compiled.top if failed_path == p or failed_path.startswith(p + "/")), None)
        if leaf is None or top_path is None:
            return None, []
        pos = compiled.top.index(top_path)
        call_index = index[pos]
        self._forget_misplaced(leaf, failed_path)
        later = [(_call(compiled.tasks[p]), index[pos + 1 + i]) for i, p in enumerate(compiled.top[pos + 1:])]
        later += [(c, j) for j, c in enumerate(m.calls) if j > max(index)]
        later_calls = [c for c, _ in later]
        later_index = [j for _, j in later]
        planner = Planner(self.domain, acks=False)
        compound = leaf.parent
        while compound is not None and compound.kind != "mission":
            calls = [_call(compound), *_following(compound)]
            try:
                plan = planner.plan(calls + later_calls, self._state())
            except (PlanningFailed, PlanningBudgetExceeded, TaskArgumentError):
                compound = compound.parent
                continue
            repaired = compile_plan(plan, markers_file=str(self.markers_file))
            return repaired, [call_index] * len(calls) + later_index
        rest = [j for j in range(call_index, len(m.calls)) if j == call_index or j > max(index)]
        try:  # last resort: the whole task that was asked for, again from here
            plan = planner.plan([m.calls[j] for j in rest], self._state())
        except (PlanningFailed, PlanningBudgetExceeded, TaskArgumentError):
            return None, []
        return compile_plan(plan, markers_file=str(self.markers_file)), rest

    def _forget_misplaced(self, task: TaskNode, failed_path: str) -> None:
        """A pick or find that failed because the object was not there: forget where it was, so
        the re-plan looks for it."""
        label = (task.skill_args or {}).get("object")
        if task.skill in ("pick", "find") and label and self._leaf_outcome(failed_path).get("code") in OBJECT_FAULTS:
            self.world.objects.pop(label, None)

    # -- running one tree ---------------------------------------------------------------------------
    def _run_tree(self, spec: TreeSpec, mission: Mission | None) -> tuple[RunOutcome, set[str], str | None]:
        """Build and tick one tree on the session's daemons; the paths that succeeded and the
        leaf whose failure failed the tree."""
        executor = self.session.executor_for(spec)
        root = executor.root
        succeeded: set[str] = set()

        def track(event: Any) -> None:
            if event.kind == "status" and event.data.get("new") == "SUCCESS" and event.path:
                succeeded.add(event.path)

        unsubscribe = self.events.subscribe(track)
        if mission is not None:
            executor.pre_tick.append(self._say_aside)
        with self._cond:
            self._executor = executor
            if mission is not None and mission.cancelled is not None:
                executor.request_stop(mission.cancelled)
            elif self._closing:  # close() came while this tree was being built: it must not run on
                executor.request_stop("shutting down")
        try:
            outcome = executor.run(self.options.max_duration)
        finally:
            unsubscribe()
            with self._cond:
                self._executor = None
        failed = _failed_leaf(root) if outcome.status == "FAILURE" else None
        return outcome, succeeded, failed

    def _say_aside(self) -> None:
        """Before a mission tick: a reply that is waiting goes to the speech daemon when the mission
        is not speaking, so a question asked during a walk is answered during the walk. The
        mission's own next speech takes the voice back (the daemon preempts the older one)."""
        if not self._asides or self.session.supervisor is None or "tts" not in self.session.supervisor.families:
            return
        tts = self.session.supervisor.client("tts")
        if any(r.cmd == "say" for r in tts.in_flight):
            return
        with self._cond:
            text = self._asides.popleft() if self._asides else None
        if text is not None:
            tts.request("say", {"text": text}, path="reply")

    def _leaf_outcome(self, path: str | None) -> dict[str, Any]:
        """What the leaf at ``path`` recorded last: status, reason, the daemon's error code, result."""
        outcomes = self.session.blackboard.get("outcomes", None) or {}
        return (outcomes.get(path) if path else None) or {}

    def _leaf_reason(self, path: str | None) -> str | None:
        return self._leaf_outcome(path).get("reason")

    def _failure_reason(self, path: str | None, outcome: RunOutcome) -> str:
        return self._leaf_reason(path) or outcome.reason or "something went wrong"

    def _explain_failure(self, m: Mission, compiled: CompiledMission | None, path: str | None, reason: str) -> None:
        idx = min(m.done, len(m.texts) - 1)
        what = m.texts[idx] if m.texts else "do that"
        detail = reason.split(": ", 1)[1] if failure_code(reason) else reason
        sentence = f"Sorry, I could not {_clause(what)}: {detail.rstrip('.')}."
        self._say(sentence)
        self._finish(m, "failed", sentence)


# -- helpers --------------------------------------------------------------------------------------------
def _all_families_spec(markers_file: str) -> TreeSpec:
    """A stand-in tree naming one leaf of every skill family, so the Session starts every daemon."""
    where = _where()
    leaves = [NodeSpec("speak", "speak", "daemons/speak", where, {"text": ""}),
              NodeSpec("navigate", "navigate", "daemons/navigate", where, {"dx": 0}),
              NodeSpec("gesture", "gesture", "daemons/gesture", where, {"play": "clap"}),
              NodeSpec("pick", "pick", "daemons/pick", where, {"object": "cup"}),
              NodeSpec("find", "find", "daemons/find", where, {"object": "cup"})]
    return TreeSpec(NodeSpec("sequence", "daemons", "daemons", where, {}, leaves), "<missions>",
                    markers_file=markers_file)


def _where() -> Location:
    return Location("<mission>", 1, 1)


def _failed_leaf(root: Any) -> str | None:
    """Follow the failure down: the last failed child of every failed node ends at the leaf."""
    node = root
    while node.children:
        failed = [c for c in node.children if c.status == Status.FAILURE]
        if not failed:
            break
        node = failed[-1]
    return getattr(node, "spec_path", None) if not node.children else None


def _following(node: TaskNode) -> list[TaskCall]:
    """What was still to do after ``node`` inside its top-level task: the later siblings at
    every level up (acknowledgements left out: they were said already)."""
    out: list[TaskCall] = []
    while node.parent is not None and node.parent.kind != "mission":
        out += [_call(s) for s in _after(node) if not s.ack]
        node = node.parent
    return out


def _after(node: TaskNode) -> list[TaskNode]:
    siblings = node.parent.children if node.parent is not None else []
    return siblings[siblings.index(node) + 1:]


def _call(node: TaskNode) -> TaskCall:
    return TaskCall(node.name, tuple(node.args.values()))


def _calls_done(compiled: CompiledMission, index: list[int], succeeded: set[str]) -> int:
    """How many of the mission's calls are finished: a call is done when every top-level entry
    of the tree that belongs to it succeeded."""
    done = 0
    for i, path in enumerate(compiled.top):
        if path not in succeeded:
            break
        if i + 1 == len(compiled.top) or index[i + 1] != index[i]:
            done = index[i] + 1
    return done


def _clause(text: str) -> str:
    text = text.strip().rstrip(".!?")
    return text[0].lower() + text[1:] if text else "do that"


def _sentence(text: str, call: TaskCall, error: Exception) -> str:
    """One spoken sentence for a task that cannot be planned."""
    cause = _why(error.failure, call.name) if isinstance(error, PlanningFailed) else None
    return f"Sorry, I cannot {_clause(text) if text else str(call)}: {cause or str(error).splitlines()[0]}."


HUMAN_CLAUSES = {"held == null": "my hands are full", "held == obj": "I am not holding it",
                 "place in markers": "I do not know that place", "obj in objects": "I do not know where it is"}


def _why(failure: Any, task: str) -> str | None:
    """The first rejection of the failed ``task`` inside a nested planning failure, in words."""
    stack = [failure]
    while stack:
        f = stack.pop()
        if f.task.split("(")[0] == task:
            for attempt in f.attempts:
                if not attempt.chosen and attempt.reason is not None and not hasattr(attempt.reason, "attempts"):
                    clause = str(attempt.reason).split(" is false")[0].strip()
                    return HUMAN_CLAUSES.get(clause, str(attempt.reason))
            return f.message
        stack.extend(a.reason for a in f.attempts if hasattr(a.reason, "attempts"))
    return None
