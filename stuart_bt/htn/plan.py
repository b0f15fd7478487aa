"""What the planner returns: the whole task tree, the flat list of steps, and why.

A :class:`Plan` keeps every task it refined as a :class:`TaskNode`: compound nodes record the
method chosen and, for each method tried and rejected, a :class:`MethodAttempt` saying why
(a precondition clause and the values it read, or the failure further down or later in the plan
that made the planner back up). Primitive nodes carry the skill and its arguments: what the
compiler turns into leaves. ``primitives()`` is the flat plan GTPyhop would return;
``explain()`` draws the tree as text; ``to_dict()`` is JSON with the tree as a flat node table
(so a plan thousands of levels deep still serialises).

When no plan exists, :class:`PlanningFailed` carries the same kind of explanation for the
failure; when a budget runs out, :class:`PlanningBudgetExceeded` says how far the search got.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..core.errors import StuartError
from .expressions import ClauseFailure
from .state import State, jsonable
from .values import format_value

if TYPE_CHECKING:
    from ..tree.spec import Location

MAX_JSON_NESTING = 40  # failure chains deeper than this are cut in to_dict (json.dumps recurses)


@dataclass(eq=False)
class MethodAttempt:
    """One method of a compound task, as the planner tried it.

    ``kind`` of a rejection: ``precondition`` (``reason`` is a ClauseFailure), ``subtask`` (a
    task below this method failed), ``later`` (this method worked, a task after it failed and
    the planner backed up to try the next method), ``arguments`` (its subtasks could not be built).
    """

    method: str
    chosen: bool
    kind: str | None = None
    reason: ClauseFailure | Failure | str | None = None
    location: Location | None = None

    def summary(self) -> str:
        """One line: what went wrong (nested failures summarised by their first line)."""
        if self.chosen:
            return f"chose {self.method}"
        if isinstance(self.reason, Failure):
            lead = "a subtask failed" if self.kind == "subtask" else "a later task failed"
            return f"{self.method}: {lead}: {self.reason.headline()}"
        if self.kind == "arguments":
            return f"{self.method}: cannot build its subtasks: {self.reason}"
        return f"{self.method}: {self.reason}"

    def to_dict(self, depth: int = 0) -> dict[str, Any]:
        out: dict[str, Any] = {"method": self.method, "chosen": self.chosen}
        if not self.chosen:
            out["kind"] = self.kind
            if isinstance(self.reason, ClauseFailure):
                out["reason"] = str(self.reason)
                out["clause"] = self.reason.to_dict()
            elif isinstance(self.reason, Failure):
                out["reason"] = self.summary()
                out["failure"] = self.reason.to_dict(depth + 1) if depth < MAX_JSON_NESTING else "..."
            else:
                out["reason"] = str(self.reason)
        if self.location is not None:
            out["where"] = str(self.location)
        return out


@dataclass(eq=False)
class Failure:
    """Why a task could not be refined: a primitive's precondition, no applicable method (with
    every method's rejection), bad arguments, or effects that could not be computed."""

    task: str
    path: str
    kind: str  # "precondition" | "no_method" | "arguments" | "effects"
    message: str
    attempts: list[MethodAttempt] = field(default_factory=list)
    node: TaskNode | None = field(default=None, repr=False)

    def headline(self) -> str:
        return f"{self.task}: {self.message}"

    def lines(self, indent: str = "  ", mark: str = "✗") -> list[str]:
        """The failure and, for each rejected method, why, nested failures indented below."""
        out: list[str] = []
        stack: list[tuple[str, Any, int]] = [("failure", self, 0)]
        while stack:
            what, item, level = stack.pop()
            pad = indent * level
            if what == "line":
                out.append(pad + item)
                continue
            out.append(pad + item.headline())
            pending: list[tuple[str, Any, int]] = []
            for attempt in item.attempts:
                if attempt.chosen:
                    continue
                if isinstance(attempt.reason, Failure):
                    lead = "a subtask failed" if attempt.kind == "subtask" else "worked, then a later task failed"
                    pending.append(("line", f"{mark} {attempt.method}: {lead}:", level + 1))
                    pending.append(("failure", attempt.reason, level + 2))
                else:
                    pending.append(("line", f"{mark} {attempt.summary()}", level + 1))
            stack.extend(reversed(pending))
        return out

    def __str__(self) -> str:
        return "\n".join(self.lines())

    def to_dict(self, depth: int = 0) -> dict[str, Any]:
        return {"task": self.task, "path": self.path, "kind": self.kind, "message": self.message,
                "attempts": [a.to_dict(depth) for a in self.attempts]}


