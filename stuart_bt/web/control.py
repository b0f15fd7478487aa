"""What the buttons do: the web view's commands, through the public run and mission APIs only.

Two kinds of robot sit behind the page. :class:`TreeControl` runs one tree file on a
:class:`~stuart_bt.run.session.Session` (the same daemons for the whole serve): run, stop, continue,
and small trees of its own for "walk here", "go to marker" and "play this gesture"; what is typed
in the console (or said with push-to-talk) while the tree runs goes to a
:class:`~stuart_bt.mission.tour_talk.TourTalk` for that run (a question is answered at the next
pause in speech, "stop" holds the tree, "continue" lets it go on).
:class:`MissionControl` wraps a :class:`~stuart_bt.mission.executor.MissionExecutor`: what is
typed in the console is submitted as an utterance; stop and continue are said, as a person would.

Neither looks into an executor's tree: what happened is learnt from the event stream (the web
hub subscribes to it), and a run is stopped with ``Executor.request_stop``.
"""

from __future__ import annotations

import itertools
import queue
import threading
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from ..core.errors import StuartError
from ..core.events import Event, EventStream
from ..core.world import Marker
from ..language import Parser, Resolver
from ..mission.running import failed_leaf, failure_reason
from ..mission.tour_talk import TourTalk
from ..run.session import RunOptions, Session
from ..tree.spec import Location, NodeSpec, TreeSpec

WAKE = "Hey Stuart"
IDLE_STEP = 0.05  # sim seconds the idle world advances per step (so the arms follow the sliders)
TALK_START_WAIT_S = 30.0  # wall seconds an utterance waits for a reserved run's tree to be built


class ControlError(StuartError):
    """A command that cannot be done now (busy, not on this backend); the message says why."""


_job_ids = itertools.count(1)


@dataclass
class Job:
    spec: TreeSpec
    label: str
    main: bool = False  # the served tree (its top-level progress is what "continue" resumes)
    id: int = field(default_factory=lambda: next(_job_ids))  # on its run events: the page follows it


