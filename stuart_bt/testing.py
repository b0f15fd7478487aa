"""Run trees in tests and assert on what the robot did.

::

    from stuart_bt.testing import run_tree

    def test_greeting_waves_while_speaking():
        result = run_tree("trees/greet.yaml")
        result.assert_success()
        result.assert_said("I'm Stuart")
        result.assert_gestured("high wave")

``run_tree`` starts the daemons of the chosen backend (``dry`` by default, sped up; ``sim``
launches the MuJoCo world in lockstep with the tree), runs the tree to the end, always shuts
everything down, and returns a :class:`RunResult`: the report plus, on the sim, the world's own
state before, during (sampled every tick) and after the run. Assertions about what the report
says work on every backend; assertions about the world (objects, collisions, arm joints) judge
by the physics, not by the report's word, and need the sim. The assertion helpers hide their
own frames from pytest tracebacks (``__tracebackhide__``), so a failure points at the test.

Hooks act on the world mid-run. They get a :class:`LiveRun`; :func:`at` and :func:`when` make
one-shot hooks that read like a script::

    result = run_tree(text=WALK, backend="sim", on_tick=[
        at(3.0, lambda run: run.world.person_at(2.0, 0.5)),
        at(6.0, lambda run: run.world.person_leaves()),
    ])

The pytest plugin (:mod:`stuart_bt.pytest_plugin`) wraps this in the ``stuart_sim`` and
``stuart_dry`` fixtures; docs/testing.md is the guide.

PYTEST_DONT_REWRITE: the assertion messages here are written for people; keep them as written.
"""

from __future__ import annotations

import math
import os
import shutil
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from .run.executor import RunOutcome
from .run.session import RunOptions, Session
from .tree.loader import load_tree, load_tree_text
from .tree.spec import TreeSpec

DRY_SPEED = 50.0  # dry runs: clock seconds per wall second unless told otherwise
DEGREE = math.pi / 180.0
ARM_JOINT_WORDS = ("shoulder", "elbow", "wrist", "_hand_")

Hook = Callable[["LiveRun"], Any]


VOICES = ("en-us", "en-gb+m3", "en-us+f2", "en-gb-x-rp", "en-us+m3", "en-gb+f3")  # espeak-ng voices, varied


