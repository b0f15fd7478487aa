"""Base classes for leaves: never block a tick, always time out, always say why they failed.

A :class:`Leaf` is a py_trees behaviour built from a :class:`~stuart_bt.tree.spec.NodeSpec`.
A :class:`SkillLeaf` drives one daemon command through the lifecycle py_trees gives us:

- ``initialise`` resolves blackboard references and sends exactly one command;
- ``update`` only reads what the daemon has said (the executor polls the daemons once per tick);
- ``terminate`` with INVALID (preemption by a parent) cancels the command in the daemon, so the
  motion really stops.

Every outcome and failure reason goes to the blackboard (``outcomes``, ``last_failure``) and to the
event stream (``leaf`` events), so reports and tests can ask what happened and where.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import py_trees
from py_trees.common import Status

from ..core.blackboard import Blackboard
from ..core.catalogue import LEAVES, LeafSpec
from ..core.clock import Clock
from ..core.events import EventStream
from ..tree.spec import NodeSpec


class DaemonRequest(Protocol):
    id: str
    status: str
    result: dict[str, Any] | None
    error_code: str | None
    reason: str | None

    @property
    def finished(self) -> bool: ...


class DaemonClientPort(Protocol):
    @property
    def connected(self) -> bool:
        """A daemon process is attached (it may still be starting up)."""

    def request(self, cmd: str, args: dict[str, Any], path: str | None = None) -> DaemonRequest: ...

    def cancel(self, request: Any) -> object:  # a request this client made
        ...


class DaemonPort(Protocol):
    """What leaves need of the supervisor (kept narrow so tests can pass a double)."""

    def client(self, family: str) -> DaemonClientPort: ...

    def stop_all(self) -> Sequence[DaemonRequest]: ...


@dataclass
class RunContext:
    """Everything a leaf may touch, handed over by the executor."""

    clock: Clock
    events: EventStream
    blackboard: Blackboard
    daemons: DaemonPort | None
    tree_dir: Path


class LeafFailure(Exception):
    """Raised inside a leaf's own code to fail the leaf with a reason (never escapes a tick)."""


class Leaf(py_trees.behaviour.Behaviour):
    """Common machinery: parameters with defaults, timeout on the shared clock, outcome records."""

    kind: str = ""

    def __init__(self, spec: NodeSpec, ctx: RunContext) -> None:
        super().__init__(name=spec.name)
        self.spec = spec
        self.spec_path = spec.path
        self.ctx = ctx
        self.leaf_spec: LeafSpec = LEAVES[spec.kind]
        self.failure_reason = ""
        self.failure_code: str | None = None  # the daemon's error code, when a daemon failed the leaf
        self.failure_detail: dict[str, Any] = {}  # the data the daemon's error carried (what blocked, where)
        self.result: dict[str, Any] = {}
        self._started_at = 0.0
        self._early: Status | None = None

    # -- parameters -------------------------------------------------------------------------
    def param(self, name: str, default: Any = None) -> Any:
        """A parameter with blackboard references resolved, else the catalogue default."""
        if name in self.spec.params:
            try:
                return self.ctx.blackboard.resolve(self.spec.params[name])
            except KeyError as e:
                raise LeafFailure(f"blackboard has no key {e.args[0]!r} (needed by '{name}')") from None
        p = self.leaf_spec.param(name)
        return p.default if p is not None and default is None else default

    def has(self, name: str) -> bool:
        return name in self.spec.params

    @property
    def timeout(self) -> float:
        given = self.spec.params.get("timeout")
        if given is not None:
            return float(self.ctx.blackboard.resolve(given))
        return self.default_timeout()

    def default_timeout(self) -> float:
        return self.leaf_spec.default_timeout

    # -- py_trees lifecycle -------------------------------------------------------------------
    def initialise(self) -> None:
        self.failure_reason = ""
        self.failure_code = None
        self.failure_detail = {}
        self.result = {}
        self._early = None
        self._started_at = self.ctx.clock.now()
        try:
            self._early = self.start()
        except LeafFailure as e:
            self.failure_reason = str(e)
            self._early = Status.FAILURE

    def update(self) -> Status:
        if self._early is not None:
            status = self._early
        else:
            try:
                status = self.step()
            except LeafFailure as e:
                self.failure_reason = str(e)
                status = Status.FAILURE
            if status == Status.RUNNING and self.ctx.clock.now() - self._started_at > self.timeout:
                self.failure_reason = f"timed out after {_seconds(self.timeout)}"
                self.on_timeout()
                status = Status.FAILURE
        if status != Status.RUNNING:
            self._record(status)
        return status

    def terminate(self, new_status: Status) -> None:
        if new_status == Status.INVALID and self.status == Status.RUNNING:
            self.on_preempt()

    # -- hooks for subclasses -------------------------------------------------------------------
    def start(self) -> Status | None:
        """Begin the work; return a final status to finish at once, or None to keep running."""
        return None

    def step(self) -> Status:
        """Report progress; called once per tick while running."""
        return Status.SUCCESS

    def on_timeout(self) -> None:
        """The leaf ran out of time: release whatever it started."""

    def on_preempt(self) -> None:
        """A parent stopped the leaf while it ran: release whatever it started."""

    # -- outcome ----------------------------------------------------------------------------------
    def _record(self, status: Status) -> None:
        outcome = status.value
        bb = self.ctx.blackboard
        entry = {"status": outcome, "reason": self.failure_reason or None, "code": self.failure_code,
                 "result": self.result or None}
        detail = {"detail": self.failure_detail} if self.failure_detail else {}  # only when an error carried data
        entry.update(detail)
        outcomes = bb.get("outcomes", None)
        if outcomes is None:
            outcomes = {}
            bb.set("outcomes", outcomes)
        outcomes[self.spec_path] = entry
        if status == Status.FAILURE:
            bb.set("last_failure", {"path": self.spec_path, "reason": self.failure_reason})
        self.ctx.events.publish(
            "leaf", self.spec_path, skill=self.spec.kind, outcome=outcome, reason=self.failure_reason or None,
            result=self.result or None, **detail,
        )