class TreeControl:
    """Runs the served tree and the page's small trees one at a time on one session."""

    mode = "tree"

    def __init__(self, spec: TreeSpec, options: RunOptions, autostart: bool = True, require_wake: bool = True) -> None:
        self.spec = spec
        self.session = Session(spec, options)
        self.autostart = autostart
        self._jobs: queue.Queue[Job | None] = queue.Queue()
        self._lock = threading.Lock()
        # told when a run's talk comes or goes: an utterance said as a run starts waits for it
        self._talk_changed = threading.Condition(self._lock)
        self._executor: Any = None
        self._current: Job | None = None
        self._finished_steps: set[str] = set()  # top-level children of the root that succeeded
        self._stopped_main = False
        self._worker: threading.Thread | None = None
        self._closing = threading.Event()
        self._world_client: Any = None
        self._talk: TourTalk | None = None  # the served tree's, while it runs
        self._parser = Parser(require_wake=require_wake)
        self._resolver = Resolver.from_files(spec.markers_file)
        self._ears: Any = None  # BrowserEars, made on the first push-to-talk (it loads hearing)

    @property
    def events(self) -> EventStream:
        return self.session.events

    # -- life cycle ---------------------------------------------------------------------------------
    def start(self) -> TreeControl:
        self.session.start()
        self.events.subscribe(self._track_steps)
        self._worker = threading.Thread(target=self._work, name="web-runs", daemon=True)
        self._worker.start()
        if self.autostart:
            self.run()
        return self

    def close(self) -> None:
        self._closing.set()
        with self._lock:
            if self._executor is not None:
                self._executor.request_stop("shutting down")
        self._jobs.put(None)
        if self._worker is not None:
            self._worker.join(timeout=30)
        if self._world_client is not None:
            self._world_client.close()
        self.session.close()

    # -- commands -----------------------------------------------------------------------------------
    def state(self) -> dict[str, Any]:
        """``held``: why the running tree is held (a stop said, a question being answered), else None."""
        with self._lock:
            job, executor, talk = self._current, self._executor, self._talk
        said_stop = talk is not None and talk.stopped_by_user
        return {"mode": self.mode, "busy": job is not None, "running": job.label if job else None,
                "held": executor.hold_reason if executor is not None else None,
                "can_continue": (self._stopped_main and job is None) or said_stop}

    def run(self) -> None:
        """The served tree from its start."""
        self._finished_steps.clear()
        self._submit(Job(self.spec, "run", main=True))

    def stop(self) -> None:
        with self._lock:
            if self._executor is None:
                raise ControlError("nothing is running")
            self._executor.request_stop("stopped from the web view")

    def resume(self) -> None:
        """Continue the served tree: held by a "stop" said, it goes on (as "continue" said would);
        stopped, its top-level steps that already succeeded are skipped (for a sequence root) and
        the step that was stopped starts again."""
        with self._lock:
            talk = self._talk
        if talk is not None and talk.stopped_by_user:
            talk.submit(f"{WAKE}, continue", source="web")
            return
        if not self._stopped_main:
            raise ControlError("nothing to continue: the tree was not stopped")
        root = self.spec.root
        rest = [c for c in root.children if c.path not in self._finished_steps] if root.kind == "sequence" else None
        if rest == []:
            raise ControlError("nothing left to continue: every step of the tree succeeded")
        spec = self.spec if rest is None else replace(self.spec, root=replace(root, children=rest))
        self._submit(Job(spec, "continue", main=True))

    def say(self, text: str) -> dict[str, Any]:
        """An utterance to the running tree; what it was understood as."""
        command = self._talking().submit(text, source="web")
        return {"kind": command.kind, "intents": [i.to_dict() for i in command.intents]}

    def hear(self, samples: Any, ended_at: float) -> dict[str, Any]:
        """One utterance from the console's push-to-talk (16 kHz mono int16), heard and said to
        the running tree."""
        talk = self._talking()
        with self._lock:
            if self._ears is None:
                from .ears import BrowserEars

                self._ears = BrowserEars()
            ears = self._ears
        return ears.hear(talk, samples, ended_at)

    def _talking(self) -> TourTalk:
        """The running tree's talk. Run reserves the tree at once (the page says busy) and builds it
        on the worker: what is said in between waits for it instead of being refused."""
        deadline = time.monotonic() + TALK_START_WAIT_S
        with self._talk_changed:
            while self._talk is None and self._current is not None and self._current.main and (
                    not self._closing.is_set()) and (left := deadline - time.monotonic()) > 0:
                self._talk_changed.wait(left)
            talk = self._talk
        if talk is None:
            raise ControlError("nothing is running to talk to: Run starts the tree, and what is said then goes to "
                               "it (stuart-bt serve --mission takes commands)")
        return talk

    def walk(self, x: float, y: float, yaw: float | None) -> dict[str, Any]:
        """Walk to a map pose; ``{"run": id}``: the ``run`` events with that id say how it ends."""
        self._need("loco", "walk")
        params: dict[str, Any] = {"x": x, "y": y} | ({"yaw": yaw} if yaw is not None else {})
        return {"run": self._submit(Job(_one_leaf("navigate", "walk", params), f"walk to ({x:.2f}, {y:.2f})"))}

    def go_to(self, marker: str) -> dict[str, Any]:
        """Walk to a marker; ``{"run": id}`` as for :meth:`walk`."""
        self._need("loco", "walk")
        if marker not in self.session.blackboard.world.markers:
            raise ControlError(f"unknown marker {marker!r}")
        return {"run": self._submit(Job(_one_leaf("navigate", "go_to", {"marker": marker}), f"go to {marker}"))}

    def play_gesture(self, path: Path) -> None:
        self._need("gesture", "play gestures")
        self._submit(Job(_one_leaf("gesture", "play", {"file": str(path.resolve())}), f"play {path.stem}"))

    def set_markers(self, markers: dict[str, Marker]) -> None:
        """The marker file changed: leaves that walk to a marker by name see the new ones (the
        world state is the documented place markers live during a run)."""
        self.session.blackboard.world.markers = dict(markers)

    def world_call(self, cmd: str, **args: Any) -> dict[str, Any]:
        """A request to the simulator's world server (sim backend only)."""
        world = self.session.world
        if world is None:
            raise ControlError("the pose is applied live only with --backend sim")
        if self._world_client is None:
            from ..sim.world.client import WorldClient

            self._world_client = WorldClient(world.socket_path, timeout=10.0)
        return self._world_client.call(cmd, **args)

    # -- the worker ---------------------------------------------------------------------------------
    def _need(self, family: str, what: str) -> None:
        supervisor = self.session.supervisor
        if supervisor is None or family not in supervisor.families:
            raise ControlError(f"cannot {what}: this tree starts no {family} daemon")

    def _submit(self, job: Job) -> int:
        with self._lock:
            if self._current is not None:
                raise ControlError(f"busy ({self._current.label}); stop it first")
            self._current = job  # reserved now, so a second click is refused at once
        self._jobs.put(job)
        return job.id

    def _work(self) -> None:
        while not self._closing.is_set():
            try:
                job = self._jobs.get(timeout=IDLE_STEP)
            except queue.Empty:
                self._idle()
                continue
            if job is None:
                return
            try:
                self._run(job)
            except Exception as e:  # noqa: BLE001 - a bug in one run must not take the page down
                self.events.publish("warning", message=f"web run {job.label}: {type(e).__name__}: {e}")
            finally:
                with self._talk_changed:
                    self._current = None
                    self._executor = None
                    self._talk_changed.notify_all()

    def _run(self, job: Job) -> None:
        executor = self.session.executor_for(job.spec)
        talk = TourTalk(self.session, executor, self._parser, self._resolver) if job.main else None
        with self._talk_changed:
            self._executor, self._talk = executor, talk
            self._talk_changed.notify_all()
            if self._closing.is_set():
                executor.request_stop("shutting down")
        if job.main:
            self._stopped_main = False
        self.events.publish("run", phase="start", id=job.id, tree=job.spec.file, label=job.label,
                            backend=self.session.options.backend)
        try:
            outcome = executor.run(self.session.options.max_duration)
        finally:
            with self._lock:
                self._talk = None
            if talk is not None:
                talk.close()
        reason = outcome.reason
        if outcome.status == "FAILURE":  # why: the reason of the leaf whose failure failed the tree
            reason = failure_reason(self.session, failed_leaf(executor.root), outcome)
        self.events.publish("run", phase="end", id=job.id, label=job.label, status=outcome.status, reason=reason)
        if job.main and outcome.status == "STOPPED":
            self._stopped_main = True

    def _idle(self) -> None:
        """Between runs: keep reading the daemons, and let the simulated world run on (it steps
        only when its clock driver, this session, allows it) so the arms follow the sliders."""
        if self.session.supervisor is not None:
            self.session.supervisor.poll()
        if self.session.world is not None:
            clock = self.session.clock
            clock.sleep_until(clock.now() + IDLE_STEP)

    def _track_steps(self, event: Event) -> None:
        root = self.spec.root
        path = event.path
        succeeded = event.kind == "status" and event.data.get("new") == "SUCCESS"
        if path and succeeded and any(path == c.path for c in root.children):
            self._finished_steps.add(path)


