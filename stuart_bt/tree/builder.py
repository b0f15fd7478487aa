"""Turning a loaded :class:`TreeSpec` into py_trees behaviours.

Composites and decorators are built here; leaves come from the caller's ``make_leaf`` so the
executor (real daemons) and tests (fakes) can supply their own. Every behaviour gets
``spec_path`` (its node path) and is named by the last path segment, so logs, reports and the
web view name nodes exactly as errors and ``show`` do. Options given as ``$key`` references
are read from the blackboard at build time.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import py_trees
from py_trees.behaviour import Behaviour
from py_trees.common import OneShotPolicy, ParallelPolicy

from ..core import expr
from ..core.blackboard import Blackboard
from ..core.catalogue import COMPOSITES, DECORATORS
from ..core.clock import Clock
from ..core.errors import StuartError
from .decorators import Delay, Guard, Timeout
from .spec import NodeSpec, TreeSpec

LeafFactory = Callable[[NodeSpec], Behaviour]


class BuildError(StuartError, ValueError):
    """An option that could only be resolved at build time (a ``$key`` reference) is unusable."""


def build(spec: TreeSpec | NodeSpec, make_leaf: LeafFactory, clock: Clock, blackboard: Blackboard) -> Behaviour:
    """The py_trees behaviour for ``spec`` (a whole tree or one node) and everything below it."""
    node = spec.root if isinstance(spec, TreeSpec) else spec
    return _Builder(make_leaf, clock, blackboard).node(node)


class _Builder:
    def __init__(self, make_leaf: LeafFactory, clock: Clock, blackboard: Blackboard) -> None:
        self.make_leaf = make_leaf
        self.clock = clock
        self.blackboard = blackboard

    def node(self, spec: NodeSpec) -> Behaviour:
        if spec.kind in COMPOSITES:
            behaviour = self.composite(spec)
        elif spec.kind in DECORATORS:
            behaviour = self.decorator(spec)
        else:
            behaviour = self.make_leaf(spec)
            behaviour.name = spec.name
        behaviour.spec_path = spec.path  # type: ignore[attr-defined]
        return behaviour

    def option(self, spec: NodeSpec, name: str) -> Any:
        """An option as given or its catalogue default, with a ``$key`` reference resolved."""
        kind = COMPOSITES.get(spec.kind) or DECORATORS[spec.kind]
        default = next(p.default for p in kind.params if p.name == name)
        value = spec.params.get(name, default)
        try:
            return self.blackboard.resolve(value)
        except KeyError as e:
            raise BuildError(f"{spec.path}: option {name!r} refers to blackboard key {e.args[0]!r}, "
                             "which is not set") from None

    def composite(self, spec: NodeSpec) -> Behaviour:
        children = [self.node(c) for c in spec.children]
        if spec.kind == "sequence":
            return py_trees.composites.Sequence(spec.name, memory=bool(self.option(spec, "memory")), children=children)
        if spec.kind == "selector":
            return py_trees.composites.Selector(spec.name, memory=bool(self.option(spec, "memory")), children=children)
        return py_trees.composites.Parallel(spec.name, policy=self.parallel_policy(spec, children), children=children)

    def parallel_policy(self, spec: NodeSpec, children: list[Behaviour]) -> ParallelPolicy.Base:
        policy = self.option(spec, "policy")
        synchronise = bool(self.option(spec, "synchronise"))
        if policy == "all":
            return ParallelPolicy.SuccessOnAll(synchronise=synchronise)
        if policy == "one":
            return ParallelPolicy.SuccessOnOne()
        if policy != "selected":
            raise BuildError(f"{spec.path}: unknown parallel policy {policy!r}")
        wanted = self.option(spec, "selected")
        wanted = [wanted] if isinstance(wanted, str) else list(wanted or [])
        chosen = [b for b in children if b.name in wanted]
        if len(chosen) != len(wanted):
            raise BuildError(f"{spec.path}: 'selected' names children that do not exist: {wanted}")
        return ParallelPolicy.SuccessOnSelected(children=chosen, synchronise=synchronise)

    def decorator(self, spec: NodeSpec) -> Behaviour:
        if len(spec.children) != 1:
            raise BuildError(f"{spec.path}: a decorator needs exactly one child")
        child = self.node(spec.children[0])
        name = spec.name
        if spec.kind == "retry":
            return py_trees.decorators.Retry(name, child, num_failures=int(self.option(spec, "times")))
        if spec.kind == "repeat":
            return py_trees.decorators.Repeat(name, child, num_success=int(self.option(spec, "times")))
        if spec.kind == "inverter":
            return py_trees.decorators.Inverter(name, child)
        if spec.kind == "force_success":
            return py_trees.decorators.FailureIsSuccess(name, child)
        if spec.kind == "force_failure":
            return py_trees.decorators.SuccessIsFailure(name, child)
        if spec.kind == "oneshot":
            on = self.option(spec, "on")
            policy = OneShotPolicy.ON_SUCCESSFUL_COMPLETION if on == "success" else OneShotPolicy.ON_COMPLETION
            return py_trees.decorators.OneShot(name, child, policy=policy)
        if spec.kind == "timeout":
            return Timeout(name, child, self.clock, float(self.option(spec, "seconds")))
        if spec.kind == "delay":
            return Delay(name, child, self.clock, float(self.option(spec, "seconds")))
        if spec.kind == "guard":
            try:
                condition = expr.parse(self.option(spec, "condition"))
            except expr.ExprError as e:
                raise BuildError(f"{spec.path}: guard condition: {e.message}") from None
            return Guard(name, child, condition, self.blackboard.get)
        raise BuildError(f"{spec.path}: no builder for decorator {spec.kind!r}")
