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
  looks for it again), at most ``max_repairs`` times, and not again when the repair failed for
  the very reason it was meant to mend; then the robot says why, in one sentence of words
  people use (:mod:`.failures`), while the mission's ``reason`` keeps the technical one;
- an unknown place or object is said ("I don't know where the garage is") and nothing moves;
- conversation goes to a :class:`~.commands.Conversation` on a separate thread; its reply is
  spoken.

Everything the robot says goes through the speak leaf of a small tree, so speech is on the same
event stream and report as the missions. Events: ``utterance``, ``reply`` and ``mission``
(``phase``: queued, started, replaced, stopped, resumed, repaired, finished).

The work is split by job: :mod:`.queue` (the jobs, the worker thread; stop, continue and
replace), :mod:`.understanding` (what the tasks said refer to), :mod:`.replies` (conversation),
:mod:`.proposals` (a model's task proposal, run after a yes), :mod:`.repair` (planning what is
left, repairs), :mod:`.speech` and :mod:`.failures` (sentences about plans and failures) and
:mod:`.running` (one tree on the daemons). :class:`MissionExecutor` wires them together and runs each mission from its
plan to its end.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import partial
from importlib.resources import files
from pathlib import Path
from typing import Any, Self

from ..conversation.reply import Conversation
from ..htn.domain import Domain
from ..htn.state import lab_world, spoken_name
from ..language import Parser, Resolver, TaskIntent
from ..run.executor import RunOutcome
from ..run.session import RunOptions, Session
from ..tasks import project_domain
from ..tree.spec import TreeSpec
from .attention import Attention
from .commands import CONTINUE, CONVERSATION, IGNORE, STOP, Command, hearing_doubts, interpret
from .failures import Failure, Words
from .proposals import Offers
from .queue import Job, JobQueue, Look, Mission, Say
from .repair import Replanner, calls_done
from .replies import Replies
from .running import TreeRunner, all_families_tree, failure_facts, leaf_outcome, say_tree
from .speech import WATCHDOG_SENTENCE, could_not, said_could_not
from .understanding import resolve, said