@dataclass(eq=False)
class TaskNode:
    """One task in the decomposition. ``kind``: ``mission`` (the root), ``compound`` or ``primitive``."""

    name: str
    args: dict[str, Any]
    kind: str
    parent: TaskNode | None = field(default=None, repr=False)
    depth: int = 0
    children: list[TaskNode] = field(default_factory=list, repr=False)
    method: str | None = None
    attempts: list[MethodAttempt] = field(default_factory=list, repr=False)
    skill: str | None = None
    skill_args: dict[str, Any] | None = None
    optional: bool = False
    skip_if: str | None = None
    changes: list[tuple[str, Any]] | None = None  # predicted effects: (target, value); value MISSING-free
    step: int | None = None  # 1-based position among the primitives
    status: str = "pending"  # "pending" | "planned" | "failed"
    failure: Failure | None = field(default=None, repr=False)
    source: Location | None = None
    ack: bool = False  # an acknowledgement the planner put first in an intent
    definition: Any = field(default=None, repr=False)  # the domain's TaskDef / PrimitiveDef

    @property
    def call(self) -> str:
        """The task as text: ``fetch(bottle, workbench)``."""
        if self.kind == "mission":
            return "mission"
        return f"{self.name}({', '.join(format_value(v) for v in self.args.values())})"

    @property
    def rejected(self) -> list[MethodAttempt]:
        return [a for a in self.attempts if not a.chosen]

    @property
    def path(self) -> str:
        """``fetch(bottle, workbench) > get(bottle) > approach(bottle)``."""
        return " > ".join(self._lineage())

    def short_path(self, keep: int = 3) -> str:
        """The path with the middle left out when it is deep (for one-line messages)."""
        names = self._lineage()
        if len(names) <= 2 * keep + 1:
            return " > ".join(names)
        return " > ".join([*names[:keep], f"... {len(names) - 2 * keep} more ...", *names[-keep:]])

    def _lineage(self) -> list[str]:
        names = []
        node: TaskNode | None = self
        while node is not None and node.kind != "mission":
            names.append(node.call)
            node = node.parent
        return names[::-1]

    def walk(self) -> Iterator[TaskNode]:
        """This node and every descendant, depth first, parents first (no recursion)."""
        stack = [self]
        while stack:
            node = stack.pop()
            yield node
            stack.extend(reversed(node.children))

    def primitives(self) -> list[TaskNode]:
        return [n for n in self.walk() if n.kind == "primitive"]

    def reset(self) -> None:
        """Forget a refinement the planner backed out of."""
        self.children = []
        self.method = None
        self.attempts = []
        self.skill_args = None
        self.skip_if = None
        self.changes = None
        self.step = None
        self.status = "pending"
        self.failure = None


@dataclass(frozen=True)
class PlanStats:
    expansions: int
    backtracks: int
    seconds: float
    max_depth: int

    def to_dict(self) -> dict[str, Any]:
        return {"expansions": self.expansions, "backtracks": self.backtracks,
                "seconds": round(self.seconds, 6), "max_depth": self.max_depth}


