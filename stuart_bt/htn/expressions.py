"""The domain's compiled expressions: preconditions (clauses that say which value failed them),
argument values, templates (``"Going to {place}"``) and skip conditions, all checked and
compiled once when the domain loads, evaluated with :mod:`stuart_bt.core.expr`.
"""

from __future__ import annotations

import ast
import copy
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from ..core import expr as bbexpr
from ..core.suggest import did_you_mean
from ..tree.spec import Location
from .hooks import Hook
from .state import State
from .values import MISSING, RESERVED, format_value, short

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
