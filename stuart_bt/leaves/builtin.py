"""Leaves that run inside the executor: ``wait``, ``stop``, ``condition``, ``set`` and ``log``."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from py_trees.common import Status

from ..core import expr
from ..core.blackboard import render_template
from ..tree.spec import NodeSpec
from .base import DaemonRequest, Leaf, LeafFailure, RunContext


class Wait(Leaf):
    """Succeed after some seconds of clock time."""

    kind = "wait"

    def start(self) -> Status | None:
        self._until = self._started_at + float(self.param("seconds"))
        return None

    def step(self) -> Status:
        return Status.SUCCESS if self.ctx.clock.now() >= self._until else Status.RUNNING

    def default_timeout(self) -> float:
        return float("inf")


class Stop(Leaf):
    """Send stop to every daemon; succeed when all have acknowledged."""

    kind = "stop"

    def start(self) -> Status | None:
        if self.ctx.daemons is None:
            return Status.SUCCESS
        self._requests: Sequence[DaemonRequest] = self.ctx.daemons.stop_all()
        return None

    def step(self) -> Status:
        if all(r.finished for r in self._requests):
            failed = [r for r in self._requests if r.status == "error"]
            if failed:
                raise LeafFailure("; ".join(f"{r.error_code}: {r.reason}" for r in failed))
            return Status.SUCCESS
        return Status.RUNNING


class Condition(Leaf):
    """Check a blackboard expression: SUCCESS when true; FAILURE (or RUNNING with wait) when false."""

    kind = "condition"

    def __init__(self, spec: NodeSpec, ctx: RunContext) -> None:
        super().__init__(spec, ctx)
        self.expression = expr.parse(str(spec.params["expr"]))
        self.wait = bool(spec.params.get("wait", False))

    def step(self) -> Status:
        try:
            value = self.expression.evaluate(self.ctx.blackboard.get)
        except expr.ExprError as e:
            raise LeafFailure(e.message) from None
        if value:
            return Status.SUCCESS
        if self.wait:
            return Status.RUNNING
        self.failure_reason = f"{self.expression.text!r} is false"
        return Status.FAILURE


class Set(Leaf):
    """Write a blackboard key from a literal (or ``$ref``) or from an expression."""

    kind = "set"

    def start(self) -> Status | None:
        value: Any
        if self.has("expr"):
            try:
                value = expr.parse(str(self.spec.params["expr"])).evaluate(self.ctx.blackboard.get)
            except expr.ExprError as e:
                raise LeafFailure(e.message) from None
        else:
            value = self.param("value")
        self.ctx.blackboard.set(str(self.spec.params["key"]), value)
        self.result = {"key": self.spec.params["key"], "value": value}
        return Status.SUCCESS


class Log(Leaf):
    """Publish a message on the event stream; ``${key}`` fills in blackboard values."""

    kind = "log"

    def start(self) -> Status | None:
        try:
            message = render_template(str(self.spec.params["message"]), self.ctx.blackboard.get)
        except KeyError as e:
            raise LeafFailure(f"blackboard has no key {e.args[0]!r}") from None
        self.ctx.events.publish("log", self.spec_path, level=self.param("level"), message=message)
        return Status.SUCCESS