class MissionControl:
    """The console's robot: utterances in, missions out (stop and continue are said)."""

    mode = "mission"

    def __init__(self, options: Any) -> None:
        from ..mission.executor import MissionExecutor
        from .ears import BrowserEars

        self.robot = MissionExecutor(options)
        self.markers_file = self.robot.markers_file
        self.ears = BrowserEars()

    @property
    def events(self) -> EventStream:
        return self.robot.events

    @property
    def session(self) -> Session:
        return self.robot.session

    def start(self) -> MissionControl:
        self.robot.start()
        return self

    def close(self) -> None:
        self.robot.close()

    def state(self) -> dict[str, Any]:
        return {"mode": self.mode, "busy": self.robot.busy, "running": None, "held": None,
                "can_continue": self.robot.halted is not None}

    def say(self, text: str) -> dict[str, Any]:
        command = self.robot.submit(text, source="web")
        return {"kind": command.kind, "intents": [i.to_dict() for i in command.intents]}

    def hear(self, samples: Any, ended_at: float) -> dict[str, Any]:
        """One utterance from the console's push-to-talk (16 kHz mono int16), heard and submitted."""
        return self.ears.hear(self.robot, samples, ended_at)

    def run(self) -> None:
        raise ControlError("a mission server runs what is said; type it in the console")

    def stop(self) -> None:
        self.robot.submit(f"{WAKE}, stop", source="web")

    def resume(self) -> None:
        self.robot.submit(f"{WAKE}, continue", source="web")

    def go_to(self, marker: str) -> dict[str, Any]:
        """Say "go to the MARKER"; ``{"mission": id}``: the ``mission`` events with that id say
        how it ends. Refused with what the robot answered when it queued no mission for it."""
        if marker not in self.robot.world.markers:
            raise ControlError(f"unknown marker {marker!r}")
        command = self.robot.submit(f"{WAKE}, go to the {marker.replace('_', ' ')}", source="web")
        if command.mission is None:
            raise ControlError(command.refused or f"the robot did not take it as somewhere to go ({command.kind})")
        return {"mission": command.mission}

    def walk(self, x: float, y: float, yaw: float | None) -> None:
        raise ControlError("walking to a point needs a tree server (stuart-bt serve TREE); say where to go instead")

    def play_gesture(self, path: Path) -> None:
        raise ControlError("playing a recorded gesture needs a tree server (stuart-bt serve TREE)")

    def set_markers(self, markers: dict[str, Marker]) -> None:
        self.robot.session.blackboard.world.markers = dict(markers)

    def world_call(self, cmd: str, **args: Any) -> dict[str, Any]:
        raise ControlError("the pose is applied live only in a tree server with --backend sim")


def _one_leaf(kind: str, name: str, params: dict[str, Any]) -> TreeSpec:
    """A tree of one leaf (the page's own small jobs), named so the timeline shows what it was."""
    where = Location("<web>", 1, 1)
    return TreeSpec(NodeSpec(kind, name, name, where, params), f"<web:{name}>")
