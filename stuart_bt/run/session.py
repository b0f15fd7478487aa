"""Run a loaded tree end to end: clock, event stream, blackboard, daemons, executor, report.

:class:`Session` wires the seams together in one place so that the CLI, tests and (later) the web
view and the ROS bridge start runs the same way::

    spec = load_tree("trees/lab_tour.yaml")
    with Session(spec, RunOptions(backend="dry", speed=20)) as session:
        outcome = session.run()
        report = session.report()
"""

from __future__ import annotations

import json
import math
import shutil
import signal
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

from ..core.blackboard import Blackboard
from ..core.catalogue import LEAVES
from ..core.clock import Clock, ScaledClock
from ..core.events import Event, EventStream, JsonlWriter
from ..core.world import Pose
from ..daemon.supervisor import DaemonStartError, Supervisor
from ..leaves import RunContext, make_leaf
from ..maps.markers import load_markers
from ..tree.builder import build
from ..tree.spec import TreeSpec
from .executor import Executor, RunOutcome
from .report import ReportBuilder, write_report
from .snapshot import tree_event_data

BACKENDS = ("dry", "sim", "unitree")


@dataclass
class RunOptions:
    backend: str = "dry"
    rate: float = 20.0
    # dry: clock seconds per wall second (default 1). sim: the world's pace cap (default 0: as
    # fast as the tree keeps up, in lockstep with the executor; 1.0 with the viewer).
    speed: float | None = None
    start: str | None = None  # marker the robot starts at; default 'entrance' when the map has it
    report: Path | None = None
    log: Path | None = None
    max_duration: float | None = None  # clock seconds
    daemon_options: dict[str, dict[str, Any]] = field(default_factory=dict)
    handshake_timeout: float = 20.0
    heartbeat_timeout: float = 1.0
    watchdog: float = 2.0  # wall s: a framework silent this long while motion runs leaves a stopped robot
    seed: int = 0  # sim: makes a run repeatable
    history: int | None = None  # events the report keeps (None: all; a long session keeps the last N)
    record: Path | None = None  # sim: chase-camera video (.mp4 or .gif)
    record_fps: float = 10.0
    viewer: bool = False  # sim: the interactive MuJoCo viewer
    map_out: Path | None = None  # sim: PNG of the map with the path driven


