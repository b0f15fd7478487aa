"""tick_overhead: what stuart_bt's Executor adds on top of ticking a py_trees tree.

Each tree shape (see :mod:`bench.trees`) is ticked three ways, in interleaved runs:

(a) raw py_trees: ``py_trees.trees.BehaviourTree(root).tick()``;
(b) stuart_bt: ``Executor(root, ManualClock(), events, rate).tick_once()`` on an identical tree,
    with one EventStream subscriber and one pre-tick hook that does nothing (what the runner
    installs when a tree needs no daemons: nothing, so the hook is the cost of the hook loop);
(c) BehaviorTree.CPP v4 through ``behaviortreepy``: the same tree from XML text, leaves
    registered as simple conditions (Python callbacks, as stuart_bt's leaves are Python), ticked
    with ``tick_exactly_once`` (``tick_once`` may tick again when a node signals a wake-up).

A second, identical raw py_trees tree is timed too (an A/A pair): how far its figure strays from
(a) is the noise floor of the (b)/(a) ratio in that run, reported in the note.

The goal is (b)/(a) <= 1.15 in the steady state. The ``flip`` shape is the worst case for the
executor's status diff and is reported without a goal.
"""

from __future__ import annotations

import importlib.util
import statistics
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import py_trees

from stuart_bt.core.clock import ManualClock
from stuart_bt.core.events import EventStream
from stuart_bt.run.executor import Executor

from .result import Anchor, Goal, Result
from .sink import EventCounter
from .stats import interleaved_runs, paired_ratio
from .trees import Shape, btcpp_xml, build_py_trees

NAME = "tick_overhead"
GOAL_RATIO = 1.15
SIZES = (10, 100, 1000)
KINDS = ("flat", "nested", "flip")
PY_TREES_ANCHOR = "py_trees 2.6.0 BehaviourTree.tick() (raw)"
BTCPP_ANCHOR = "behaviortreepy 0.1.4 (BT.CPP v4), Python-callback condition leaves, tick_exactly_once()"


def no_daemons_hook() -> None:
    """The pre-tick work of a run with zero daemons: none."""


class NodeCounter(py_trees.visitors.VisitorBase):
    """Counts the nodes one tick visits (used once, outside timing, to check the shapes)."""

    def __init__(self) -> None:
        super().__init__(full=False)
        self.count = 0

    def run(self, behaviour: py_trees.behaviour.Behaviour) -> None:
        self.count += 1


def visited_per_tick(shape: Shape) -> int:
    tree = py_trees.trees.BehaviourTree(build_py_trees(shape))
    counter = NodeCounter()
    tree.add_visitor(counter)
    tree.tick()
    counter.count = 0
    tree.tick()
    return counter.count


@dataclass
class BtcppTrees:
    """A behaviortreepy factory with the leaves the benchmark trees need."""

    factory: Any
    phase: list[Any]  # [status] the Flip leaves return this tick
    success: Any
    failure: Any

    @classmethod
    def create(cls) -> BtcppTrees | None:
        if importlib.util.find_spec("behaviortreepy") is None:
            return None
        import behaviortreepy as bt

        factory = bt.BehaviorTreeFactory()
        ok, fail = bt.NodeStatus.SUCCESS, bt.NodeStatus.FAILURE
        phase = [fail]
        factory.register_simple_condition("Ok", lambda node: ok)
        factory.register_simple_condition("Fail", lambda node: fail)
        factory.register_simple_condition("Flip", lambda node: phase[0])
        return cls(factory, phase, ok, fail)

    def ticker(self, shape: Shape, builtin: bool = False) -> Callable[[], object]:
        """One tick of ``shape``; ``builtin`` uses BT.CPP's C++ AlwaysSuccess/AlwaysFailure leaves."""
        ok, fail = ("AlwaysSuccess", "AlwaysFailure") if builtin else ("Ok", "Fail")
        tree = self.factory.create_tree_from_text(btcpp_xml(shape, ok, fail, "Flip"))
        if shape.steady:
            return tree.tick_exactly_once
        phase, success, failure = self.phase, self.success, self.failure

        def flip_tick() -> object:  # all Flip leaves change together, once per tick
            phase[0] = success if phase[0] is failure else failure
            return tree.tick_exactly_once()

        return flip_tick


