"""The HTN domain as the planner sees it: parameters, tasks with their methods, primitives bound
to skills, state variables, and :class:`Domain`, which binds task calls to them.

A domain file (see docs/htn.md) declares ``state`` (the variables expressions may read, with
defaults), ``primitives`` (tasks bound to one skill of :mod:`stuart_bt.core.catalogue`, with
skill arguments, preconditions and effects on the symbolic state) and ``tasks`` (compound tasks
with ordered methods, each a precondition and ordered subtasks). The htn package, bottom first:
:mod:`.values` (task calls and values as written), :mod:`.expressions` (compiled preconditions,
values and templates), this module (the model), the file readers (:mod:`.misnamed`,
:mod:`.read_yaml`, :mod:`.read_expressions`, :mod:`.read_primitives`, :mod:`.read_methods`,
and :mod:`.load` over them: reading and checking a file at file:line:column), :mod:`.planner`,
:mod:`.plan` and :mod:`.explain`.
"""

from __future__ import annotations

import copy
import json
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from ..core.catalogue import LEAVES  # primitives bind to skill leaves (daemon leaves, wait, stop)
from ..core.suggest import did_you_mean
from ..core.world import WorldState
from ..tree.spec import Location
from .expressions import Clause, Expr, SkipIf, Value
from .hooks import HookRegistry
from .state import State
from .values import MISSING, TaskArgumentError, TaskCall, format_value, parse_task_text

PARAM_TYPES: dict[str, str] = {
    "place": "a marker name",
    "object": "an object label",
    "string": "text",
    "gesture": "a gesture name",
    "number": "a number",
    "angle": "radians, counter-clockwise positive",
    "integer": "a whole number",
    "boolean": "true or false",
    "list": "a list",
    "places": "a list of marker names",
    "task": "a task, e.g. navigate_to_marker(kitchen)",
    "tasks": "a list of tasks",
    "any": "any value",
}



@dataclass(frozen=True)
class ParamDef:
    name: str
    type: str
    default: Any = MISSING
    doc: str = ""

    @property
    def required(self) -> bool:
        return self.default is MISSING


@dataclass
class CallTemplate:
    """A subtask ``name(arg, key=arg)``; arguments are expressions evaluated when the method is chosen."""

    name: str
    args: list[Expr]
    kwargs: dict[str, Expr]
    text: str
    location: Location | None


@dataclass
class ForTemplate:
    """``{for: var, in: list, do: [...]}``: the body once per element, ``var`` bound to it."""

    var: str
    iterable: Expr
    body: list[Subtask]
    location: Location | None


@dataclass
class RunTemplate:
    """``{run: expr}``: a task given as a value (``do_all``'s elements)."""

    expr: Expr
    location: Location | None

Subtask = CallTemplate | ForTemplate | RunTemplate


@dataclass
class MethodDef:
    name: str
    pre: list[Clause]
    subtasks: list[Subtask]
    ack: list[str | Expr] | None = None
    doc: str = ""
    location: Location | None = None


@dataclass
class TaskDef:
    """A compound task: methods tried in order; the first whose precondition holds is used."""

    name: str
    params: list[ParamDef]
    methods: list[MethodDef]
    ack: list[str | Expr] | None = None
    intent: dict[str, str] | None = None  # param -> TaskIntent field, when this task is an intent
    doc: str = ""
    location: Location | None = None
    kind = "compound"


@dataclass
class Target:
    """An effect's target: a whole state variable or one key of a mapping variable."""

    var: str
    key: Expr | None
    text: str


@dataclass
class PrimitiveDef:
    """A primitive task: one skill with arguments, a precondition and effects."""

    name: str
    params: list[ParamDef]
    skill: str
    args: dict[str, Value] | Value  # a Value here is a function hook returning the whole mapping
    pre: list[Clause] = field(default_factory=list)
    effects: list[tuple[Target, Value]] = field(default_factory=list)
    remove: list[Target] = field(default_factory=list)
    optional: bool = False
    skip_if: SkipIf | None = None
    doc: str = ""
    location: Location | None = None
    kind = "primitive"

