"""The HTN domain: tasks, methods and primitives read from YAML, checked once, compiled once.

A domain file (see docs/htn.md) declares

- ``state``: the state variables expressions may read, with defaults;
- ``primitives``: tasks bound to one skill of :mod:`stuart_bt.core.catalogue`, with skill arguments,
  preconditions and effects on the symbolic state;
- ``tasks``: compound tasks with ordered methods, each a precondition and ordered subtasks.

Expressions are :mod:`stuart_bt.core.expr` expressions (safe, never ``eval``'d) whose names are the
task's parameters, loop variables and state variables. One extension: an index may be a name,
``objects[obj]``: the index is evaluated first and put into the expression as a constant, which
is what the expression language accepts. Everything is checked when the file is loaded (unknown
tasks, skills, skill parameters, names, hooks, bad expressions) and reported all at once as
``file:line:column: message``, like the tree loader (:mod:`stuart_bt.tree.loader`).
"""

from __future__ import annotations

import ast
import copy
import json
import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from ..core import expr as bbexpr
from ..core.catalogue import LEAVES, SKILLS  # primitives bind to skill leaves (daemon leaves, wait, stop)
from ..core.errors import StuartError
from ..core.suggest import did_you_mean
from ..core.world import WorldState
from ..tree import yaml_source as ys
from ..tree.errors import ErrorLog, TreeLoadError
from ..tree.spec import Location
from .hooks import Hook, HookRegistry
from .state import State

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
RESERVED = {"true", "false", "null", "True", "False", "None", "len", "abs", "min", "max", "round"}
_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
_BARE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
MISSING: Any = type("Missing", (), {"__repr__": lambda self: "<missing>"})()
TOP_KEYS = ("domain", "description", "state", "primitives", "tasks", "ack_with")
PRIMITIVE_KEYS = ("doc", "params", "skill", "args", "pre", "effects", "remove", "optional", "skip_if")
TASK_KEYS = ("doc", "params", "intent", "ack", "methods")
METHOD_KEYS = ("name", "doc", "pre", "do", "ack")


class DomainLoadError(TreeLoadError):
    """The domain file could not be loaded; ``errors`` lists every problem, in reading order."""


class TaskArgumentError(StuartError, ValueError):
    """A task called with the wrong arguments, an unknown task, or task text that does not parse."""


# -- task values --------------------------------------------------------------------------------------
@dataclass(frozen=True)
class TaskCall:
    """A task and its argument values: what a user asks for, or one subtask of a method."""

    name: str
    args: tuple[Any, ...] = ()
    kwargs: tuple[tuple[str, Any], ...] = ()

    def __str__(self) -> str:
        parts = [format_value(a) for a in self.args] + [f"{k}={format_value(v)}" for k, v in self.kwargs]
        return f"{self.name}({', '.join(parts)})"


def format_value(value: Any) -> str:
    """A value as task text: bare words stay bare, other text is quoted, null/true/false."""
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, str):
        return value if _BARE.match(value) and value not in RESERVED else repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(format_value(v) for v in value) + "]"
    return str(value)


# -- compiled expressions ----------------------------------------------------------------------------
Lookup = Callable[[str], Any]


class _CompileError(Exception):
    def __init__(self, message: str, column: int = 1) -> None:
        super().__init__(message)
        self.message = message
        self.column = column


@dataclass(frozen=True)
class Scope:
    """The names an expression may read: parameters and loop variables (bound values) and
    state variables."""

    owner: str
    bound: tuple[str, ...]
    state_vars: frozenset[str]

    def check(self, name: str) -> str | None:
        head = name.split(".")[0]
        if head in self.bound or head in self.state_vars or head in RESERVED:
            return None
        names = [*self.bound, *self.state_vars]
        params = f" ({', '.join(self.bound)})" if self.bound else ""
        return (f"unknown name {head!r}: not a parameter of {self.owner}{params} nor a state variable"
                f"{did_you_mean(head, names)}")

    def with_bound(self, *names: str) -> Scope:
        return Scope(self.owner, (*self.bound, *names), self.state_vars)


class Expr:
    """An expression compiled once. Names are looked up through a ``Lookup``; ``a[name]``
    indexes are evaluated first and substituted as constants (cached per value)."""

    __slots__ = ("_cache", "_holes", "_names", "_plain", "_template", "text")

    def __init__(self, text: str, plain: bbexpr.Expression | None, template: ast.expr | None,
                 holes: list[Expr], names: list[str]) -> None:
        self.text = text
        self._plain = plain
        self._template = template
        self._holes = holes
        self._cache: dict[tuple[Any, ...], bbexpr.Expression] = {}
        self._names = names

    @property
    def names(self) -> list[str]:
        """Dotted names read, index expressions included, in order of appearance."""
        return self._names

    def evaluate(self, lookup: Lookup) -> Any:
        """The value; raises :class:`stuart_bt.core.expr.ExprError` with a readable message."""
        try:
            return self._expression(lookup).evaluate(lookup)
        except bbexpr.ExprError as e:
            raise bbexpr.ExprError(e.message.replace("blackboard has no key", "no entry"), e.column) from None

    def instantiated(self, lookup: Lookup) -> str:
        """The text with ``a[name]`` indexes filled in, e.g. ``objects['bottle']``."""
        try:
            return self._expression(lookup).text
        except bbexpr.ExprError:
            return self.text

    def _expression(self, lookup: Lookup) -> bbexpr.Expression:
        if self._plain is not None:
            return self._plain
        values = tuple(h.evaluate(lookup) for h in self._holes)
        key = tuple((type(v), v) for v in values)
        for v in values:
            if not (v is None or isinstance(v, (str, int, float, bool))):
                raise bbexpr.ExprError(f"an index must be text or a number, got {format_value(v)} in {self.text!r}")
        found = self._cache.get(key)
        if found is None:
            tree = copy.deepcopy(self._template)
            assert tree is not None
            for node in ast.walk(tree):
                index = getattr(node, "_hole", None)
                if index is not None:
                    node.slice = ast.Constant(values[index])  # type: ignore[attr-defined]
            found = bbexpr.parse(ast.unparse(tree))
            if len(self._cache) > 1024:
                self._cache.clear()
            self._cache[key] = found
        return found

    def __repr__(self) -> str:
        return f"Expr({self.text!r})"


