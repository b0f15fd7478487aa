"""Run trees in tests and assert on what the robot did.

::

    from stuart_bt.testing import run_tree

    def test_greeting_waves_while_speaking():
        result = run_tree("trees/greet.yaml")
        result.assert_success()
        result.assert_said("I'm Stuart")
        result.assert_gestured("high wave")

``run_tree`` starts the daemons of the chosen backend (``dry`` by default, sped up), runs the tree
to the end, shuts everything down and returns a :class:`RunResult` holding the report. The
assertion helpers read only the report, so they work the same on any backend.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any, Callable

from .executor import RunOutcome
from .runner import RunOptions, Session
from .tree.loader import load_tree, load_tree_text
from .tree.spec import TreeSpec


def lab_markers() -> Path:
    """The lab's marker map shipped with the package."""
    return Path(str(resources.files("stuart_bt.sim") / "maps" / "lab_markers.json"))


@dataclass
class RunResult:
    outcome: RunOutcome
    report: dict[str, Any]
    world: dict[str, Any] = field(default_factory=dict)

    @property
    def status(self) -> str:
        return self.outcome.status

    def failure(self, path: str) -> str | None:
        """Why the leaf at ``path`` last failed (conditions included), or None if it never did."""
        reasons = [e.get("reason") for e in self.events("leaf") if e["path"] == path and e["outcome"] == "FAILURE"]
        return reasons[-1] if reasons else None

    def events(self, kind: str) -> list[dict[str, Any]]:
        return [e for e in self.report["events"] if e["kind"] == kind]

    # -- assertions -----------------------------------------------------------------------------
    def assert_success(self) -> None:
        failures = "; ".join(f"{f['path']}: {f['reason']}" for f in self.report["failures"])
        assert self.status == "SUCCESS", f"run ended {self.status}: {failures or self.outcome.reason}"

    def assert_no_failures(self) -> None:
        assert not self.report["failures"], f"failures: {self.report['failures']}"

    def assert_visited(self, *markers: str) -> None:
        """These markers were reached in this order (others may come between)."""
        visited = iter(self.report["visited"])
        missing = [m for m in markers if m not in visited]
        assert not missing, f"visited {self.report['visited']}, expected in order {list(markers)}"

    def assert_said(self, fragment: str) -> None:
        texts = [s["text"] for s in self.report["spoken"]]
        assert any(fragment in t for t in texts), f"nothing said contains {fragment!r}; said {texts}"

    def assert_gestured(self, name: str) -> None:
        played = [g["name"] for g in self.report["gestures"]]
        flat = [n for p in played for n in (p if isinstance(p, list) else [p])]
        assert name in flat, f"gesture {name!r} not played; played {flat}"

    def assert_holding(self, label: str | None) -> None:
        assert self.report.get("held") == label, f"holding {self.report.get('held')!r}, expected {label!r}"

    def assert_final_pose(self, x: float, y: float, yaw: float | None = None,
                          tolerance: float = 0.10, yaw_tolerance: float = 0.0873) -> None:
        pose = self.report["final_pose"]
        distance = math.hypot(pose["x"] - x, pose["y"] - y)
        assert distance <= tolerance, f"final pose {pose} is {distance:.3f} m from ({x}, {y})"
        if yaw is not None:
            error = abs(math.remainder(pose["yaw"] - yaw, math.tau))
            assert error <= yaw_tolerance, f"final yaw {pose['yaw']:.3f} is {error:.3f} rad from {yaw}"


def run_tree(
    tree: str | Path | TreeSpec | None = None,
    *,
    text: str | None = None,
    backend: str = "dry",
    speed: float = 50.0,
    rate: float = 20.0,
    markers: str | Path | None = None,
    start: str | None = None,
    max_duration: float | None = 3600.0,
    on_tick: Callable[[Session], None] | None = None,
    options: RunOptions | None = None,
) -> RunResult:
    """Load (a path, a TreeSpec, or YAML ``text``), run to the end, return the result.

    ``markers`` defaults to the tree's own ``markers:`` key, else the lab map. ``on_tick`` is
    called before every tick with the session (to stop it, move things, or inject faults).
    """
    if isinstance(tree, TreeSpec):
        spec = tree
    elif text is not None:
        spec = load_tree_text(text, markers_file=markers or lab_markers())
    else:
        assert tree is not None, "give a tree path, a TreeSpec or text="
        spec = load_tree(tree, markers_file=markers)
    if spec.markers_file is None:
        spec.markers_file = str(lab_markers())
    opts = options or RunOptions()
    opts.backend, opts.speed, opts.rate, opts.max_duration = backend, speed, rate, max_duration
    if start is not None:
        opts.start = start
    with Session(spec, opts) as session:
        if on_tick is not None:
            assert session.executor is not None
            session.executor.pre_tick.append(lambda: on_tick(session))
        outcome = session.run()
        report = session.report()
        world = session.blackboard.world.to_dict()
    return RunResult(outcome, report, world)
