"""The benchmark trees, described once and built twice: as py_trees objects and as BT.CPP XML.

Describing a shape once is what makes the comparison fair: both engines tick the same nodes in
the same order with the same outcomes. Three kinds:

- ``flat``: a root Sequence(memory=False) of Success leaves. Statuses never change after the
  first tick: the steady state of a long tour.
- ``nested``: root Sequence -> g Selectors -> two Sequences each -> m leaves, depth 3. The first
  Sequence of every Selector ends in a Failure leaf, so the Selector goes on to its second
  Sequence and every node is ticked on every tick (a Selector whose first child succeeds would
  skip the rest, and the per-node figure would lie). Statuses are steady as well.
- ``flip``: a root Parallel of leaves that all alternate SUCCESS / FAILURE each tick, so every
  node (the root too) changes status on every tick: the worst case for the executor's
  status-change diff, which then publishes one event per node per tick.

``size`` counts every node, composites included; per-node figures divide by it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import py_trees
from py_trees.common import ParallelPolicy, Status

Kind = Literal["flat", "nested", "flip"]

# (selectors g, leaves per sequence m): 1 + g * (3 + 2m) nodes, exactly the nominal size.
NESTED_SHAPES: dict[int, tuple[int, int]] = {10: (1, 3), 100: (9, 4), 1000: (37, 12)}


@dataclass(frozen=True)
class Shape:
    kind: Kind
    size: int

    @property
    def label(self) -> str:
        return f"{self.kind}-{self.size}"

    @property
    def steady(self) -> bool:
        """True when statuses stop changing after the first tick."""
        return self.kind != "flip"


class Flip(py_trees.behaviour.Behaviour):
    """SUCCESS, FAILURE, SUCCESS, ... one per tick; as cheap as a leaf that returns a constant."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self._ok = False

    def update(self) -> Status:
        self._ok = not self._ok
        return Status.SUCCESS if self._ok else Status.FAILURE


def build_py_trees(shape: Shape) -> py_trees.behaviour.Behaviour:
    """A fresh py_trees tree of ``shape`` (call twice for two independent, identical trees)."""
    if shape.kind == "flat":
        leaves = [py_trees.behaviours.Success(f"ok{i}") for i in range(shape.size - 1)]
        return py_trees.composites.Sequence("root", memory=False, children=leaves)
    if shape.kind == "flip":
        leaves = [Flip(f"flip{i}") for i in range(shape.size - 1)]
        policy = ParallelPolicy.SuccessOnAll(synchronise=False)
        return py_trees.composites.Parallel("root", policy=policy, children=leaves)
    groups, per = _nested(shape.size)
    selectors = []
    for g in range(groups):
        failing = [py_trees.behaviours.Success(f"g{g}a{i}") for i in range(per - 1)]
        failing.append(py_trees.behaviours.Failure(f"g{g}fail"))
        passing = [py_trees.behaviours.Success(f"g{g}b{i}") for i in range(per)]
        selectors.append(py_trees.composites.Selector(f"sel{g}", memory=False, children=[
            py_trees.composites.Sequence(f"g{g}a", memory=False, children=failing),
            py_trees.composites.Sequence(f"g{g}b", memory=False, children=passing),
        ]))
    return py_trees.composites.Sequence("root", memory=False, children=selectors)


def btcpp_xml(shape: Shape, ok: str, fail: str, flip: str) -> str:
    """The same tree as BehaviorTree.CPP v4 XML, with leaf node IDs supplied by the caller.

    py_trees Sequence/Selector(memory=False) restart from the first child on every tick; in
    BT.CPP that is ReactiveSequence / ReactiveFallback (plain Sequence resumes a RUNNING child,
    i.e. memory=True). With leaves that never return RUNNING both behave alike, but the reactive
    ones are the true equivalents. The py_trees Parallel ticks every child before deciding; in
    BT.CPP that is ParallelAll (plain Parallel stops ticking once its failure threshold is hit).
    """
    if shape.kind == "flat":
        body = _wrap("ReactiveSequence", f"<{ok}/>" * (shape.size - 1))
    elif shape.kind == "flip":
        body = _wrap('ParallelAll max_failures="1"', f"<{flip}/>" * (shape.size - 1))
    else:
        groups, per = _nested(shape.size)
        failing = _wrap("ReactiveSequence", f"<{ok}/>" * (per - 1) + f"<{fail}/>")
        passing = _wrap("ReactiveSequence", f"<{ok}/>" * per)
        body = _wrap("ReactiveSequence", _wrap("ReactiveFallback", failing + passing) * groups)
    return f'<root BTCPP_format="4"><BehaviorTree ID="Main">{body}</BehaviorTree></root>'


def _wrap(tag: str, inner: str) -> str:
    return f"<{tag}>{inner}</{tag.split()[0]}>"


def _nested(size: int) -> tuple[int, int]:
    try:
        return NESTED_SHAPES[size]
    except KeyError:
        raise ValueError(f"no nested shape of {size} nodes; sizes: {sorted(NESTED_SHAPES)}") from None