class Session:
    """One run of one tree. Use as a context manager: daemons always shut down."""

    def __init__(self, spec: TreeSpec, options: RunOptions | None = None, clock: Clock | None = None,
                 events: EventStream | None = None) -> None:
        self.spec = spec
        self.options = options or RunOptions()
        if self.options.backend not in BACKENDS:
            raise ValueError(f"unknown backend {self.options.backend!r}; choose one of {', '.join(BACKENDS)}")
        dry_speed = self.options.speed if self.options.speed else 1.0
        self.clock = clock or ScaledClock(dry_speed)  # the sim backend swaps in the world's clock
        self.events = events or EventStream(self.clock)
        self.recorder = ReportBuilder(self.events, self.options.history)
        self._trouble: str | None = None  # the first daemon that died, hung or babbled: keep the logs
        self.events.subscribe(self._note_trouble)
        self.blackboard = Blackboard(self.events, spec.blackboard)
        self.supervisor: Supervisor | None = None
        self.world: Any = None  # the simulator's WorldProcess (sim backend)
        self.executor: Executor | None = None
        self.outcome: RunOutcome | None = None
        self._hurry = False
        self.lost: str | None = None  # why the run cannot go on (its world died), once it cannot
        self.run_dir = Path(tempfile.mkdtemp(prefix="stuart_bt-run-"))  # daemon and world logs
        self._log_file: IO[str] | None = None
        self._log_writer: JsonlWriter | None = None

    # -- set-up -------------------------------------------------------------------------------------
    def start(self) -> Session:
        if self.options.log:
            Path(self.options.log).parent.mkdir(parents=True, exist_ok=True)
            self._log_file = open(self.options.log, "w", encoding="utf-8")  # noqa: SIM115 - the session's life
            self._log_writer = JsonlWriter(self.events, self._log_file)
        self.blackboard.publish_initial()  # the log and the views listen now: the table starts full
        world = self.blackboard.world
        if self.spec.markers_file:
            world.markers = load_markers(self.spec.markers_file)
        start = self.options.start or ("entrance" if "entrance" in world.markers else None)
        if start is not None:
            if start not in world.markers:
                raise ValueError(f"unknown start marker {start!r}")
            world.pose = world.markers[start].pose
            world.last_marker = start
        families = needed_families(self.spec)
        if self.options.backend == "sim":
            self._start_world(world.pose)
        if families:
            options = {f: dict(self.options.daemon_options.get(f, {})) for f in families}
            options.setdefault("loco", {}).setdefault("start_pose", world.pose.to_dict())
            if self.world is not None:
                for family_options in options.values():
                    family_options.setdefault("world", str(self.world.socket_path))
            self.supervisor = Supervisor(
                self.options.backend, self.clock, self.events, families=families, options=options,
                handshake_timeout=self.options.handshake_timeout, heartbeat_timeout=self.options.heartbeat_timeout,
                watchdog=self.options.watchdog, run_dir=self.run_dir,
                stalled=getattr(self.clock, "world_stalled", None),  # a frozen world is not a hung daemon
            )
            self._start_daemons()
        self.executor = self.executor_for(self.spec)
        if self.supervisor is not None and "loco" in self.supervisor.families:
            self.supervisor.client("loco").state_listeners.append(self._track_pose)
            self.events.subscribe(self._track_loco_replies)
        return self

    def executor_for(self, spec: TreeSpec) -> Executor:
        """An executor for ``spec`` on this session's clock, blackboard and daemons (the mission
        executor runs one tree after another on one session)."""
        ctx = RunContext(self.clock, self.events, self.blackboard, self.supervisor, Path(spec.file).parent)
        root = build(spec, lambda node: make_leaf(node, ctx), self.clock, self.blackboard)
        executor = Executor(root, self.clock, self.events, rate=self.options.rate)
        self.events.publish("tree", **tree_event_data(spec))  # views and the bridge learn the structure
        if self.world is not None:
            executor.pre_tick.append(lambda: self._check_world(executor))
            executor.while_waiting.append(lambda: self._check_world(executor))
        if self.supervisor is not None:
            executor.pre_tick.append(self.supervisor.poll)
            executor.while_waiting.append(self.supervisor.poll)  # keep-alives while the world is frozen
            executor.on_halt.append(self.stop_daemons)
        return executor

    def _start_world(self, start: Pose) -> None:
        """Launch the MuJoCo world server and make its sim time this run's clock (lockstep)."""
        from ..sim.world.client import launch_world

        speed = self.options.speed if self.options.speed is not None else (1.0 if self.options.viewer else 0.0)
        self._world_log = open(self.run_dir / "world.stderr.log", "wb")  # noqa: SIM115 - the world's life
        self.world = launch_world(seed=self.options.seed, speed=speed, stderr=self._world_log, hold=True,
                                  record=str(self.options.record) if self.options.record else None,
                                  record_fps=self.options.record_fps, viewer=self.options.viewer,
                                  start=(start.x, start.y, start.yaw))
        self.clock = self.world.clock(driver=True)
        self.events.clock = self.clock

    def _start_daemons(self) -> None:
        """Start the daemons; when the world server died meanwhile, that is the error to give (a
        daemon that lost its world mid-handshake only knows that its socket broke)."""
        assert self.supervisor is not None
        try:
            self.supervisor.start()
        except DaemonStartError:
            lost = self._world_death()
            if lost is None:
                raise
            self.lost = lost  # the logs are kept, and the user told where
            raise DaemonStartError(f"{lost} while the daemons were starting") from None

    def _world_death(self) -> str | None:
        """One sentence on how the world server died, or None while it runs (or without one)."""
        code = self.world.proc.poll() if self.world is not None else None
        if code is None:
            return None
        how = f"killed by {signal.Signals(-code).name}" if code < 0 else f"exit code {code}"
        return f"the simulator's world server (pid {self.world.pid}) died ({how})"

    def _note_trouble(self, event: Event) -> None:
        if self._trouble is None and event.kind == "daemon_state" and \
                event.data.get("state") in ("died", "hung", "faulty"):
            self._trouble = f"{event.data.get('family')} daemon {event.data.get('state')}"

    def _check_world(self, executor: Executor) -> None:
        """The world server is the run's physics and clock: when it dies the run cannot go on.
        Checked before every tick (a ``waitpid`` that does not block), so the tree stops on the
        next tick and every daemon is told to stop, with one sentence that says what happened."""
        if self.lost is None:
            self.lost = self._world_death()
            if self.lost is None:
                return
            self.events.publish("warning", message=f"{self.lost}; stopping the run")
        executor.request_stop(self.lost, status="ERROR")

    def __enter__(self) -> Session:
        try:
            return self.start()
        except BaseException:
            self.close()  # a daemon or the world that did start must not outlive a failed start
            raise

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- running ------------------------------------------------------------------------------------
    def run(self) -> RunOutcome:
        assert self.executor is not None, "call start() first"
        self.events.publish("run", phase="start", tree=self.spec.file, backend=self.options.backend,
                            rate=self.options.rate, speed=self.clock.factor)
        self.outcome = self.executor.run(self.options.max_duration)
        self._settle()
        self.events.publish("run", phase="end", status=self.outcome.status, reason=self.outcome.reason)
        if self.options.report:
            write_report(self.report(), self.options.report)
        return self.outcome

    def request_stop(self, reason: str = "stop requested") -> None:
        if self.executor is not None:
            self.executor.request_stop(reason)

    def request_before_tick(self, executor: Executor, family: str, cmd: str,
                            args: dict[str, Any] | None = None) -> None:
        """Send one command to a skill daemon before ``executor``'s next tick (held or not): the
        supervisor belongs to the tick thread, so another thread (a ROS callback, the web view) asks
        it this way, e.g. ``("pick", "confirm")`` for the pick confirmation gate."""
        supervisor = self.supervisor
        if supervisor is None or family not in supervisor.families:
            have = ", ".join(supervisor.families) if supervisor is not None else "none"
            raise ValueError(f"no {family!r} daemon; the daemons are {have}")
        sent: list[bool] = []

        def send() -> None:  # once; it stays in the list (removing it mid-iteration skips a hook)
            if not sent:
                sent.append(True)
                supervisor.client(family).request(cmd, args or {})

        executor.pre_tick.append(send)

    def hurry(self) -> None:
        """Shorten the waits of stopping and shutting down (a second Ctrl-C); daemons still get
        stop and are still reaped."""
        self._hurry = True

    def report(self) -> dict[str, Any]:
        outcome = self.outcome
        return self.recorder.build(
            status=outcome.status if outcome else "NOT_RUN",
            reason=outcome.reason if outcome else None,
            tree=self.spec.file,
            backend=self.options.backend,
            ticks=outcome.ticks if outcome else 0,
            final_pose=self.blackboard.world.pose.to_dict(),
            held=self.blackboard.world.held,
        )

    def close(self) -> None:
        if self.supervisor is not None:
            self.supervisor.shutdown(timeout=0.3 if self._hurry else 2.0)
        if self.world is not None:
            if self.options.map_out and self.outcome is not None:
                self._draw_map(self.options.map_out)
            self.world.close()
            self._world_log.close()
        if self._trouble is None and self.lost is None:
            shutil.rmtree(self.run_dir, ignore_errors=True)
        else:  # a daemon or the world failed: its log says why, so it is kept, and the user told where
            print(f"stuart-bt: daemon and world logs kept in {self.run_dir} ({self.lost or self._trouble})",
                  file=sys.stderr)
        if self._log_writer is not None:
            self._log_writer.close()
        if self._log_file is not None:
            self._log_file.close()
        self.recorder.close()

    # -- hooks --------------------------------------------------------------------------------------
    def _track_pose(self, state: dict[str, Any]) -> None:
        """Heartbeat state from the loco daemon: the robot's pose right now."""
        if isinstance(state.get("pose"), dict):
            self._set_pose(state["pose"])

    def _track_loco_replies(self, event: Event) -> None:
        """Progress, results and stop/cancel replies of the loco daemon carry the latest pose."""
        if event.kind != "daemon" or event.data.get("family") != "loco":
            return
        for key in ("data", "result"):
            body = event.data.get(key)
            if isinstance(body, dict) and isinstance(body.get("pose"), dict):
                self._set_pose(body["pose"])

    def _set_pose(self, pose: dict[str, Any]) -> None:
        new = Pose.from_dict(pose)  # finite numbers: the protocol's schema check refused anything else
        world = self.blackboard.world
        moved = world.pose.distance_to(new) > 0.01 or abs(math.remainder(new.yaw - world.pose.yaw, math.tau)) > 0.01
        world.pose = new
        if self.supervisor is not None:  # a restarted loco daemon starts where the robot is
            self.supervisor.options.setdefault("loco", {})["start_pose"] = new.to_dict()
        if moved:
            self.events.publish("pose", **new.to_dict())

    def _draw_map(self, out: Path) -> None:
        """The lab map with the markers, the path the robot drove and the known objects."""
        from ..maps.picture import draw_map_png
        from ..sim.world.occupancy import scene_grid

        path = [(e.data["x"], e.data["y"]) for e in self.recorder.events if e.kind == "pose"]
        markers = self.blackboard.world.markers
        objects = {k: {"x": o.x, "y": o.y} for k, o in self.blackboard.world.objects.items()}
        memories = [e.data.get("objects", []) for e in self.recorder.events if e.kind == "memory"]
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        draw_map_png(scene_grid(), markers, path, objects, out, memory=memories[-1] if memories else ())

    def _settle(self, timeout: float = 1.0) -> None:
        """After the run: wait (wall time) for replies still owed, e.g. to cancels, so the report
        and the world state end with what the daemons last did."""
        if self.supervisor is None:
            return
        for family in self.supervisor.families:
            for request in self.supervisor.client(family).in_flight:
                if request.cmd in ("cancel", "stop"):
                    self.supervisor.wait(request, timeout=timeout)

    def stop_daemons(self) -> None:
        """Halt path: every daemon receives stop; wait briefly so the acknowledgements are logged."""
        assert self.supervisor is not None
        for request in self.supervisor.stop_all():
            self.supervisor.wait(request, timeout=0.1 if self._hurry else 1.0)


def needed_families(spec: TreeSpec) -> list[str]:
    """Daemon families the tree's leaves use (``stop`` reaches every family that runs)."""
    families = {LEAVES[n.kind].family for n in spec.walk() if n.kind in LEAVES}
    families.discard(None)
    return sorted(families)  # type: ignore[arg-type]


def load_report(path: str | Path) -> dict[str, Any]:
    return json.loads(Path(path).read_text(encoding="utf-8"))