def compile_expr(text: str, scope: Scope) -> Expr:
    """Compile ``text`` for ``scope``; raises ``_CompileError`` (column 1-based in ``text``)."""
    if not isinstance(text, str) or not text.strip():
        raise _CompileError("expression is empty")
    text = text.strip()
    try:
        tree = ast.parse(text, mode="eval").body
    except SyntaxError as e:
        raise _CompileError(f"syntax error in expression {text!r}: {e.msg}", e.offset or 1) from None
    except (RecursionError, MemoryError, ValueError):
        raise _CompileError("expression too complex") from None
    holes: list[Expr] = []
    _Holes(text, scope, holes).visit(tree)
    try:
        if holes:
            plain = None
            checked = bbexpr.parse(ast.unparse(tree))
        else:
            plain = checked = bbexpr.parse(text)
    except bbexpr.ExprError as e:
        raise _CompileError(f"{e.message} in {text!r}", e.column if not holes else 1) from None
    names = list(checked.names)
    for name in names:
        problem = scope.check(name)
        if problem:
            raise _CompileError(problem, _column_of(text, name.split(".")[0]))
    for hole in holes:
        names += [n for n in hole.names if n not in names]
    return Expr(text, plain, tree if holes else None, holes, names)


class _Holes(ast.NodeTransformer):
    """Replace every non-constant index by a numbered placeholder; compile the index itself."""

    def __init__(self, text: str, scope: Scope, holes: list[Expr]) -> None:
        self.text = text
        self.scope = scope
        self.holes = holes

    def visit_Subscript(self, node: ast.Subscript) -> ast.AST:
        node.value = self.visit(node.value)
        if isinstance(node.slice, ast.Slice):
            raise _CompileError("slices such as a[1:] are not allowed; use a for loop", node.slice.col_offset + 1)
        if not isinstance(node.slice, ast.Constant):
            source = ast.get_source_segment(self.text, node.slice) or ast.unparse(node.slice)
            try:
                self.holes.append(compile_expr(source, self.scope))
            except _CompileError as e:
                raise _CompileError(e.message, node.slice.col_offset + e.column) from None
            node._hole = len(self.holes) - 1  # type: ignore[attr-defined]
            node.slice = ast.Constant(0)
        return node


def _column_of(text: str, name: str) -> int:
    m = re.search(rf"\b{re.escape(name)}\b", text)
    return m.start() + 1 if m else 1


def make_lookup(bound: Mapping[str, Any], state: Mapping[str, Any]) -> Lookup:
    """Names resolve to bound parameters first, then to state variables; dots reach inside."""

    def lookup(dotted: str) -> Any:
        head, dot, rest = dotted.partition(".")
        value = bound[head] if head in bound else state[head]
        return bbexpr.resolve_dotted(value, rest) if dot else value

    return lookup


def short(value: Any, limit: int = 6) -> str:
    """A value as the explanation shows it: mappings by their keys unless small, long lists cut."""
    if isinstance(value, dict):
        if len(value) <= 4 and all(not isinstance(v, (dict, list, tuple)) for v in value.values()):
            return "{" + ", ".join(f"{k}: {short(v) if isinstance(v, float) else format_value(v)}"
                                   for k, v in value.items()) + "}"
        keys = [str(k) for k in value]
        more = f", +{len(keys) - limit} more" if len(keys) > limit else ""
        return "{" + ", ".join(keys[:limit]) + more + "}"
    if isinstance(value, (list, tuple)):
        more = f", +{len(value) - limit} more" if len(value) > limit else ""
        return "[" + ", ".join(short(v) for v in value[:limit]) + more + "]"
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, float):
        return f"{round(value, 4):g}"
    return format_value(value)


# -- conditions, values, templates ----------------------------------------------------------------------
@dataclass(frozen=True)
class ClauseFailure:
    """Why one clause of a precondition does not hold: the clause, the values it read, a hint."""

    clause: str
    values: tuple[tuple[str, str], ...] = ()
    verdict: str = "is false"  # or "returned false", "could not be evaluated: ..."
    hint: str = ""  # e.g. "(did you mean 'kitchen'?)"

    def __str__(self) -> str:
        shown = f" ({', '.join(f'{k}={v}' for k, v in self.values)})" if self.values else ""
        hint = f" {self.hint}" if self.hint else ""
        return f"{self.clause} {self.verdict}{shown}{hint}"

    def to_dict(self) -> dict[str, Any]:
        return {"clause": self.clause, "verdict": self.verdict, "values": dict(self.values), "hint": self.hint}


@dataclass
class Clause:
    """One conjunct of a precondition: an expression or a condition hook call."""

    text: str
    expr: Expr | None = None
    hook: Hook | None = None
    hook_args: dict[str, Value] = field(default_factory=dict)
    membership: tuple[Expr, Expr] | None = None  # `x in y`: for "did you mean"
    location: Location | None = None

    def check(self, lookup: Lookup, state: State) -> ClauseFailure | None:
        if self.hook is not None:
            return self._check_hook(lookup, state)
        assert self.expr is not None
        try:
            if self.expr.evaluate(lookup):
                return None
        except bbexpr.ExprError as e:
            return ClauseFailure(self.text, self._values(lookup), f"could not be evaluated: {e.message}")
        return ClauseFailure(self.text, self._values(lookup), hint=self._suggestion(lookup))

    def _check_hook(self, lookup: Lookup, state: State) -> ClauseFailure | None:
        assert self.hook is not None
        try:
            args = {k: v.evaluate(lookup, state) for k, v in self.hook_args.items()}
        except bbexpr.ExprError as e:
            return ClauseFailure(self.text, (), f"could not be evaluated: {e.message}")
        call = f"{self.hook.name}({', '.join(f'{k}={short(v)}' for k, v in args.items())})"
        try:
            if self.hook(state, **args):
                return None
        except Exception as e:  # noqa: BLE001 - a hook bug rejects the method and says so
            return ClauseFailure(f"hook {call}", (), f"could not be evaluated: raised {type(e).__name__}: {e}")
        return ClauseFailure(f"hook {call}", (), "returned false")

    def _values(self, lookup: Lookup) -> tuple[tuple[str, str], ...]:
        assert self.expr is not None
        out = []
        for name in self.expr.names:
            try:
                out.append((name, short(lookup(name))))
            except (KeyError, IndexError, TypeError):
                out.append((name, "<missing>"))
        instantiated = self.expr.instantiated(lookup)
        if instantiated != self.expr.text:
            out.append(("as evaluated", instantiated))
        return tuple(out)

    def _suggestion(self, lookup: Lookup) -> str:
        if self.membership is None:
            return ""
        try:
            needle = self.membership[0].evaluate(lookup)
            haystack = self.membership[1].evaluate(lookup)
        except bbexpr.ExprError:
            return ""
        if isinstance(needle, str) and isinstance(haystack, (dict, list, tuple)):
            return did_you_mean(needle, [str(h) for h in haystack]).strip()
        return ""