SESSION_HISTORY = 5000  # events a mission session keeps for its report: it may run all day


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
        self.session = Session(all_families_tree(str(markers)), RunOptions(
            backend=self.options.backend, rate=self.options.rate, speed=self.options.speed,
            start=self.options.start, log=self.options.log, daemon_options=self.options.daemon_options,
            seed=self.options.seed, history=SESSION_HISTORY))
        self.jobs = JobQueue(self.session.events)
        self.offers = Offers(self.jobs, conversation, self.lab, self.options.propose_tasks,
                             partial(resolve, self.resolver, self.domain), self._accept, self.parser.grammar.parse)
        self.replies = Replies(self.jobs, self.session, conversation, self.offers.offer, self._run_tree)
        self.runner = TreeRunner(self.session, self.jobs, aside=self.replies.say_aside)
        self.replanner = Replanner(self.domain, self.session.blackboard, markers)
        self.attention = Attention()  # "Hey Stuart." ... "go to the kitchen"

    # -- life cycle ---------------------------------------------------------------------------------
    def start(self) -> Self:
        self.session.start()
        self.world.objects = dict(self.lab.objects)  # the robot's memory of where things are
        self.jobs.start(self._run_job)
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
        self.jobs.close()
        self.replies.close()
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
    def missions(self) -> list[Mission]:
        """Every mission accepted so far, in the order they were said."""
        return self.jobs.missions

    @property
    def halted(self) -> Mission | None:
        """The mission that stopped part way and is kept for "continue"."""
        return self.jobs.halted

    @property
    def busy(self) -> bool:
        return self.jobs.busy

    def wait_idle(self, timeout: float | None = None) -> bool:
        """Wait (wall time) until nothing is queued, running or being answered."""
        return self.jobs.wait_idle(timeout)

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
    def submit(self, utterance: str, woken: bool = False, *, source: str = "typed",
               heard: Mapping[str, Any] | None = None) -> Command:
        """Take one utterance (any thread); returns at once with what it was understood as.
        ``woken``: treat it as if the wake phrase had been said (an input that filtered it already).
        ``source`` says where it came from (``typed``, ``web``, ``ros``, a hearing source such as
        ``mic:...``); ``heard``, for speech, what hearing adds (``audio_s``, ``confidence``, ...).
        The ``utterance`` event's ``parsed`` holds every intent the grammar found (the
        ``stuart-bt parse`` intents, a leading ``stop`` included); ``intents`` the ones to plan."""
        held = self.attention.take() and not woken
        command = interpret(self.parser, utterance, woken or held)
        command.parse.doubt.extend(hearing_doubts(command, heard or {}))
        self.attention.after(command)
        self.events.publish("utterance", text=utterance, kind=command.kind, replace=command.replace,
                            intents=[i.to_dict() for i in command.intents],
                            parsed=[i.to_dict() for i in command.parse.intents], source=source,
                            **({"wake_held": True} if held else {}), **(heard or {}))
        if self.offers.answer(command):
            return command
        if command.kind == IGNORE:
            return command
        if command.kind == STOP:
            self.jobs.stop(command.text, command.replace)
        elif command.kind == CONTINUE:
            self.jobs.continue_()
        elif command.kind == CONVERSATION:
            self.replies.converse(command.text)
        if command.intents and command.parse.doubt:  # a stop in it has already stopped the robot
            command.refused = self.offers.ask(utterance, command.intents, [d.detail for d in command.parse.doubt])
        elif command.intents:
            taken = self._accept(utterance, command.intents, replace=command.replace)
            if isinstance(taken, Mission):
                command.mission = taken.id
            else:
                command.refused = taken
        return command

    def daemon_request(self, family: str, cmd: str, args: dict[str, Any] | None = None) -> bool:
        """Send one command to a skill daemon from the tick thread (the supervisor belongs to it),
        before the running tree's next tick: e.g. ``("pick", "confirm")`` for the pick
        confirmation gate. False (and nothing is sent) when no tree is running: a command kept for
        a later tree could confirm a pick nobody has seen yet."""
        with self.jobs.cond:
            executor = self.jobs.executor
            if executor is None or self.session.supervisor is None:
                return False
            self.session.request_before_tick(executor, family, cmd, args)
            return True

    def _accept(self, utterance: str, intents: list[TaskIntent], replace: bool) -> Mission | str:
        """The mission queued for the intents, or what the robot says instead (an unknown place)."""
        _, calls, unknown = resolve(self.resolver, self.domain, intents)
        if unknown:  # say so; nothing of this command moves the robot
            sentence = " ".join(unknown)
            self.jobs.say_first(Say(sentence, "unknown"))
            return sentence
        return self.jobs.add(utterance, calls, said(intents), replace)

    # -- the worker's jobs --------------------------------------------------------------------------
    def _run_job(self, job: Job) -> None:
        if isinstance(job, Say):
            if not self.jobs.stale(job):
                self._say(job.text)
        elif isinstance(job, Look):
            self.replies.look_then_answer(job.question)
        else:
            self._run_mission(job)

    def _run_tree(self, spec: TreeSpec, mission: Mission | None) -> tuple[RunOutcome, set[str], str | None]:
        """Every tree runs through here (a subclass may watch them): the outcome, the paths that
        succeeded and the leaf whose failure failed the tree."""
        return self.runner.run(spec, mission, self.options.max_duration)

    def _say(self, text: str) -> RunOutcome:
        outcome, _, _ = self._run_tree(say_tree(text), None)
        return outcome

    def _run_mission(self, m: Mission) -> None:
        jobs = self.jobs
        if jobs.halted is not None and jobs.halted is not m:
            jobs.halted = None  # a new mission: the halted one is not resumed any more
        m.status = "running"
        self.events.publish("mission", id=m.id, phase="started", tasks=[str(c) for c in m.calls[m.done:]],
                            resumed=m.resumed)
        if self.session.lost is not None:  # the world is gone: nothing can run any more
            jobs.finish(m, "failed", self.session.lost)
            return
        compiled, index, unplannable = self.replanner.plan_remaining(m)
        previous: tuple[str | None, str] | None = None  # the failure (skill, reason) the last repair was for
        while compiled is not None:
            outcome, succeeded, failed_path = self._run_tree(compiled.spec, m)
            m.done = max(m.done, calls_done(compiled, index, succeeded))
            if outcome.status == "SUCCESS":
                break
            if outcome.status == "ERROR":  # no repair can help: the run itself could not go on
                jobs.finish(m, "failed", outcome.reason)
                return
            if m.cancelled == "replaced" or jobs.closing:
                jobs.finish(m, "replaced", "replaced by a new command")
                return
            if outcome.status == "STOPPED" or m.cancelled == "stopped":
                jobs.hold(m, outcome.ticks, outcome.reason)
                return
            failure = failure_facts(self.session, compiled.spec, failed_path, outcome)
            reason = failure.reason
            code = leaf_outcome(self.session, failed_path).get("code")
            if code == "watchdog":
                # this process froze and a daemon stopped the robot: it moves again only when told to
                jobs.hold(m, outcome.ticks, reason)
                if jobs.halted is m:
                    self._say(WATCHDOG_SENTENCE)
                return
            again = (failure.skill, reason) == previous
            if m.repairs >= self.options.max_repairs or failed_path is None or again:
                self._explain_failure(m, failure)  # a repair that met its own failure again would only repeat it
                return
            m.repairs += 1
            previous = (failure.skill, reason)
            compiled, index = self.replanner.repair(m, compiled, index, failed_path, code)
            if compiled is None:
                self._explain_failure(m, failure)
                return
            self.events.publish("mission", id=m.id, phase="repaired", failed=failed_path, reason=reason,
                                repairs=m.repairs, tasks=[compiled.tasks[p].call for p in compiled.top])
        if unplannable is not None:
            self._say(unplannable)
            jobs.finish(m, "failed", unplannable)
            return
        jobs.finish(m, "succeeded", None)

    def _explain_failure(self, m: Mission, failure: Failure) -> None:
        """Say what went wrong in words people use; the mission's reason keeps the technical
        sentence, and ``said`` and ``failure`` (the facts) are added next to it."""
        places = {name: spoken_name(marker.label) for name, marker in self.world.markers.items()}
        said = said_could_not(m.texts, m.done, failure, Words(places=places, held=self.world.held))
        m.said, m.failure = said, failure.to_dict()
        self._say(said)
        self.jobs.finish(m, "failed", could_not(m.texts, m.done, failure.reason))