def speak(text: str, path: str | Path, voice: str = "en-us", speed: int = 160) -> Path:
    """``text`` spoken by espeak-ng into the WAV ``path``: real audio for testing what the robot
    hears (``stuart-bt hear``, ``listen``), made at test time instead of kept as recordings.
    ``voice`` is an espeak-ng voice (:data:`VOICES` are a varied set), ``speed`` words per minute."""
    import shutil
    import subprocess

    espeak = shutil.which("espeak-ng")
    if espeak is None:
        raise FileNotFoundError("espeak-ng is not installed (apt-get install espeak-ng; make test installs it)")
    subprocess.run([espeak, "-v", voice, "-s", str(speed), "-w", str(path), text], check=True, timeout=30,
                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return Path(path)


def lab_markers() -> Path:
    """The lab's marker map shipped with the package."""
    return Path(str(resources.files("stuart_bt.sim") / "maps" / "lab_markers.json"))


def is_arm_joint(name: str) -> bool:
    """Arm and hand joints (not legs, not the waist): what gestures and picks move."""
    return any(word in name for word in ARM_JOINT_WORDS)


# --- acting on a running tree ------------------------------------------------------------------


class WorldControl:
    """The simulated world seen from a test: named helpers for what tests do to it, and
    ``call`` for any world command (docs/sim.md lists them)."""

    def __init__(self, process: Any, live: LiveRun) -> None:
        self.process = process  # the WorldProcess
        self._live = live

    @property
    def pid(self) -> int:
        return int(self.process.pid)

    @property
    def socket_path(self) -> Path:
        return Path(self.process.socket_path)

    def call(self, cmd: str, **args: Any) -> dict[str, Any]:
        return self.process.call(cmd, **args)

    def state(self) -> dict[str, Any]:
        """A fresh ``state`` from the world (costs a round trip; see :attr:`latest`)."""
        return self.call("state")

    @property
    def latest(self) -> dict[str, Any]:
        """The latest watched sample (this tick's, with the default ``watch``): free, unlike
        :meth:`state`; a fresh state when the run is not watched."""
        return self._live.timeline[-1] if self._live.timeline else self.state()

    def person_at(self, x: float, y: float) -> dict[str, Any]:
        """Put the simulated person standing at (x, y) in the map frame."""
        return self.call("person", x=x, y=y)

    def person_leaves(self) -> dict[str, Any]:
        return self.call("person", present=False)

    def move_object(self, label: str, x: float, y: float, z: float, yaw: float | None = None) -> dict[str, Any]:
        """Teleport an object (a hand holding it lets go first); ``yaw`` also stands it upright."""
        args: dict[str, Any] = {"label": label, "x": x, "y": y, "z": z}
        if yaw is not None:
            args["yaw"] = yaw
        return self.call("set_object", **args)

    def robot_pose(self) -> dict[str, float]:
        return dict(self.latest["base"])

    def object(self, label: str) -> dict[str, float]:
        return dict(self.latest["objects"][label])


class LiveRun:
    """What an ``on_tick`` hook receives, once per tick before the tree ticks.

    Anything not defined here is the :class:`Session`'s (``run.supervisor``, ``run.clock``,
    ``run.request_stop``), so hooks written against a Session keep working.
    """

    def __init__(self, session: Session, watch_every: int = 1) -> None:
        self.session = session
        self.tick = 0
        self.timeline: list[dict[str, Any]] = []
        self._watch_every = watch_every
        self._world: WorldControl | None = None

    def __getattr__(self, name: str) -> Any:
        return getattr(self.session, name)

    @property
    def t(self) -> float:
        """Clock seconds, the same time base as the report's ``t``, ``start`` and ``end``."""
        return self.session.clock.now()

    @property
    def world(self) -> WorldControl:
        if self.session.world is None:
            raise RuntimeError(f"the {self.session.options.backend} backend has no simulated world; "
                               "run on the sim backend (stuart_sim, or backend='sim')")
        if self._world is None:
            self._world = WorldControl(self.session.world, self)
        return self._world

    @property
    def has_world(self) -> bool:
        return self.session.world is not None

    def daemon(self, family: str) -> Any:
        """The client of one skill daemon: ``run.daemon("pick").request("confirm", {})``."""
        if self.session.supervisor is None:
            raise RuntimeError("this tree starts no daemons")
        return self.session.supervisor.client(family)

    def stop(self, reason: str = "stop requested by the test") -> None:
        """Like the operator's stop: the tree halts at the start of the next tick."""
        self.session.request_stop(reason)

    def sample(self) -> dict[str, Any] | None:
        """Record the world's state now (the timeline the world assertions read)."""
        if self.session.world is None or self._watch_every <= 0:
            return None
        state = self.session.world.call("state")
        self.timeline.append(state)
        return state


@dataclass
class Trigger:
    """A hook that runs its actions once: when ``condition`` has held for ``held_for`` clock
    seconds. ``fired_at`` says when (None: never), for assertions after the run."""

    condition: Callable[[LiveRun], bool]
    actions: tuple[Hook, ...]
    held_for: float = 0.0
    fired_at: float | None = None
    _since: float | None = None

    @property
    def fired(self) -> bool:
        return self.fired_at is not None

    def __call__(self, run: LiveRun) -> None:
        if self.fired_at is not None:
            return
        if not self.condition(run):
            self._since = None
            return
        if self._since is None:
            self._since = run.t
        if run.t - self._since < self.held_for:
            return
        self.fired_at = run.t
        for action in self.actions:
            action(run)


def at(t: float, *actions: Hook) -> Trigger:
    """Run ``actions`` once, at the first tick at or after clock time ``t``."""
    return Trigger(lambda run: run.t >= t, actions)


def when(condition: Callable[[LiveRun], bool], *actions: Hook, held_for: float = 0.0) -> Trigger:
    """Run ``actions`` once, when ``condition(run)`` is true (for ``held_for`` seconds)."""
    return Trigger(condition, actions, held_for)


# --- the result ----------------------------------------------------------------------------------


@dataclass
class RunResult:
    outcome: RunOutcome
    report: dict[str, Any]
    world: dict[str, Any] = field(default_factory=dict)  # the tree's belief (blackboard world state)
    # sim only: the world's own ``state`` before the first tick, every watched tick, and at the end
    initial_world: dict[str, Any] | None = None
    final_world: dict[str, Any] | None = None
    timeline: list[dict[str, Any]] = field(default_factory=list)

    @property
    def status(self) -> str:
        return self.outcome.status

    def __repr__(self) -> str:  # short: pytest prints it in tracebacks
        r = self.report
        return (f"RunResult({self.status}, {r.get('backend')}, {r.get('tree')}, {r.get('duration')} s, "
                f"visited={r.get('visited')}, failures={len(r.get('failures', []))}, samples={len(self.timeline)})")

    def failure(self, path: str) -> str | None:
        """Why the leaf at ``path`` last failed (conditions included), or None if it never did."""
        reasons = [e.get("reason") for e in self.events("leaf") if e["path"] == path and e["outcome"] == "FAILURE"]
        return reasons[-1] if reasons else None

    def events(self, kind: str) -> list[dict[str, Any]]:
        return [e for e in self.report["events"] if e["kind"] == kind]

    def commands(self, cmd: str) -> list[dict[str, Any]]:
        """Commands sent to the daemons (``cmd`` e.g. "pick"), in order, with their clock ``t``."""
        return [e for e in self.events("command") if e.get("cmd") == cmd]

    def leaf_results(self, skill: str) -> list[dict[str, Any]]:
        """Successful leaves of one skill, in order: ``{"path", "t", "result"}``."""
        return [{"path": e["path"], "t": e["t"], "result": e.get("result") or {}}
                for e in self.events("leaf") if e.get("skill") == skill and e["outcome"] == "SUCCESS"]

    def arrivals(self) -> list[dict[str, Any]]:
        """Every finished walk or turn: ``{"path", "t", "marker", "pose", "error"}``; ``error`` is
        the sim's measured arrival error (``position`` m, ``yaw`` rad, ``within_tolerance``)."""
        out = []
        for skill in ("navigate", "turn"):
            for leaf in self.leaf_results(skill):
                r = leaf["result"]
                out.append({"path": leaf["path"], "t": leaf["t"], "marker": r.get("marker"),
                            "pose": r.get("pose"), "error": r.get("error")})
        return sorted(out, key=lambda a: a["t"])

    def utterances(self) -> list[dict[str, Any]]:
        """Spoken lines with what the tts daemon said about them (``duration``, ``wav``)."""
        results = {e["path"]: e for e in self.leaf_results("speak")}
        out = []
        for s in self.report["spoken"]:
            r = results.get(s["path"], {}).get("result", {})
            out.append({**s, "duration": r.get("duration"), "wav": r.get("wav")})
        return out

    # -- the world (sim) ----------------------------------------------------------------------------
    def _need_world(self, what: str) -> dict[str, Any]:
        __tracebackhide__ = True
        assert self.final_world is not None, (
            f"{what} needs the simulated world's state; this run used the {self.report.get('backend')} "
            "backend (use stuart_sim or run_tree(..., backend='sim'))")
        return self.final_world

    def _first_world(self, what: str) -> dict[str, Any]:
        """The world at the start of the run (or the first watched tick)."""
        self._need_world(what)
        return self.initial_world or self.timeline[0]

    def _need_timeline(self, what: str) -> list[dict[str, Any]]:
        __tracebackhide__ = True
        self._need_world(what)
        assert self.timeline, f"{what} needs the world watched during the run (watch=False was given)"
        return self.timeline

    @property
    def objects(self) -> dict[str, dict[str, float]]:
        """Where every object ended up (the world's final state)."""
        return self._need_world("objects")["objects"]

    def object_position(self, label: str) -> dict[str, float]:
        objects = self.objects
        assert label in objects, f"no object {label!r} in the world; objects: {sorted(objects)}"
        return objects[label]

    def samples(self, since: float | None = None, until: float | None = None) -> list[dict[str, Any]]:
        """World states sampled with ``since <= t <= until`` (clock seconds)."""
        return [s for s in self.timeline
                if (since is None or s["t"] >= since) and (until is None or s["t"] <= until)]

    def state_at(self, t: float) -> dict[str, Any]:
        """The last world state sampled at or before clock time ``t``."""
        before = [s for s in self._need_timeline("state_at") if s["t"] <= t]
        assert before, f"no world state sampled by t={t:g} (first sample at t={self.timeline[0]['t']:g})"
        return before[-1]

    # -- assertions: the run ------------------------------------------------------------------------
    def assert_success(self) -> None:
        __tracebackhide__ = True
        failures = "; ".join(f"{f['path']}: {f['reason']}" for f in self.report["failures"])
        assert self.status == "SUCCESS", f"run ended {self.status}: {failures or self.outcome.reason}"

    def assert_no_failures(self) -> None:
        __tracebackhide__ = True
        listed = "\n".join(f"  t={f['t']:.2f} {f['path']} ({f['skill']}): {f['reason']}"
                           for f in self.report["failures"])
        assert not self.report["failures"], f"{len(self.report['failures'])} leaf failure(s):\n{listed}"

    def assert_failed(self, path: str, code: str | None = None) -> str:
        """The leaf at ``path`` (or ending in ``/path``) failed, with reason ``code: ...`` when
        given; returns the reason."""
        __tracebackhide__ = True
        matching = [f for f in self.report["failures"] if f["path"] == path or f["path"].endswith("/" + path)]
        every = [f"{f['path']}: {f['reason']}" for f in self.report["failures"]] or ["none"]
        assert matching, f"leaf {path!r} never failed; failures: {every}"
        reason = str(matching[-1]["reason"])
        if code is not None:
            assert reason.split(":", 1)[0] == code, f"leaf {path!r} failed with {reason!r}, expected {code!r}"
        return reason

    def assert_visited(self, *markers: str, exactly: bool = False) -> None:
        """These markers were reached in this order (others may come between unless ``exactly``)."""
        __tracebackhide__ = True
        visited = self.report["visited"]
        if exactly:
            assert visited == list(markers), f"visited {visited}, expected exactly {list(markers)}"
            return
        remaining = iter(visited)
        missing = [m for m in markers if m not in remaining]
        assert not missing, f"visited {visited}, expected in order {list(markers)} (first out of order: {missing[0]!r})"

    def assert_said(self, fragment: str) -> None:
        __tracebackhide__ = True
        texts = [s["text"] for s in self.report["spoken"]]
        assert any(fragment in t for t in texts), f"nothing said contains {fragment!r}; said {texts}"

    def assert_gestured(self, name: str) -> None:
        __tracebackhide__ = True
        played = [g["name"] for g in self.report["gestures"]]
        flat = [n for p in played for n in (p if isinstance(p, list) else [p])]
        assert name in flat, f"gesture {name!r} not played; played {flat}"

    def assert_holding(self, label: str | None) -> None:
        """What the tree believes it holds and, on the sim, what a hand really holds."""
        __tracebackhide__ = True
        believed = self.report.get("held")
        assert believed == label, f"the tree believes it holds {believed!r}, expected {label!r}"
        if self.final_world is not None:
            held = [v for v in self.final_world["held"].values() if v]
            actual = held[0] if held else None
            assert actual == label, f"the world's hands hold {self.final_world['held']}, expected {label!r}"

    def assert_final_pose(self, x: float, y: float, yaw: float | None = None,
                          tolerance: float = 0.10, yaw_tolerance: float = 5 * DEGREE) -> None:
        __tracebackhide__ = True
        pose = self.report["final_pose"]
        distance = math.hypot(pose["x"] - x, pose["y"] - y)
        assert distance <= tolerance, f"final pose {pose} is {distance:.3f} m from ({x}, {y}) (tolerance {tolerance} m)"
        if yaw is not None:
            error = abs(math.remainder(pose["yaw"] - yaw, math.tau))
            assert error <= yaw_tolerance, (f"final yaw {pose['yaw']:.3f} is {error / DEGREE:.1f}° from {yaw:.3f} "
                                            f"(tolerance {yaw_tolerance / DEGREE:.1f}°)")

    def assert_arrivals_within(self, tolerance: float = 0.10, yaw_tolerance: float = 5 * DEGREE) -> None:
        """Every walk and turn ended within tolerance, by the sim's measured arrival error."""
        __tracebackhide__ = True
        arrivals = self.arrivals()
        measured = [a for a in arrivals if isinstance(a["error"], dict)]
        assert measured, (f"no arrival carries a measured error ({len(arrivals)} arrivals); the sim's navigate "
                          "results do, the dry backend's do not")
        bad = []
        for a in measured:
            e = a["error"]
            yaw = abs(e["yaw"]) if e.get("yaw") is not None else 0.0
            if e["position"] > tolerance or yaw > yaw_tolerance or not e.get("within_tolerance", True):
                bad.append(f"  {a['path']} ({a['marker'] or 'no marker'}) at t={a['t']:.2f}: {e['position']:.3f} m, "
                           f"{yaw / DEGREE:.1f}° off, within_tolerance={e.get('within_tolerance')}")
        assert not bad, (f"{len(bad)} of {len(measured)} arrivals outside {tolerance} m / "
                         f"{yaw_tolerance / DEGREE:.1f}°:\n" + "\n".join(bad))

    def assert_speech_overlaps_gestures(self, *prefixes: str) -> None:
        """Under each subtree path prefix, the speech and the gestures played at the same time."""
        __tracebackhide__ = True
        assert prefixes, "name the subtrees, e.g. assert_speech_overlaps_gestures('tour/station_1/')"
        problems = []
        for prefix in prefixes:
            speech = [s for s in self.report["spoken"] if s["path"].startswith(prefix)]
            moves = [g for g in self.report["gestures"] if g["path"].startswith(prefix)]
            if not speech or not moves:
                problems.append(f"  {prefix}: {len(speech)} utterance(s), {len(moves)} gesture(s) finished")
                continue
            for s in speech:
                if not any(s["start"] < g["end"] and g["start"] < s["end"] for g in moves):
                    spans = ", ".join(f"{g['name']} {g['start']:.2f}..{g['end']:.2f}" for g in moves)
                    problems.append(
                        f"  {prefix}: speech {s['start']:.2f}..{s['end']:.2f} overlaps no gesture ({spans})")
        assert not problems, "speech did not overlap gestures:\n" + "\n".join(problems)

    # -- assertions: the world (sim) ----------------------------------------------------------------
    def assert_no_collisions(self) -> None:
        """The base footprint never touched a wall or furniture in any watched tick."""
        __tracebackhide__ = True
        for s in self._need_timeline("assert_no_collisions"):
            if s.get("collision") or s.get("collided"):
                b = s["base"]
                raise AssertionError(f"the base collided by t={s['t']:.2f} at ({b['x']:.2f}, {b['y']:.2f}) "
                                     f"with {s.get('collision_with') or 'an outline (flag collided)'}")

    def assert_object_raised(self, label: str, by: float = 0.05, in_hand: bool = True) -> float:
        """``label`` rose at least ``by`` metres above where it started (while a hand held it,
        unless ``in_hand`` is false), judged by the world's object heights; returns the rise."""
        __tracebackhide__ = True
        timeline = self._need_timeline("assert_object_raised")
        start = (self.initial_world or timeline[0])["objects"][label]["z"]
        states = [*timeline, self._need_world("assert_object_raised")]
        considered = [s for s in states if not in_hand or label in s["held"].values()]
        assert considered, f"no hand ever held {label!r} (start z={start:.3f})"
        top = max(considered, key=lambda s: s["objects"][label]["z"])
        rise = top["objects"][label]["z"] - start
        held = " while held" if in_hand else ""
        assert rise >= by, (f"{label} rose {rise * 100:.1f} cm at most{held} (z {start:.3f} -> "
                            f"{top['objects'][label]['z']:.3f} at t={top['t']:.2f}); "
                            f"expected at least {by * 100:.1f} cm")
        return rise

    def assert_object_at(self, label: str, x: float, y: float, z: float | None = None,
                         tolerance: float = 0.05) -> None:
        """Where ``label`` ended up (the world's final state), within ``tolerance`` metres."""
        __tracebackhide__ = True
        p = self.object_position(label)
        error = math.dist((p["x"], p["y"]) + ((p["z"],) if z is not None else ()),
                          (x, y) + ((z,) if z is not None else ()))
        want = f"({x}, {y}" + (f", {z})" if z is not None else ")")
        assert error <= tolerance, f"{label} ended at {p}, {error:.3f} m from {want} (tolerance {tolerance} m)"

    def assert_robot_did_not_move(self, tolerance: float = 0.01) -> None:
        """The base stayed where it started, in every watched tick and at the end."""
        __tracebackhide__ = True
        b0 = self._first_world("assert_robot_did_not_move")["base"]
        for s in [*self.timeline, self._need_world("assert_robot_did_not_move")]:
            b = s["base"]
            moved = math.hypot(b["x"] - b0["x"], b["y"] - b0["y"])
            turned = abs(math.remainder(b["yaw"] - b0["yaw"], math.tau))
            assert moved <= tolerance and turned <= tolerance, (
                f"the robot moved by t={s['t']:.2f}: ({b0['x']:.3f}, {b0['y']:.3f}, {b0['yaw']:.3f}) -> "
                f"({b['x']:.3f}, {b['y']:.3f}, {b['yaw']:.3f})")

    def assert_arms_did_not_move(self, tolerance: float = 0.005, since: float | None = None,
                                 until: float | None = None) -> None:
        """No arm or hand joint left the angle it had at ``since`` (default: the start), in any
        watched tick up to ``until`` (default: the end of the run)."""
        __tracebackhide__ = True
        start = self.state_at(since) if since is not None else self._first_world("assert_arms_did_not_move")
        states = self.samples(since=since, until=until)
        if until is None:
            states.append(self._need_world("assert_arms_did_not_move"))
        q0 = {k: v for k, v in start["joints"].items() if is_arm_joint(k)}
        for s in states:
            moved = {k: round(s["joints"][k] - v, 4) for k, v in q0.items() if abs(s["joints"][k] - v) > tolerance}
            assert not moved, f"arm joints moved between t={start['t']:.2f} and t={s['t']:.2f} (rad): {moved}"


# --- running -------------------------------------------------------------------------------------


def run_tree(
    tree: str | Path | TreeSpec | None = None,
    *,
    text: str | None = None,
    backend: str = "dry",
    speed: float | None = None,
    rate: float = 20.0,
    markers: str | Path | None = None,
    start: str | None = None,
    seed: int | None = None,
    max_duration: float | None = 3600.0,
    on_tick: Hook | Sequence[Hook] | None = None,
    daemon_options: dict[str, dict[str, Any]] | None = None,
    watch: bool | int = True,
    settle: float = 0.0,
    options: RunOptions | None = None,
) -> RunResult:
    """Load (a path, a TreeSpec, or YAML ``text``), run to the end, return the result.

    ``markers`` defaults to the tree's own ``markers:`` key, else the lab map. ``speed``: the dry
    clock's factor (default 50), or the sim's pace cap (default none: lockstep, as fast as the
    tree keeps up). ``on_tick`` (one hook or a list) is called before every tick with a
    :class:`LiveRun`. On the sim, ``watch`` samples the world's state every tick (or every
    ``watch`` ticks; False: never) and ``settle`` lets the world run that many more sim seconds
    after the tree ends, before its final state is read (a braking robot, a falling object).
    The world and the daemons are shut down whatever happens, hook exceptions included.
    """
    spec = _load(tree, text, markers)
    opts = options or RunOptions()
    opts.backend, opts.rate, opts.max_duration = backend, rate, max_duration
    if speed is not None:
        opts.speed = speed
    elif backend == "dry" and opts.speed is None:
        opts.speed = DRY_SPEED
    if start is not None:
        opts.start = start
    if seed is not None:
        opts.seed = seed
    for family, values in (daemon_options or {}).items():
        opts.daemon_options.setdefault(family, {}).update(values)
    if backend == "sim":
        os.environ.setdefault("MUJOCO_GL", "egl")  # headless; the world server sets it too
    hooks = [on_tick] if callable(on_tick) else list(on_tick or [])
    session = Session(spec, opts)
    live = LiveRun(session, int(watch))
    try:
        session.start()
        assert session.executor is not None
        session.executor.pre_tick.append(lambda: _tick(live, hooks))
        initial = session.world.call("state") if session.world is not None else None
        outcome = session.run()
        _settle(live, settle)
        final = session.world.call("state") if session.world is not None else None
        report = session.report()
        world = session.blackboard.world.to_dict()
    finally:
        session.close()
        # the runner keeps a failed run's log folder for a reader; here the RunResult is what a
        # test reads, and a kept folder per run would pile up in /tmp
        shutil.rmtree(session.run_dir, ignore_errors=True)
    return RunResult(outcome, report, world, initial, final, live.timeline)


def _load(tree: str | Path | TreeSpec | None, text: str | None, markers: str | Path | None) -> TreeSpec:
    if isinstance(tree, TreeSpec):
        spec = tree
    elif text is not None:
        spec = load_tree_text(text, markers_file=markers or lab_markers())
    else:
        assert tree is not None, "give a tree path, a TreeSpec or text="
        spec = load_tree(tree, markers_file=markers)
    if spec.markers_file is None:
        spec.markers_file = str(lab_markers())
    return spec


def _tick(live: LiveRun, hooks: Iterable[Hook]) -> None:
    """Before each tick (after the daemons were polled): sample the world, then the test's hooks."""
    if live._watch_every > 0 and live.tick % live._watch_every == 0:
        live.sample()
    for hook in hooks:
        hook(live)
    live.tick += 1


def _settle(live: LiveRun, seconds: float) -> None:
    """Let the sim world run on after the tree ended, still watched and with daemons polled."""
    session = live.session
    if seconds <= 0 or session.world is None:
        return
    end = session.clock.now() + seconds
    period = 1.0 / session.options.rate
    while session.clock.now() < end - 1e-9:
        session.clock.sleep_until(min(end, session.clock.now() + period))
        if session.supervisor is not None:
            session.supervisor.poll()
        if live._watch_every > 0:
            live.sample()