def check_all(clauses: Sequence[Clause], lookup: Lookup, state: State) -> ClauseFailure | None:
    """The first clause that does not hold, or None when all do (clauses are tried in order)."""
    for clause in clauses:
        failure = clause.check(lookup, state)
        if failure is not None:
            return failure
    return None


@dataclass
class Value:
    """Where a skill argument or an effect's value comes from: a literal, an expression, a
    function hook or a text template (``{format: "Here is the {names[place]}"}``)."""

    kind: str  # "literal" | "expr" | "hook" | "format"
    text: str
    literal: Any = None
    expr: Expr | None = None
    hook: Hook | None = None
    hook_args: dict[str, Value] = field(default_factory=dict)
    template: list[str | Expr] = field(default_factory=list)

    def evaluate(self, lookup: Lookup, state: State) -> Any:
        if self.kind == "literal":
            return self.literal
        if self.kind == "expr":
            assert self.expr is not None
            return self.expr.evaluate(lookup)
        if self.kind == "format":
            return render_template(self.template, lookup)
        assert self.hook is not None
        args = {k: v.evaluate(lookup, state) for k, v in self.hook_args.items()}
        try:
            return self.hook(state, **args)
        except Exception as e:  # noqa: BLE001 - reported as the step's failure, with the hook's name
            raise bbexpr.ExprError(f"hook {self.hook.name} raised {type(e).__name__}: {e}") from None


def render_template(parts: Sequence[str | Expr], lookup: Lookup) -> str:
    out = []
    for part in parts:
        if isinstance(part, str):
            out.append(part)
        else:
            value = part.evaluate(lookup)
            out.append(f"{value:g}" if isinstance(value, float) else str(value))
    return "".join(out)


def parse_template(text: str, scope: Scope) -> list[str | Expr]:
    """``"Navigating to the {names[place]}"`` -> text and expressions; ``{{``/``}}`` are braces."""
    parts: list[str | Expr] = []
    buf: list[str] = []
    i = 0
    while i < len(text):
        c = text[i]
        if c in "{}" and text[i:i + 2] in ("{{", "}}"):
            buf.append(c)
            i += 2
            continue
        if c == "}":
            raise _CompileError("a single '}' in a template; write '}}' for a brace", i + 1)
        if c == "{":
            end = text.find("}", i + 1)
            if end < 0:
                raise _CompileError("'{' without a closing '}' in a template", i + 1)
            if buf:
                parts.append("".join(buf))
                buf = []
            try:
                parts.append(compile_expr(text[i + 1:end], scope))
            except _CompileError as e:
                raise _CompileError(e.message, i + 1 + e.column) from None
            i = end + 1
            continue
        buf.append(c)
        i += 1
    if buf:
        parts.append("".join(buf))
    return parts


@dataclass
class SkipIf:
    """A run-time guard for the compiler: a blackboard expression in which the step's parameters
    are replaced by their values when the step is planned (``'keys' in world.objects``)."""

    text: str
    tree: ast.expr
    params: frozenset[str]

    def render(self, bound: Mapping[str, Any]) -> str:
        return ast.unparse(_FillParams(self.params, bound).visit(copy.deepcopy(self.tree)))


class _FillParams(ast.NodeTransformer):
    def __init__(self, params: frozenset[str], bound: Mapping[str, Any]) -> None:
        self.params = params
        self.bound = bound

    def visit_Name(self, node: ast.Name) -> ast.AST:
        value = self.bound.get(node.id, MISSING)
        if node.id in self.params and (value is None or isinstance(value, (str, int, float, bool))):
            return ast.copy_location(ast.Constant(value), node)
        return node


# -- definitions --------------------------------------------------------------------------------------
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


# -- the domain ---------------------------------------------------------------------------------------
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
        """A task value: a TaskCall, task text, ``[name, *args]``, or a TaskIntent mapping."""
        if isinstance(value, TaskCall):
            return value
        if isinstance(value, str):
            calls = self.parse_tasks(value)
            if len(calls) != 1:
                raise TaskArgumentError(f"expected one task, got {len(calls)} in {value!r}")
            return calls[0]
        if isinstance(value, (list, tuple)) and value and isinstance(value[0], str):
            return TaskCall(value[0], tuple(value[1:]))
        if (isinstance(value, dict) and "action" in value) or hasattr(value, "action"):
            return self.calls_from_intents([value])[0]
        raise TaskArgumentError(f"not a task: {format_value(value)}")

    # inputs ------------------------------------------------------------------------------------------
    def parse_tasks(self, text: str) -> list[TaskCall]:
        """Tasks from text: ``fetch(bottle, workbench)``, several separated by ``;``, or a JSON
        list of TaskIntents ``[{"action": "navigate_to_marker", "target": "kitchen"}]``."""
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


def parse_task_text(text: str) -> list[TaskCall]:
    """``fetch(bottle, workbench); greet`` -> TaskCalls. Bare words are text, numbers are numbers,
    ``[...]`` lists, nested calls task values; quote names with spaces: ``gesture('high wave')``."""
    try:
        module = ast.parse(text.strip().replace("\n", ";") or "pass")
    except SyntaxError as e:
        hint = " (quote names with spaces: gesture('high wave'))" if "comma" in (e.msg or "") else ""
        raise TaskArgumentError(f"cannot read task {text!r}: {e.msg} at column {e.offset}{hint}") from None
    calls: list[TaskCall] = []
    for stmt in module.body:
        if not isinstance(stmt, ast.Expr):
            raise TaskArgumentError(f"cannot read task {text!r}: expected task(args), e.g. fetch(bottle, workbench)")
        items = stmt.value.elts if isinstance(stmt.value, ast.List) else [stmt.value]
        for item in items:
            calls.append(_call_from_ast(item, text))
    if not calls:
        raise TaskArgumentError("no task given")
    return calls