class SkillLeaf(Leaf):
    """A leaf that sends one command to its skill family's daemon and follows it to the end."""

    def __init__(self, spec: NodeSpec, ctx: RunContext) -> None:
        super().__init__(spec, ctx)
        self.request: DaemonRequest | None = None
        self.wait_for_completion = True

    @property
    def family(self) -> str:
        assert self.leaf_spec.family is not None
        return self.leaf_spec.family

    def command(self) -> tuple[str, dict[str, Any]]:
        """The daemon command name and its JSON arguments."""
        raise NotImplementedError

    def on_done(self, result: dict[str, Any]) -> None:
        """The daemon finished the command: update the world state from its result."""

    def start(self) -> Status | None:
        self.request = None
        if self.ctx.daemons is None:
            raise LeafFailure(f"no daemons are running for the '{self.family}' skill family")
        self._command = self.command()
        self._send_when_connected()
        return None

    def _send_when_connected(self) -> None:
        """Send now, or (while the daemon restarts after a crash) on a later tick, within the
        leaf's timeout: a leaf that starts during a restart waits instead of failing."""
        assert self.ctx.daemons is not None
        client = self.ctx.daemons.client(self.family)
        if client.connected:
            cmd, args = self._command
            self.request = client.request(cmd, args, path=self.spec_path)

    def step(self) -> Status:
        if self.request is None:
            self._send_when_connected()
            if self.request is None:
                return Status.RUNNING
        request = self.request
        if request.status == "error":
            code = self.failure_code = request.error_code or "error"
            self.failure_reason = f"{code}: {request.reason}" if request.reason else code
            self.failure_detail = dict(request.result or {})
            return Status.FAILURE
        if request.status == "done":
            self.result = dict(request.result or {})
            try:
                self.on_done(self.result)
            except (ValueError, TypeError, KeyError) as e:  # a result the world state cannot take in
                self.failure_reason = f"bad_result: {self.family} daemon's result for {request.id} is unusable: {e}"
                self.result = {}
                return Status.FAILURE
            return Status.SUCCESS
        if not self.wait_for_completion and request.status == "accepted":
            return Status.SUCCESS
        return Status.RUNNING

    def _cancel(self) -> None:
        if self.request is not None and not self.request.finished and self.ctx.daemons is not None:
            self.ctx.daemons.client(self.family).cancel(self.request)

    on_timeout = _cancel
    on_preempt = _cancel


def failure_code(reason: str | None) -> str | None:
    """The error code a skill leaf's failure reason starts with ("watchdog: loco daemon heard
    nothing ..." -> "watchdog"), so a caller can act on the kind of failure, not its wording."""
    code, sep, _ = (reason or "").partition(": ")
    return code if sep and code.isidentifier() else None


def _seconds(value: float) -> str:
    if math.isinf(value):
        return "forever"
    return f"{value:g} s"