def measure_shape(shape: Shape, btcpp: BtcppTrees | None, window: float, runs: int) -> list[Result]:
    visited = visited_per_tick(shape)
    if visited != shape.size:
        raise AssertionError(f"{shape.label}: a tick visits {visited} nodes, expected {shape.size}")
    raw = py_trees.trees.BehaviourTree(build_py_trees(shape))
    clock = ManualClock()
    events = EventStream(clock)
    counter = EventCounter()
    events.subscribe(counter)
    executor = Executor(build_py_trees(shape), clock, events, rate=20.0, pre_tick=[no_daemons_hook])
    twin = py_trees.trees.BehaviourTree(build_py_trees(shape))  # A/A: the noise floor of the ratio
    candidates: dict[str, Callable[[], object]] = {"raw": raw.tick, "executor": executor.tick_once,
                                                   "raw_twin": twin.tick}
    if btcpp is not None:
        candidates["btcpp"] = btcpp.ticker(shape)
        if shape.steady:
            candidates["btcpp_builtin"] = btcpp.ticker(shape, builtin=True)
    executor.tick_once()  # the first tick publishes every node's INVALID -> status change
    events_before, ticks_before = counter.count, executor.ticks
    runs_s = interleaved_runs(candidates, window, runs)
    per_tick_events = (counter.count - events_before) / max(1, executor.ticks - ticks_before)
    us = {name: statistics.median(values) / shape.size * 1e6 for name, values in runs_s.items()}
    ratios = {name: paired_ratio(runs_s[name], runs_s[base]) for name, base in
              (("executor", "raw"), ("raw_twin", "raw"), ("raw", "btcpp"), ("btcpp_builtin", "btcpp"))
              if name in runs_s and base in runs_s}
    return [_executor_result(shape, us, ratios, per_tick_events), _py_trees_result(shape, us, ratios)]


def _executor_result(shape: Shape, us: dict[str, float], ratios: dict[str, float], per_tick_events: float) -> Result:
    ratio = ratios["executor"]
    note = (f"{shape.size} nodes, {per_tick_events:g} status events per tick while timed; "
            f"ratio = median of per-round ratios; A/A noise: a second raw tree timed {ratios['raw_twin']:.3f}x "
            "the first")
    goal = None
    if shape.steady:
        goal = Goal(GOAL_RATIO)
        note += "; steady state (statuses unchanged after the first tick)"
    else:
        note += "; worst case for the status diff (every node changes every tick), reported without a goal"
    return Result(f"{NAME}.executor.{shape.label}", us["executor"], "us/node/tick",
                  Anchor(PY_TREES_ANCHOR, us["raw"]), goal, note, paired_ratio=ratio)


def _py_trees_result(shape: Shape, us: dict[str, float], ratios: dict[str, float]) -> Result:
    name = f"{NAME}.py_trees.{shape.label}"
    if "btcpp" not in us:
        return Result(name, us["raw"], "us/node/tick", None,
                      note="behaviortreepy is not installed (pip install 'stuart-bt[bench]'): no BT.CPP anchor")
    note = "raw py_trees against BT.CPP; no goal (context for the executor figures); ratio = median of per-round ratios"
    if "btcpp_builtin" in us:
        note += (f"; BT.CPP with its built-in C++ AlwaysSuccess/AlwaysFailure leaves instead: "
                 f"{us['btcpp_builtin']:.3f} us/node ({ratios['btcpp_builtin']:.2f}x the Python-callback leaves)")
    return Result(name, us["raw"], "us/node/tick", Anchor(BTCPP_ANCHOR, us["btcpp"]), note=note,
                  paired_ratio=ratios["raw"])


def run(quick: bool = False) -> list[Result]:
    window, runs = (0.005, 3) if quick else (0.02, 25)
    btcpp = BtcppTrees.create()
    results: list[Result] = []
    for kind in KINDS:
        for size in SIZES:
            results += measure_shape(Shape(kind, size), btcpp, window, runs)
    return results