def _call_from_ast(node: ast.expr, text: str) -> TaskCall:
    if isinstance(node, ast.Name):
        return TaskCall(node.id)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
        args = tuple(_value_from_ast(a, text) for a in node.args)
        kwargs = tuple((k.arg, _value_from_ast(k.value, text)) for k in node.keywords if k.arg)
        if any(k.arg is None for k in node.keywords):
            raise TaskArgumentError(f"cannot read task {text!r}: '**' is not allowed")
        return TaskCall(node.func.id, args, kwargs)
    raise TaskArgumentError(f"cannot read task {text!r}: expected task(args) at column {node.col_offset + 1}, "
                            f"got {ast.get_source_segment(text, node) or type(node).__name__!r}")


_WORDS = {"true": True, "false": False, "null": None, "True": True, "False": False, "None": None}


def _value_from_ast(node: ast.expr, text: str) -> Any:
    if isinstance(node, ast.Constant) and isinstance(node.value, (str, int, float, bool, type(None))):
        return node.value
    if isinstance(node, ast.Name):
        return _WORDS.get(node.id, node.id)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)) \
            and isinstance(node.operand, ast.Constant) and isinstance(node.operand.value, (int, float)) \
            and not isinstance(node.operand.value, bool):
        return -node.operand.value if isinstance(node.op, ast.USub) else node.operand.value
    if isinstance(node, (ast.List, ast.Tuple)):
        return [_value_from_ast(e, text) for e in node.elts]
    if isinstance(node, ast.Call):
        return _call_from_ast(node, text)
    raise TaskArgumentError(f"cannot read task {text!r}: {ast.get_source_segment(text, node)!r} at column "
                            f"{node.col_offset + 1} is not a value "
                            "(use a word, a number, 'quoted text', [a list] or a task)")


# -- loading ------------------------------------------------------------------------------------------
def load_domain(path: str | Path, hooks: HookRegistry | None = None) -> Domain:
    """Load and check a domain file; raises :class:`DomainLoadError` listing every problem."""
    file = str(path)
    return _Loader(file, hooks or HookRegistry()).load(ys.read_file(Path(path), file))


def load_domain_text(text: str, file: str = "<domain>", hooks: HookRegistry | None = None) -> Domain:
    return _Loader(file, hooks or HookRegistry()).load(ys.read_text(text, file))