Definition = TaskDef | PrimitiveDef


@dataclass(frozen=True)
class StateVarDef:
    name: str
    default: Any = None
    doc: str = ""


def check_skill_args(skill: str, keys: Iterable[str]) -> str | None:
    """Why these argument names cannot go to ``skill`` (unknown name, alternatives mixed,
    required one missing), or None."""
    spec = LEAVES[skill]
    keys = list(keys)
    for key in keys:
        if spec.param(key) is None:
            return f"skill {skill!r} has no parameter {key!r}{did_you_mean(key, spec.param_names)}"
    if spec.one_of:
        used = [g for g in spec.one_of if any(k in g for k in keys)]
        if len(used) != 1:
            groups = " | ".join("(" + ", ".join(g) + ")" for g in spec.one_of)
            what = "mixes" if used else "needs one of"
            return f"skill {skill!r} {what} the alternatives {groups}"
        group = used[0]
    else:
        group = tuple(p.name for p in spec.params)
    missing = [p for p in group if spec.param(p).required and p not in keys]  # type: ignore[union-attr]
    if missing:
        return f"skill {skill!r} needs {', '.join(map(repr, missing))}"
    return None


@dataclass
class Domain:
    name: str
    file: str
    state_vars: dict[str, StateVarDef]
    definitions: dict[str, Definition]
    hooks: HookRegistry
    ack_with: str = "acknowledge"
    description: str = ""

    def get(self, name: str) -> Definition | None:
        return self.definitions.get(name)

    @property
    def compound(self) -> dict[str, TaskDef]:
        return {n: d for n, d in self.definitions.items() if isinstance(d, TaskDef)}

    @property
    def primitives(self) -> dict[str, PrimitiveDef]:
        return {n: d for n, d in self.definitions.items() if isinstance(d, PrimitiveDef)}

    @property
    def intents(self) -> dict[str, TaskDef]:
        """Tasks a TaskIntent's ``action`` may name."""
        return {n: d for n, d in self.compound.items() if d.intent is not None}

    # binding -----------------------------------------------------------------------------------------
    def bind(self, call: TaskCall) -> tuple[Definition, dict[str, Any]]:
        """The definition and the parameter values for ``call``; raises TaskArgumentError."""
        defn = self.definitions.get(call.name)
        if defn is None:
            raise TaskArgumentError(f"unknown task {call.name!r}{did_you_mean(call.name, self.definitions)}")
        return defn, self.bind_args(defn, call.args, dict(call.kwargs))

    def bind_args(self, defn: Definition, args: Sequence[Any], kwargs: Mapping[str, Any]) -> dict[str, Any]:
        params = defn.params
        signature = f"{defn.name}({', '.join(p.name for p in params)})"
        if len(args) > len(params):
            raise TaskArgumentError(f"{signature} takes {len(params)} argument(s), got {len(args)}")
        bound: dict[str, Any] = {}
        for p, value in zip(params, args, strict=False):
            bound[p.name] = value
        names = [p.name for p in params]
        for key, value in kwargs.items():
            if key not in names:
                raise TaskArgumentError(f"{signature} has no parameter {key!r}{did_you_mean(key, names)}")
            if key in bound:
                raise TaskArgumentError(f"{signature}: {key!r} given twice")
            bound[key] = value
        out: dict[str, Any] = {}
        for p in params:
            if p.name not in bound or (bound[p.name] is None and not p.required):
                if p.required:
                    raise TaskArgumentError(f"{signature}: missing {p.name!r} ({PARAM_TYPES[p.type]})")
                out[p.name] = p.default
                continue
            out[p.name] = self.check_type(signature, p, bound[p.name])
        return out

    def check_type(self, where: str, p: ParamDef, value: Any) -> Any:
        t = p.type
        ok = True
        if t in ("place", "object", "string", "gesture"):
            ok = isinstance(value, str)
        elif t in ("number", "angle"):
            ok = isinstance(value, (int, float)) and not isinstance(value, bool)
        elif t == "integer":
            ok = isinstance(value, int) and not isinstance(value, bool)
        elif t == "boolean":
            ok = isinstance(value, bool)
        elif t == "list":
            ok = isinstance(value, (list, tuple))
        elif t == "places":
            ok = isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value)
        elif t == "task":
            return self.to_call(value)
        elif t == "tasks":
            if not isinstance(value, (list, tuple)):
                ok = False
            else:
                return [self.to_call(v) for v in value]
        if not ok:
            raise TaskArgumentError(f"{where}: {p.name!r} must be {PARAM_TYPES[t]}, got {format_value(value)}")
        return list(value) if isinstance(value, tuple) else value

    def to_call(self, value: Any) -> TaskCall:
        """A task value: a TaskCall, task text, ``[name, *args]``, or a TaskIntent mapping.

        Values of ``task``/``tasks`` parameters come from expressions and task text in all these
        shapes, so binding accepts each; the planner's own input does not (a list of TaskCall)."""
        if isinstance(value, TaskCall):
            return value
        if isinstance(value, str):
            calls = self.calls_from_text(value)
            if len(calls) != 1:
                raise TaskArgumentError(f"expected one task, got {len(calls)} in {value!r}")
            return calls[0]
        if isinstance(value, (list, tuple)) and value and isinstance(value[0], str):
            return TaskCall(value[0], tuple(value[1:]))
        if (isinstance(value, dict) and "action" in value) or hasattr(value, "action"):
            return self.calls_from_intents([value])[0]
        raise TaskArgumentError(f"not a task: {format_value(value)}")

    # inputs ------------------------------------------------------------------------------------------
    def calls_from_text(self, text: str) -> list[TaskCall]:
        """Tasks from text, for the planner (which takes only TaskCalls): ``fetch(bottle,
        workbench)``, several separated by ``;``, or a JSON list of TaskIntents
        ``[{"action": "navigate_to_marker", "target": "kitchen"}]`` (what ``stuart-bt plan`` is given)."""
        text = text.strip()
        if text[:1] in "[{":
            try:
                data = json.loads(text)
            except json.JSONDecodeError:
                data = None
            if isinstance(data, dict):
                data = [data]
            if isinstance(data, list) and all(isinstance(d, dict) for d in data):
                return self.calls_from_intents(data)
        return parse_task_text(text)

    def calls_from_intents(self, intents: Iterable[Any]) -> list[TaskCall]:
        """One task per TaskIntent (a mapping or an object with ``action``, ``target``, ``x``,
        ``y``, ``yaw``, ``raw_text``): the task named by ``action``, its parameters filled from
        the fields its ``intent:`` mapping names; absent or null fields take the defaults."""
        calls = []
        known = self.intents
        for i, item in enumerate(intents):
            get = item.get if isinstance(item, dict) else (lambda k, it=item: getattr(it, k, None))
            action = get("action")
            if not isinstance(action, str) or action not in known:
                raise TaskArgumentError(f"intent {i + 1}: unknown action {action!r}"
                                        f"{did_you_mean(str(action), known)} (known: {', '.join(known)})")
            mapping = known[action].intent or {}
            kwargs = tuple((param, get(fld)) for param, fld in mapping.items() if get(fld) is not None)
            calls.append(TaskCall(action, (), kwargs))
        return calls

    # start state -------------------------------------------------------------------------------------
    def initial_state(self, world: WorldState | None = None, *, speaker_at: Any = None,
                      overrides: Mapping[str, Any] | None = None) -> State:
        """Declared defaults, then what the world knows (pose, held, objects, markers), then
        ``overrides`` (e.g. a state file)."""
        values = {name: copy.deepcopy(v.default) for name, v in self.state_vars.items()}
        if world is not None:
            values.update(State.from_world(world, speaker_at=speaker_at))
        if overrides:
            values.update(overrides)
        return State(values)
