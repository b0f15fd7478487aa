"""Total-order HTN planning with backtracking, on an explicit stack.

Semantics a GTPyhop user recognises: tasks are refined depth first, left to right; a compound
task's methods are tried in the order written and a method applies when its precondition holds
in the current (predicted) state; its subtasks' argument expressions are evaluated when it is
chosen; a primitive task checks its precondition, then applies its effects, so later tasks plan
against the predicted state.

Unlike GTPyhop's default strategy, the search backtracks: when a task fails, the most recent
task that still has untried methods gets its next method (with the state, the steps and the
task tree put back as they were), even when the failure is in a later task, not below it. The
pending tasks are a linked list and the choice points a Python list, so a plan thousands of
steps deep needs no recursion. Undoing is by a trail (old values of the state variables
assigned) and a log of the tree nodes refined, so backing up costs what was done since the
choice point, never a copy of the whole state.

Budgets: ``max_expansions`` (tasks popped plus backtracks) and ``time_limit`` (seconds, checked
every 64 expansions) raise :class:`PlanningBudgetExceeded` with how far the search got. Given
the same domain, state and tasks, the result is always the same.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ..core.errors import StuartError
from ..core.expr import ExprError
from .domain import (
    MISSING,
    CallTemplate,
    Definition,
    Domain,
    ForTemplate,
    MethodDef,
    PrimitiveDef,
    RunTemplate,
    Subtask,
    TaskDef,
    check_skill_args,
)
from .expressions import check_all, make_lookup, render_template
from .plan import Failure, MethodAttempt, Plan, PlanningBudgetExceeded, PlanningFailed, PlanStats, TaskNode
from .state import State
from .values import TaskArgumentError, TaskCall, format_value

DEFAULT_MAX_EXPANSIONS = 500_000
DEFAULT_TIME_LIMIT = 2.0  # seconds
_CHECK_EVERY = 64

Agenda = tuple[TaskNode, "Agenda"] | None  # a linked list: (first, rest)


@dataclass
class _ChoicePoint:
    """A compound task with methods not yet tried, and how to put everything back."""

    node: TaskNode
    next_method: int
    rest: Agenda  # the tasks after this one, as they were
    trail_mark: int
    log_mark: int
    steps_len: int


class Planner:
    """Plans tasks in a :class:`Domain`.

    ``backtracking=False`` commits to the first applicable method, as GTPyhop's default
    strategy does (useful to compare; a failure is then final). ``acks=False`` leaves out the
    spoken acknowledgements the domain's ``ack:`` fields add.
    """

    def __init__(self, domain: Domain, *, backtracking: bool = True, max_expansions: int = DEFAULT_MAX_EXPANSIONS,
                 time_limit: float = DEFAULT_TIME_LIMIT, acks: bool = True) -> None:
        self.domain = domain
        self.backtracking = backtracking
        self.max_expansions = max_expansions
        self.time_limit = time_limit
        self.acks = acks

    def plan(self, calls: Sequence[TaskCall], state: State | Mapping[str, Any] | None = None) -> Plan:
        """Plan ``calls``, in order, from ``state`` (variables it does not set take the domain's
        declared defaults); ``state`` is not changed.

        ``calls`` is a list of :class:`TaskCall`, and nothing else: task text and TaskIntents are
        converted first, by name (:meth:`TaskCall.parse`, :meth:`Domain.calls_from_text`,
        :meth:`Domain.calls_from_intents`), so what a caller meant is never guessed from the
        shape of what it passed. Raises :class:`PlannerInputError` for any other shape,
        TaskArgumentError for tasks that do not exist or do not fit their parameters,
        PlanningFailed when no plan exists, PlanningBudgetExceeded when a budget runs out."""
        checked = _checked_calls(calls)
        start = self.domain.initial_state(overrides=state)  # declared variables it lacks take their defaults
        return _Search(self, checked, start).run()


class PlannerInputError(StuartError, TypeError):
    """The planner was given something other than a list of TaskCall: a caller's mistake, told
    with what was given and the converter that would make it a list of TaskCall."""

    code = "planner_input"


def _checked_calls(calls: object) -> list[TaskCall]:
    """``calls`` as a list, when it is a list (or tuple) of TaskCall; else PlannerInputError."""
    expected = "Planner.plan takes a list of TaskCall"
    if not isinstance(calls, (list, tuple)):
        raise PlannerInputError(f"{expected}; got {_given(calls)}")
    for i, item in enumerate(calls):
        if not isinstance(item, TaskCall):
            raise PlannerInputError(f"{expected}; item {i + 1} of the list is {_given(item)}")
    return list(calls)


def _given(value: object) -> str:
    """What was passed instead of a list of TaskCall, and the converter for it, if there is one."""
    shown = repr(value) if len(repr(value)) <= 80 else repr(value)[:77] + "..."
    if isinstance(value, str):
        return (f"task text {shown}: convert it with domain.calls_from_text(text) "
                f"(or [TaskCall.parse(text)] for one task)")
    if isinstance(value, TaskCall):
        return f"one TaskCall {value}: put it in a list, [call]"
    if (isinstance(value, Mapping) and "action" in value) or hasattr(value, "action"):
        return f"a TaskIntent {shown}: convert TaskIntents with domain.calls_from_intents(intents)"
    return f"{type(value).__name__} {shown}"


class _Search:
    def __init__(self, planner: Planner, calls: list[TaskCall], state: State) -> None:
        self.planner = planner
        self.domain = planner.domain
        self.state = state
        self.vars: dict[str, Any] = state._vars  # effects assign here; the trail puts old values back
        self.trail: list[tuple[str, Any]] = []
        self.log: list[TaskNode] = []  # every node refined, applied or failed, in order
        self.steps: list[TaskNode] = []
        self.choice_points: list[_ChoicePoint] = []
        self.expansions = 0
        self.backtracks = 0
        self.max_depth = 1
        self.started = time.perf_counter()
        self.root = TaskNode("mission", {}, "mission")
        for call in calls:
            defn, args = self.domain.bind(call)
            self.root.children.append(self.new_node(defn, args, self.root))

    # the loop ----------------------------------------------------------------------------------------
    def run(self) -> Plan:
        agenda: Agenda = None
        for node in reversed(self.root.children):
            agenda = (node, agenda)
        limit = self.planner.max_expansions
        deadline = self.started + self.planner.time_limit
        while agenda is not None:
            node, agenda = agenda
            self.expansions += 1
            if self.expansions > limit:
                self.over_budget("expansions", limit, node)
            if not self.expansions % _CHECK_EVERY and time.perf_counter() > deadline:
                self.over_budget("seconds", self.planner.time_limit, node)
            if node.kind == "primitive":
                failure = self.apply(node)
                if failure is None:
                    continue
            else:
                failure, agenda = self.refine(node, 0, agenda, fresh=True)
                if failure is None:
                    continue
            agenda = self.backtrack(failure)
        self.root.status = "planned"
        return Plan(self.root, self.state.copy(), self.stats(), self.domain.name)

    def stats(self) -> PlanStats:
        return PlanStats(self.expansions, self.backtracks, time.perf_counter() - self.started, self.max_depth)

    def over_budget(self, limit: str, budget: float, node: TaskNode) -> None:
        raise PlanningBudgetExceeded(limit, budget, self.stats(), len(self.steps), node.short_path())

    # compound tasks ----------------------------------------------------------------------------------
    def refine(self, node: TaskNode, first: int, rest: Agenda, fresh: bool) -> tuple[Failure | None, Agenda]:
        """Choose the first applicable method from ``first`` on; push its subtasks."""
        defn: TaskDef = node.definition
        if fresh:
            self.log.append(node)
        lookup = make_lookup(node.args, self.state)
        methods = defn.methods
        for i in range(first, len(methods)):
            method = methods[i]
            why = check_all(method.pre, lookup, self.state)
            if why is not None:
                node.attempts.append(MethodAttempt(method.name, False, "precondition", why, method.location))
                continue
            try:
                children = self.subtasks(node, defn, method, lookup)
            except (ExprError, TaskArgumentError) as e:
                node.attempts.append(MethodAttempt(method.name, False, "arguments", str(e), method.location))
                continue
            node.method = method.name
            node.children = children
            node.status = "planned"
            node.attempts.append(MethodAttempt(method.name, True, location=method.location))
            if self.planner.backtracking and i + 1 < len(methods):
                self.choice_points.append(
                    _ChoicePoint(node, i + 1, rest, len(self.trail), len(self.log), len(self.steps)))
            agenda = rest
            for child in reversed(children):
                agenda = (child, agenda)
            return None, agenda
        node.status = "failed"
        node.children = []
        node.method = None
        worked = any(not a.chosen and isinstance(a.reason, Failure) for a in node.attempts)
        message = "no method works" if worked else "no method applies"
        node.failure = Failure(node.call, node.path, "no_method", message, list(node.attempts), node)
        return node.failure, rest

    def subtasks(self, node: TaskNode, defn: TaskDef, method: MethodDef, lookup: Any) -> list[TaskNode]:
        children: list[TaskNode] = []
        ack = method.ack if method.ack is not None else defn.ack
        if ack is not None and self.planner.acks:
            ack_defn = self.domain.definitions[self.domain.ack_with]
            text = render_template(ack, lookup)
            child = self.new_node(ack_defn, {ack_defn.params[0].name: text}, node)
            child.ack = True
            children.append(child)
        self.build(method.subtasks, node.args, node, children)
        return children

    def build(self, templates: list[Subtask], bound: Mapping[str, Any], parent: TaskNode, out: list[TaskNode]) -> None:
        lookup = make_lookup(bound, self.state)
        for t in templates:
            if isinstance(t, CallTemplate):
                defn = self.domain.definitions[t.name]
                positional = [a.evaluate(lookup) for a in t.args]
                kwargs = {k: v.evaluate(lookup) for k, v in t.kwargs.items()}
                out.append(self.new_node(defn, self.domain.bind_args(defn, positional, kwargs), parent))
            elif isinstance(t, ForTemplate):
                items = t.iterable.evaluate(lookup)
                if not isinstance(items, (list, tuple)):
                    raise TaskArgumentError(
                        f"for {t.var} in {t.iterable.text}: expected a list, got {format_value(items)}")
                for item in items:
                    self.build(t.body, {**bound, t.var: item}, parent, out)
            elif isinstance(t, RunTemplate):
                defn, args = self.domain.bind(self.domain.to_call(t.expr.evaluate(lookup)))
                out.append(self.new_node(defn, args, parent))

    def new_node(self, defn: Definition, args: dict[str, Any], parent: TaskNode) -> TaskNode:
        depth = parent.depth + 1
        self.max_depth = max(self.max_depth, depth)
        return TaskNode(defn.name, args, defn.kind, parent, depth, source=defn.location, definition=defn)

    # primitive tasks ---------------------------------------------------------------------------------
    def apply(self, node: TaskNode) -> Failure | None:
        """Check the precondition, compute skill arguments and effects, apply the effects."""
        defn: PrimitiveDef = node.definition
        self.log.append(node)
        lookup = make_lookup(node.args, self.state)
        why = check_all(defn.pre, lookup, self.state)
        if why is not None:
            return self.fail(node, "precondition", f"precondition not met: {why}")
        what = "skill arguments"
        try:
            if isinstance(defn.args, dict):
                args = {k: v.evaluate(lookup, self.state) for k, v in defn.args.items()}
            else:
                args = defn.args.evaluate(lookup, self.state)
                if not isinstance(args, dict):
                    return self.fail(node, "effects", f"hook {defn.args.text} must return a mapping of skill "
                                                      f"arguments, got {format_value(args)}")
                problem = check_skill_args(defn.skill, args)
                if problem:
                    return self.fail(node, "effects", f"hook {defn.args.text}: {problem}")
            what = "effects"
            assigned = [(t, None if t.key is None else t.key.evaluate(lookup), v.evaluate(lookup, self.state))
                        for t, v in defn.effects]
            removed = [(t, t.key.evaluate(lookup)) for t in defn.remove if t.key is not None]
        except ExprError as e:
            return self.fail(node, "effects", f"cannot compute the {what}: {e.message}")
        changes: list[tuple[str, Any]] = []
        for target, key, value in assigned:
            if key is None:
                self.assign(target.var, value)
                changes.append((target.var, value))
                continue
            current = self.vars.get(target.var)
            if not isinstance(current, dict):
                return self.fail(node, "effects", f"effect {target.text}: {target.var} is not a mapping "
                                                  f"({format_value(current)})")
            updated = dict(current)
            updated[key] = value
            self.assign(target.var, updated)
            changes.append((f"{target.var}[{key!r}]", value))
        for target, key in removed:
            current = self.vars.get(target.var)
            if isinstance(current, dict) and key in current:
                updated = dict(current)
                del updated[key]
                self.assign(target.var, updated)
                changes.append((f"-{target.var}[{key!r}]", None))
        node.skill = defn.skill
        node.skill_args = args
        node.optional = defn.optional
        node.skip_if = defn.skip_if.render(node.args) if defn.skip_if is not None else None
        node.changes = changes
        node.status = "planned"
        self.steps.append(node)
        node.step = len(self.steps)
        return None

    def fail(self, node: TaskNode, kind: str, message: str) -> Failure:
        node.status = "failed"
        node.failure = Failure(node.call, node.path, kind, message, node=node)
        return node.failure

    def assign(self, var: str, value: Any) -> None:
        self.trail.append((var, self.vars.get(var, MISSING)))
        self.vars[var] = value

    # backing up --------------------------------------------------------------------------------------
    def backtrack(self, failure: Failure) -> Agenda:
        """Resume at the latest task with an untried method; raise PlanningFailed if none is left."""
        while self.choice_points:
            cp = self.choice_points.pop()
            self.backtracks += 1
            self.expansions += 1
            self.undo(cp)
            node = cp.node
            chosen = node.attempts[-1]
            chosen.chosen = False
            chosen.kind = "subtask" if _below(failure.node, node) else "later"
            chosen.reason = failure
            node.children = []
            node.method = None
            new_failure, agenda = self.refine(node, cp.next_method, cp.rest, fresh=False)
            if new_failure is None:
                return agenda
            failure = new_failure
        raise PlanningFailed(self.in_context(failure), self.root, self.stats())

    def in_context(self, failure: Failure) -> Failure:
        """The final failure as seen from the highest task that tried other methods first, so
        the reason lists every alternative the search gave up on, not only the last one."""
        node = failure.node.parent if failure.node is not None else None
        while node is not None and node.kind == "compound":
            if any(a.kind in ("subtask", "later") for a in node.rejected):
                attempts = [a if not a.chosen else MethodAttempt(a.method, False, "subtask", failure, a.location)
                            for a in node.attempts]
                failure = Failure(node.call, node.path, "no_method", "no method works", attempts, node)
            node = node.parent
        return failure

    def undo(self, cp: _ChoicePoint) -> None:
        trail, values = self.trail, self.vars
        while len(trail) > cp.trail_mark:
            var, old = trail.pop()
            if old is MISSING:
                values.pop(var, None)
            else:
                values[var] = old
        for node in self.log[cp.log_mark:]:
            node.reset()
        del self.log[cp.log_mark:]
        del self.steps[cp.steps_len:]


def _below(node: TaskNode | None, ancestor: TaskNode) -> bool:
    while node is not None:
        if node is ancestor:
            return True
        node = node.parent
    return False