class _Loader:
    def __init__(self, file: str, hooks: HookRegistry) -> None:
        self.file = file
        self.hooks = hooks
        self.log = ErrorLog()
        self.state_vars: dict[str, StateVarDef] = {}
        self.params: dict[str, list[ParamDef]] = {}
        self.kinds: dict[str, str] = {}  # task name -> "primitive" | "compound"
        self.ack_uses: list[tuple[Node, str]] = []

    # helpers -----------------------------------------------------------------------------------------
    def loc(self, node: Node, column: int = 1) -> Location:
        """Where ``node`` starts; for a one-line scalar, ``column`` within its text."""
        base = ys.location(self.file, node)
        if column > 1 and isinstance(node, ScalarNode) and node.start_mark.line == node.end_mark.line \
                and node.style in (None, "'", '"'):
            return Location(self.file, base.line, base.column + (0 if node.style is None else 1) + column - 1)
        return base

    def err(self, node: Node, message: str, path: str | None, column: int = 1) -> None:
        self.log.add(self.loc(node, column), message, path)

    def items(self, node: Node, path: str, allowed: Sequence[str] | None = None) -> dict[str, tuple[ScalarNode, Node]]:
        if not isinstance(node, MappingNode):
            self.err(node, f"expected a mapping, got {_shape(node)}", path)
            return {}
        out: dict[str, tuple[ScalarNode, Node]] = {}
        for key, value in ys.named_items(node, self.file, self.log, path):
            name = str(key.value)
            if allowed is not None and name not in allowed:
                self.err(key, f"unknown key {name!r}{did_you_mean(name, allowed)} "
                              f"(expected: {', '.join(allowed)})", path)
                continue
            out[name] = (key, value)
        return out

    def text(self, node: Node, path: str, what: str = "text") -> str | None:
        if isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:str":
            return str(node.value)
        self.err(node, f"expected {what}, got {_shape(node)}", path)
        return None

    def python(self, node: Node, path: str) -> Any:
        try:
            return ys.to_python(node, self.file)
        except ys.BadValue as e:
            self.log.add(e.error.location, e.error.message, path)
            return MISSING

    def name_ok(self, key: ScalarNode, what: str, path: str) -> bool:
        name = str(key.value)
        if not _IDENT.match(name) or name in RESERVED:
            self.err(key, f"{what} {name!r} must be a plain name (letters, digits, '_', not starting with '_' "
                          f"or a digit, not one of {', '.join(sorted(RESERVED))})", path)
            return False
        return True

    # the file ----------------------------------------------------------------------------------------
    def load(self, source: ys.Source) -> Domain:
        self.log.extend(source.errors)
        if source.root is None:
            if not source.errors:
                self.log.add(Location(self.file, 1, 1), "the domain file is empty")
            raise DomainLoadError(self.log.in_reading_order())
        top = self.items(source.root, "domain", TOP_KEYS)
        name = self.text(top["domain"][1], "domain") if "domain" in top else None
        if "domain" not in top:
            self.log.add(Location(self.file, 1, 1), "missing 'domain: NAME' at the top")
        description = self.text(top["description"][1], "description") if "description" in top else ""
        ack_with = (self.text(top["ack_with"][1], "ack_with") if "ack_with" in top else None) or "acknowledge"
        if "state" in top:
            self.read_state(top["state"][1])
        sections = self.declare_tasks(top)
        definitions = self.define_tasks(sections)
        self.check_ack(ack_with, definitions)
        if self.log:
            raise DomainLoadError(self.log.in_reading_order())
        return Domain(name or "domain", self.file, self.state_vars, definitions, self.hooks, ack_with,
                      description or "")

    def declare_tasks(self, top: dict[str, tuple[ScalarNode, Node]]) -> dict[str, dict[str, tuple[ScalarNode, Node]]]:
        """First pass: every task's name, kind and parameters, so bodies may name tasks that
        are defined later in the file."""
        sections: dict[str, dict[str, tuple[ScalarNode, Node]]] = {}
        for section in ("primitives", "tasks"):
            sections[section] = self.items(top[section][1], section) if section in top else {}
            for tname, (key, value) in sections[section].items():
                if not self.name_ok(key, "task", section):
                    continue
                if tname in self.kinds:
                    self.err(key, f"task {tname!r} is defined twice (as a primitive and as a compound task)", section)
                    continue
                self.kinds[tname] = "primitive" if section == "primitives" else "compound"
                self.params[tname] = self.read_params(value, f"{section}.{tname}")
        if not sections["tasks"] and not sections["primitives"]:
            self.log.add(Location(self.file, 1, 1), "the domain defines no tasks ('primitives:' and 'tasks:')")
        return sections

    def define_tasks(self, sections: dict[str, dict[str, tuple[ScalarNode, Node]]]) -> dict[str, Definition]:
        """Second pass: each declared task's body."""
        definitions: dict[str, Definition] = {}
        for tname, (key, value) in sections["primitives"].items():
            prim = self.read_primitive(tname, key, value) if self.kinds.get(tname) == "primitive" else None
            if prim is not None:
                definitions[tname] = prim
        for tname, (key, value) in sections["tasks"].items():
            task = self.read_task(tname, key, value) if self.kinds.get(tname) == "compound" else None
            if task is not None:
                definitions[tname] = task
        return definitions

    def read_state(self, node: Node) -> None:
        for vname, (key, value) in self.items(node, "state").items():
            path = f"state.{vname}"
            if not self.name_ok(key, "state variable", "state"):
                continue
            if isinstance(value, ScalarNode) and value.tag == "tag:yaml.org,2002:null":
                self.state_vars[vname] = StateVarDef(vname)
                continue
            spec = self.items(value, path, ("default", "doc"))
            default = self.python(spec["default"][1], path) if "default" in spec else None
            doc = (self.text(spec["doc"][1], path) or "") if "doc" in spec else ""
            self.state_vars[vname] = StateVarDef(vname, None if default is MISSING else default, doc)

    def read_params(self, task_node: Node, path: str) -> list[ParamDef]:
        if not isinstance(task_node, MappingNode):
            return []
        entries = {str(k.value): (k, v) for k, v in ys.named_items(task_node, self.file, ErrorLog(), path)}
        if "params" not in entries:
            return []
        ppath = f"{path}.params"
        params = []
        for pname, (key, value) in self.items(entries["params"][1], ppath).items():
            if not self.name_ok(key, "parameter", ppath):
                continue
            if pname in self.state_vars:
                self.err(key, f"parameter {pname!r} would hide the state variable of that name; rename it", ppath)
            if isinstance(value, MappingNode):
                spec = self.items(value, f"{ppath}.{pname}", ("type", "default", "doc"))
                tnode = spec.get("type", (None, None))[1]
                ptype = self.text(tnode, ppath, "a type name") if tnode is not None else "any"
                default = self.python(spec["default"][1], ppath) if "default" in spec else MISSING
                doc = (self.text(spec["doc"][1], ppath) or "") if "doc" in spec else ""
                where = tnode if tnode is not None else value
            else:
                ptype, default, doc, where = self.text(value, ppath, "a type name"), MISSING, "", value
            if ptype is None:
                continue
            if ptype not in PARAM_TYPES:
                self.err(where, f"unknown type {ptype!r}{did_you_mean(ptype, PARAM_TYPES)} "
                                f"(types: {', '.join(PARAM_TYPES)})", ppath)
                ptype = "any"  # keep the parameter: uses of it are not errors too
            params.append(ParamDef(pname, ptype, default, doc))
        return params

    def scope(self, tname: str) -> Scope:
        return Scope(f"{tname!r}", tuple(p.name for p in self.params.get(tname, [])), frozenset(self.state_vars))

    # compiled pieces ---------------------------------------------------------------------------------
    def compile(self, text: str, scope: Scope, node: Node, path: str, offset: int = 0) -> Expr | None:
        try:
            return compile_expr(text, scope)
        except _CompileError as e:
            self.err(node, e.message, path, offset + e.column)
            return None

    def read_conditions(self, node: Node, scope: Scope, path: str) -> list[Clause]:
        items = node.value if isinstance(node, SequenceNode) else [node]
        clauses: list[Clause] = []
        for item in items:
            if isinstance(item, MappingNode):
                clause = self.read_hook_clause(item, scope, path)
                if clause is not None:
                    clauses.append(clause)
                continue
            text = self.text(item, path, "an expression or {hook: name}")
            if text is None:
                continue
            clauses += self.split_clauses(text, scope, item, path)
        return clauses

    def split_clauses(self, text: str, scope: Scope, node: Node, path: str) -> list[Clause]:
        """``a and b and c`` becomes three clauses, so a rejection can name the one that failed."""
        stripped = text.strip()
        lead = len(text) - len(text.lstrip())
        try:
            tree = ast.parse(stripped, mode="eval").body
        except SyntaxError as e:
            self.err(node, f"syntax error in expression {stripped!r}: {e.msg}", path, lead + (e.offset or 1))
            return []
        parts = tree.values if isinstance(tree, ast.BoolOp) and isinstance(tree.op, ast.And) else [tree]
        clauses = []
        for part in parts:
            segment = ast.get_source_segment(stripped, part) or ast.unparse(part)
            expr = self.compile(segment, scope, node, path, lead + part.col_offset)
            if expr is None:
                continue
            membership = None
            if isinstance(part, ast.Compare) and len(part.ops) == 1 and isinstance(part.ops[0], ast.In):
                left = ast.get_source_segment(stripped, part.left) or ast.unparse(part.left)
                right = ast.get_source_segment(stripped, part.comparators[0]) or ast.unparse(part.comparators[0])
                try:
                    membership = (compile_expr(left, scope), compile_expr(right, scope))
                except _CompileError:
                    membership = None
            clauses.append(Clause(segment, expr, membership=membership, location=self.loc(node)))
        return clauses

    def read_hook_clause(self, node: MappingNode, scope: Scope, path: str) -> Clause | None:
        hook, args = self.read_hook_call(node, scope, path, "condition")
        if hook is None:
            return None
        shown = ", ".join(f"{k}={v.text}" for k, v in args.items())
        return Clause(f"hook {hook.name}({shown})", hook=hook, hook_args=args, location=self.loc(node))

    def read_hook_call(self, node: MappingNode, scope: Scope, path: str,
                       kind: str) -> tuple[Hook | None, dict[str, Value]]:
        spec = self.items(node, path, ("hook", "args"))
        if "hook" not in spec:
            self.err(node, "expected {hook: NAME, args: {...}}", path)
            return None, {}
        hname = self.text(spec["hook"][1], path, "a hook name")
        if hname is None:
            return None, {}
        hook = self.hooks.get(hname)
        where = spec["hook"][1]
        if hook is None:
            known = self.hooks.names(kind)
            self.err(where, f"unknown {kind} hook {hname!r}{did_you_mean(hname, known)} "
                            f"(registered: {', '.join(known) or 'none'})", path)
            return None, {}
        if hook.kind != kind:
            self.err(where, f"hook {hname!r} is a {hook.kind} hook; a {kind} hook is needed here", path)
            return None, {}
        args: dict[str, Value] = {}
        if "args" in spec:
            for aname, (akey, avalue) in self.items(spec["args"][1], f"{path}.args").items():
                if aname not in hook.params and not hook.accepts_any:
                    self.err(akey, f"hook {hname!r} has no parameter {aname!r}{did_you_mean(aname, hook.params)} "
                                   f"(parameters: {', '.join(hook.params) or 'none'})", path)
                    continue
                value = self.read_value(avalue, scope, f"{path}.args.{aname}")
                if value is not None:
                    args[aname] = value
        else:  # bind the hook's parameters by name from the task's parameters
            for pname in hook.params:
                if pname in scope.bound:
                    args[pname] = Value("expr", pname, expr=compile_expr(pname, scope))
        missing = [p for p in hook.required if p not in args]
        if missing:
            self.err(node, f"hook {hname!r} needs {', '.join(map(repr, missing))}"
                           f"{'' if 'args' in spec else ' (no task parameter of that name; give args:)'}", path)
            return None, {}
        return hook, args

    def read_value(self, node: Node, scope: Scope, path: str) -> Value | None:
        if isinstance(node, MappingNode):
            keys = {str(k.value) for k, _ in node.value if isinstance(k, ScalarNode)}
            if "hook" in keys:
                hook, args = self.read_hook_call(node, scope, path, "function")
                if hook is None:
                    return None
                return Value("hook", f"{hook.name}(...)", hook=hook, hook_args=args)
            if keys == {"format"}:
                fnode = node.value[0][1]
                text = self.text(fnode, path, "a template")
                if text is None:
                    return None
                try:
                    return Value("format", text, template=parse_template(text, scope))
                except _CompileError as e:
                    self.err(fnode, e.message, path, e.column)
                    return None
        if isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:str":
            expr = self.compile(str(node.value), scope, node, path)
            return None if expr is None else Value("expr", expr.text, expr=expr)
        literal = self.python(node, path)
        if literal is MISSING:
            return None
        return Value("literal", format_value(literal), literal=literal)

    def read_template(self, node: Node, scope: Scope, path: str) -> list[str | Expr] | None:
        text = self.text(node, path, "a text template")
        if text is None:
            return None
        try:
            return parse_template(text, scope)
        except _CompileError as e:
            self.err(node, e.message, path, e.column)
            return None

    # primitives --------------------------------------------------------------------------------------
    def read_primitive(self, tname: str, key: ScalarNode, node: Node) -> PrimitiveDef | None:
        path = f"primitives.{tname}"
        spec = self.items(node, path, PRIMITIVE_KEYS)
        if not isinstance(node, MappingNode):
            return None
        scope = self.scope(tname)
        skill = self.read_skill(tname, key, spec, path)
        if skill is None:
            return None
        args = self.read_skill_args(skill, key, spec, scope, path)
        pre = self.read_conditions(spec["pre"][1], scope, f"{path}.pre") if "pre" in spec else []
        effects = self.read_effects(spec["effects"][1], scope, path) if "effects" in spec else []
        remove = self.read_remove(spec["remove"][1], scope, path) if "remove" in spec else []
        optional = self.read_flag(spec["optional"][1], "optional", path) if "optional" in spec else False
        skip_if = self.read_skip_if(spec["skip_if"][1], scope, path) if "skip_if" in spec else None
        doc = (self.text(spec["doc"][1], path) or "") if "doc" in spec else ""
        return PrimitiveDef(tname, self.params.get(tname, []), skill, args, pre, effects, remove, optional, skip_if,
                            doc, self.loc(key))

    def read_skill(self, tname: str, key: ScalarNode, spec: dict[str, tuple[ScalarNode, Node]],
                   path: str) -> str | None:
        if "skill" not in spec:
            self.err(key, f"primitive {tname!r} needs 'skill:' (one of {', '.join(SKILLS)})", path)
            return None
        skill = self.text(spec["skill"][1], path, "a skill name")
        if skill is not None and skill not in SKILLS:
            self.err(spec["skill"][1], f"unknown skill {skill!r}{did_you_mean(skill, SKILLS)} "
                                       f"(skills: {', '.join(SKILLS)})", path)
            return None
        return skill

    def read_skill_args(self, skill: str, key: ScalarNode, spec: dict[str, tuple[ScalarNode, Node]], scope: Scope,
                        path: str) -> dict[str, Value] | Value:
        """The leaf's parameters: a mapping checked against the skill's catalogue entry, or one
        hook call that returns them (``args: {hook: ...}`` for a skill with no ``hook`` parameter)."""
        if "args" not in spec:
            problem = check_skill_args(skill, [])
            if problem:
                self.err(key, f"{problem}: give them under 'args:'", path)
            return {}
        anode = spec["args"][1]
        keys = {str(k.value) for k, _ in getattr(anode, "value", []) if isinstance(k, ScalarNode)}
        if isinstance(anode, MappingNode) and "hook" in keys and LEAVES[skill].param("hook") is None:
            hook_value = self.read_value(anode, scope, f"{path}.args")
            return hook_value if hook_value is not None else {}
        values: dict[str, Value] = {}
        complete = True
        for aname, (akey, avalue) in self.items(anode, f"{path}.args").items():
            if LEAVES[skill].param(aname) is None:
                self.err(akey, f"skill {skill!r} has no parameter {aname!r}"
                               f"{did_you_mean(aname, LEAVES[skill].param_names)} "
                               f"(parameters: {', '.join(LEAVES[skill].param_names) or 'none'})", path)
                complete = False
                continue
            value = self.read_value(avalue, scope, f"{path}.args.{aname}")
            if value is not None:
                values[aname] = value
            else:
                complete = False
        problem = check_skill_args(skill, values) if complete else None
        if problem:
            self.err(anode, problem, path)
        return values

    def read_effects(self, node: Node, scope: Scope, path: str) -> list[tuple[Target, Value]]:
        effects: list[tuple[Target, Value]] = []
        for tkey, (tnode, vnode) in self.items(node, f"{path}.effects").items():
            target = self.read_target(tkey, tnode, scope, f"{path}.effects")
            value = self.read_value(vnode, scope, f"{path}.effects.{tkey}")
            if target is not None and value is not None:
                effects.append((target, value))
        return effects

    def read_remove(self, node: Node, scope: Scope, path: str) -> list[Target]:
        remove: list[Target] = []
        for item in node.value if isinstance(node, SequenceNode) else [node]:
            text = self.text(item, f"{path}.remove", "a target such as objects[obj]")
            target = self.read_target(text, item, scope, f"{path}.remove") if text else None
            if target is not None and target.key is None:
                self.err(item, f"'remove' takes keys of mapping variables, e.g. {target.var}[obj]", f"{path}.remove")
            elif target is not None:
                remove.append(target)
        return remove

    def read_flag(self, node: Node, name: str, path: str) -> bool:
        value = self.python(node, path)
        if not isinstance(value, bool):
            self.err(node, f"'{name}' must be true or false", path)
            return False
        return value

    def read_target(self, text: str | None, node: Node, scope: Scope, path: str) -> Target | None:
        if text is None:
            return None
        try:
            tree = ast.parse(text.strip(), mode="eval").body
        except SyntaxError:
            tree = None
        if isinstance(tree, ast.Name):
            var, key = tree.id, None
        elif isinstance(tree, ast.Subscript) and isinstance(tree.value, ast.Name):
            var = tree.value.id
            index = ast.get_source_segment(text.strip(), tree.slice) or ast.unparse(tree.slice)
            key = self.compile(index, scope, node, path)
            if key is None:
                return None
        else:
            self.err(node, f"effect target {text!r} must be a state variable or one key of one: at, objects[obj]", path)
            return None
        if var not in self.state_vars:
            self.err(node, f"effect on {var!r}, which is not a declared state variable"
                           f"{did_you_mean(var, self.state_vars)}", path)
            return None
        return Target(var, key, text.strip())

    def read_skip_if(self, node: Node, scope: Scope, path: str) -> SkipIf | None:
        text = self.text(node, path, "a blackboard expression")
        if text is None:
            return None
        try:
            bbexpr.parse(text)
            tree = ast.parse(text.strip(), mode="eval").body
        except (bbexpr.ExprError, SyntaxError) as e:
            self.err(node, f"skip_if: {getattr(e, 'message', None) or e}", path, getattr(e, "column", 1))
            return None
        return SkipIf(text.strip(), tree, frozenset(scope.bound))

    # compound tasks ----------------------------------------------------------------------------------
    def read_task(self, tname: str, key: ScalarNode, node: Node) -> TaskDef | None:
        path = f"tasks.{tname}"
        spec = self.items(node, path, TASK_KEYS)
        if not isinstance(node, MappingNode):
            return None
        scope = self.scope(tname)
        ack = None
        if "ack" in spec:
            ack = self.read_template(spec["ack"][1], scope, f"{path}.ack")
            self.ack_uses.append((spec["ack"][1], path))
        intent = self.read_intent(spec["intent"][1], tname, f"{path}.intent") if "intent" in spec else None
        methods: list[MethodDef] = []
        if "methods" not in spec:
            self.err(key, f"task {tname!r} needs 'methods:' (a list of {{name, pre, do}})", path)
        else:
            mnode = spec["methods"][1]
            if not isinstance(mnode, SequenceNode) or not mnode.value:
                self.err(mnode, "'methods' must be a non-empty list of {name, pre, do}", path)
            else:
                seen: dict[str, Node] = {}
                for i, item in enumerate(mnode.value):
                    method = self.read_method(tname, item, scope, f"{path}.methods[{i}]")
                    if method is None:
                        continue
                    if method.name in seen:
                        self.err(item, f"method name {method.name!r} is used twice in task {tname!r}", path)
                        continue
                    seen[method.name] = item
                    methods.append(method)
        doc = (self.text(spec["doc"][1], path) or "") if "doc" in spec else ""
        return TaskDef(tname, self.params.get(tname, []), methods, ack, intent, doc, self.loc(key))

    def read_intent(self, node: Node, tname: str, path: str) -> dict[str, str]:
        if isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:null":
            return {}
        names = [p.name for p in self.params.get(tname, [])]
        out: dict[str, str] = {}
        for pname, (pkey, fnode) in self.items(node, path).items():
            if pname not in names:
                self.err(pkey, f"task {tname!r} has no parameter {pname!r}{did_you_mean(pname, names)}", path)
                continue
            fld = self.text(fnode, path, "a TaskIntent field name (target, x, y, yaw, raw_text)")
            if fld is not None:
                out[pname] = fld
        return out

    def read_method(self, tname: str, node: Node, scope: Scope, path: str) -> MethodDef | None:
        spec = self.items(node, path, METHOD_KEYS)
        if not isinstance(node, MappingNode):
            return None
        if "name" not in spec:
            self.err(node, "a method needs 'name:'", path)
            return None
        mname = self.text(spec["name"][1], path, "a method name")
        if mname is None:
            return None
        path = f"tasks.{tname}/{mname}"
        pre = self.read_conditions(spec["pre"][1], scope, f"{path}.pre") if "pre" in spec else []
        subtasks: list[Subtask] = []
        if "do" not in spec:
            self.err(node, f"method {mname!r} needs 'do:' (a list of subtasks; [] for nothing)", path)
        else:
            subtasks = self.read_subtasks(spec["do"][1], scope, f"{path}.do")
        ack = None
        if "ack" in spec:
            ack = self.read_template(spec["ack"][1], scope, f"{path}.ack")
            self.ack_uses.append((spec["ack"][1], path))
        doc = (self.text(spec["doc"][1], path) or "") if "doc" in spec else ""
        return MethodDef(mname, pre, subtasks, ack, doc, self.loc(node))

    def read_subtasks(self, node: Node, scope: Scope, path: str) -> list[Subtask]:
        flow = self.flow_calls(node)
        if flow is not None:
            calls = [self.read_call(text, node, scope, path, at) for text, at in flow]
            return [c for c in calls if c is not None]
        items = node.value if isinstance(node, SequenceNode) else [node]
        out: list[Subtask] = []
        for item in items:
            sub: Subtask | None
            if isinstance(item, MappingNode):
                keys = {str(k.value) for k, _ in item.value if isinstance(k, ScalarNode)}
                if "for" in keys:
                    sub = self.read_for(item, scope, path)
                elif "run" in keys:
                    sub = self.read_run(item, scope, path)
                else:
                    self.err(item, "a subtask is 'task(args)', {for: VAR, in: LIST, do: [...]} or {run: TASK}", path)
                    sub = None
            else:
                text = self.text(item, path, "a subtask such as go_to(place)")
                sub = self.read_call(text, item, scope, path) if text is not None else None
            if sub is not None:
                out.append(sub)
        return out

    def flow_calls(self, node: Node) -> list[tuple[str, Location]] | None:
        """``do: [go_to(place), step(x, y, yaw)]`` read from the source text as one list, since
        YAML alone would split ``step(x, y, yaw)`` at its commas. None: not such a list."""
        if not (isinstance(node, SequenceNode) and node.flow_style and node.value
                and all(isinstance(i, ScalarNode) and i.style is None for i in node.value)):
            return None
        start, end = node.start_mark, node.end_mark
        if not isinstance(start.buffer, str):
            return None
        raw = start.buffer[start.index:end.index]
        try:
            tree = ast.parse(raw, mode="eval").body
        except SyntaxError:
            return None
        if not isinstance(tree, ast.List):
            return None
        out = []
        for elt in tree.elts:
            text = ast.get_source_segment(raw, elt) or ast.unparse(elt)
            column = (start.column if elt.lineno == 1 else 0) + elt.col_offset + 1
            out.append((text, Location(self.file, start.line + elt.lineno, column)))
        return out

    def read_call(self, text: str, node: Node, scope: Scope, path: str,
                  at: Location | None = None) -> CallTemplate | None:
        stripped = text.strip()

        def report(message: str, path: str, column: int = 1) -> None:
            if at is not None:
                self.log.add(Location(at.file, at.line, at.column + column - 1), message, path)
            else:
                self.err(node, message, path, column)

        try:
            tree = ast.parse(stripped, mode="eval").body
        except SyntaxError as e:
            report(f"syntax error in subtask {stripped!r}: {e.msg}", path, e.offset or 1)
            return None
        if isinstance(tree, ast.Name):
            name, arg_nodes, kw_nodes = tree.id, [], []
        elif isinstance(tree, ast.Call) and isinstance(tree.func, ast.Name):
            name, arg_nodes, kw_nodes = tree.func.id, list(tree.args), list(tree.keywords)
        else:
            report(f"a subtask is written task(args), e.g. go_to(place); got {stripped!r}", path)
            return None
        if name not in self.kinds:
            report(f"unknown task {name!r}{did_you_mean(name, self.kinds)}", path)
            return None
        params = self.params.get(name, [])
        names = [p.name for p in params]
        signature = f"{name}({', '.join(names)})"
        ok = True
        if len(arg_nodes) > len(params):
            report(f"{signature} takes {len(params)} argument(s), got {len(arg_nodes)}", path)
            ok = False
        given = set(names[:len(arg_nodes)])
        for kw in kw_nodes:
            if kw.arg is None or kw.arg not in names:
                report(f"{signature} has no parameter {kw.arg!r}{did_you_mean(str(kw.arg), names)}", path,
                       kw.col_offset + 1)
                ok = False
            elif kw.arg in given:
                report(f"{signature}: {kw.arg!r} given twice", path, kw.col_offset + 1)
                ok = False
            given.add(str(kw.arg))
        missing = [p.name for p in params if p.required and p.name not in given]
        if missing and ok:
            report(f"{signature}: missing {', '.join(map(repr, missing))}", path)
            ok = False

        def compiled(part: ast.expr) -> Expr | None:
            try:
                return compile_expr(ast.get_source_segment(stripped, part) or ast.unparse(part), scope)
            except _CompileError as e:
                report(e.message, path, part.col_offset + e.column)
                return None

        args = [compiled(a) for a in arg_nodes]
        kwargs = {str(k.arg): compiled(k.value) for k in kw_nodes}
        if not ok or any(a is None for a in args) or any(v is None for v in kwargs.values()):
            return None
        return CallTemplate(name, args, kwargs, stripped, at or self.loc(node))  # type: ignore[arg-type]

    def read_for(self, node: MappingNode, scope: Scope, path: str) -> ForTemplate | None:
        spec = self.items(node, path, ("for", "in", "do"))
        if not {"for", "in", "do"} <= set(spec):
            self.err(node, "a loop is {for: VAR, in: LIST, do: [subtasks]}", path)
            return None
        var = self.text(spec["for"][1], path, "a variable name")
        if var is None:
            return None
        if not _IDENT.match(var) or var in RESERVED or var in scope.bound or var in scope.state_vars:
            self.err(spec["for"][1], f"loop variable {var!r} must be a new plain name", path)
            return None
        iter_text = self.text(spec["in"][1], path, "an expression giving a list")
        iterable = self.compile(iter_text, scope, spec["in"][1], path) if iter_text is not None else None
        body = self.read_subtasks(spec["do"][1], scope.with_bound(var), f"{path}.for_{var}")
        if iterable is None:
            return None
        return ForTemplate(var, iterable, body, self.loc(node))

    def read_run(self, node: MappingNode, scope: Scope, path: str) -> RunTemplate | None:
        spec = self.items(node, path, ("run",))
        text = self.text(spec["run"][1], path, "an expression giving a task") if "run" in spec else None
        expr = self.compile(text, scope, spec["run"][1], path) if text is not None else None
        return None if expr is None else RunTemplate(expr, self.loc(node))

    def check_ack(self, ack_with: str, definitions: dict[str, Definition]) -> None:
        if not self.ack_uses:
            return
        prim = definitions.get(ack_with)
        if isinstance(prim, PrimitiveDef) and len(prim.params) == 1 and prim.params[0].type == "string":
            return
        node, path = self.ack_uses[0]
        self.err(node, f"'ack' needs a primitive {ack_with!r} with one string parameter (the text to say); "
                       f"define it under 'primitives:' or name another with 'ack_with:'", path)


def _shape(node: Node) -> str:
    if isinstance(node, MappingNode):
        return "a mapping"
    if isinstance(node, SequenceNode):
        return "a list"
    if isinstance(node, ScalarNode):
        tag = node.tag.rsplit(":", 1)[-1]
        return f"{tag} {node.value!r}" if tag != "null" else "nothing (null)"
    return "something else"