@dataclass(eq=False)
class Plan:
    """A plan: the task tree under ``root`` (a ``mission`` node whose children are the tasks
    asked for), the predicted final ``state``, and search statistics."""

    root: TaskNode
    state: State
    stats: PlanStats
    domain: str = ""

    @property
    def tasks(self) -> list[TaskNode]:
        return list(self.root.children)

    def primitives(self) -> list[TaskNode]:
        """The steps in order: primitive nodes, each with ``skill`` and ``skill_args``."""
        return self.root.primitives()

    def to_dict(self) -> dict[str, Any]:
        return {"ok": True, "domain": self.domain, **tree_to_dict(self.root),
                "state": self.state.to_dict(), "stats": self.stats.to_dict()}

    def __len__(self) -> int:
        return len(self.primitives())


def tree_to_dict(root: TaskNode) -> dict[str, Any]:
    """``tasks``, ``steps`` and ``nodes`` (a flat table, ids in depth-first order)."""
    ids = {id(node): i for i, node in enumerate(root.walk())}
    nodes: list[dict[str, Any]] = []
    steps: list[dict[str, Any]] = []
    for node in root.walk():
        entry: dict[str, Any] = {
            "id": ids[id(node)],
            "parent": ids[id(node.parent)] if node.parent is not None else None,
            "kind": node.kind,
            "task": node.call,
            "name": node.name,
            "args": jsonable(node.args),
            "status": node.status,
        }
        if node.kind == "compound":
            entry["method"] = node.method
            entry["rejected"] = [a.to_dict() for a in node.rejected]
        if node.kind == "primitive":
            entry.update(step=node.step, skill=node.skill, skill_args=jsonable(node.skill_args),
                         optional=node.optional, skip_if=node.skip_if,
                         effects={k: jsonable(v) for k, v in node.changes or []})
            if node.status == "planned":
                steps.append({"step": node.step, "task": node.call, "skill": node.skill,
                              "args": jsonable(node.skill_args), "optional": node.optional,
                              "skip_if": node.skip_if, "node": entry["id"], "ack": node.ack})
        if node.failure is not None:
            entry["failure"] = node.failure.to_dict()
        entry["children"] = [ids[id(c)] for c in node.children]
        if node.source is not None:
            entry["where"] = str(node.source)
        nodes.append(entry)
    return {"tasks": [c.call for c in root.children], "steps": steps, "nodes": nodes}


class PlanningFailed(StuartError):
    """No plan exists for the tasks from the start state. ``failure`` says why (nested), ``root``
    is the task tree as far as the search got when it gave up."""

    def __init__(self, failure: Failure, root: TaskNode, stats: PlanStats) -> None:
        self.failure = failure
        self.root = root
        self.stats = stats
        tasks = ", ".join(c.call for c in root.children)
        super().__init__(f"no plan for {tasks}:\n" + "\n".join("  " + line for line in failure.lines()))
        self.reason = str(failure)  # the failure alone; str(self) adds the tasks asked for

    def to_dict(self) -> dict[str, Any]:
        return {"ok": False, "reason": self.failure.headline(), "failure": self.failure.to_dict(),
                **tree_to_dict(self.root), "stats": self.stats.to_dict()}


class PlanningBudgetExceeded(StuartError):
    """The search ran out of its time or expansion budget; the attributes say how far it got."""

    def __init__(self, limit: str, budget: float, stats: PlanStats, steps: int, current: str) -> None:
        self.limit = limit  # "expansions" | "seconds"
        self.budget = budget
        self.stats = stats
        self.steps = steps  # primitive steps planned on the branch being explored
        self.current = current  # the task being refined when the budget ran out
        self.expansions = stats.expansions
        self.seconds = stats.seconds
        what = "expansion budget" if limit == "expansions" else "time budget"
        super().__init__(
            f"planning stopped: {what} of {budget:g} {limit} used up after {stats.expansions} expansions, "
            f"{stats.backtracks} backtracks, {stats.seconds:.3f} s; {steps} primitive steps planned so far, "
            f"depth {stats.max_depth}; working on {current}")

    def to_dict(self) -> dict[str, Any]:
        return {"ok": False, "reason": str(self), "limit": self.limit, "budget": self.budget, "steps": self.steps,
                "current": self.current, "stats": self.stats.to_dict()}
