"""Blackboard expressions for guards, conditions and ``set``: parsed safely, never ``eval``'d.

Grammar (a small, side-effect-free subset of Python expressions)::

    battery > 20 and held == 'bottle'
    not world.holding
    visits.kitchen >= 2 or mode in ['tour', 'demo']
    len(queue) == 0

Names are blackboard keys; dots reach into nested values (dict keys or attributes). ``true``,
``false`` and ``null`` are accepted beside Python's spellings. Only literals, names, attribute
and constant-index access, arithmetic, comparisons, boolean operators, list/tuple literals and
the functions ``len abs min max round`` are allowed; anything else is a parse error that says
which construct and where. Evaluation walks the syntax tree with our own interpreter.
"""

from __future__ import annotations

import ast
import operator
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from .errors import StuartError

_CONSTANT_NAMES = {"true": True, "false": False, "null": None, "True": True, "False": False, "None": None}
_FUNCTIONS: dict[str, Callable[..., Any]] = {"len": len, "abs": abs, "min": min, "max": max, "round": round}
_BINARY = {
    ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv, ast.Mod: operator.mod,
}
_COMPARE = {
    ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le,
    ast.Gt: operator.gt, ast.GtE: operator.ge,
    ast.In: lambda a, b: a in b, ast.NotIn: lambda a, b: a not in b,
    ast.Is: operator.is_, ast.IsNot: operator.is_not,
}
MAX_LENGTH = 1000


class ExprError(StuartError, ValueError):
    """A parse or evaluation problem; ``column`` is 1-based within the expression text."""

    def __init__(self, message: str, column: int = 1) -> None:
        super().__init__(message)
        self.message = message
        self.column = column


class Missing(KeyError):
    """A name the blackboard does not hold."""


Lookup = Callable[[str], Any]  # dotted key -> value; raises KeyError when absent


@dataclass(frozen=True)
class Expression:
    text: str
    _tree: ast.expr

    @property
    def names(self) -> list[str]:
        """Blackboard keys the expression reads (dotted), in order of appearance."""
        inner = {id(n.value) for n in ast.walk(self._tree) if isinstance(n, ast.Attribute)}
        found: list[tuple[int, str]] = []
        for node in ast.walk(self._tree):
            if isinstance(node, (ast.Name, ast.Attribute)) and id(node) not in inner:
                dotted = _dotted(node)
                if dotted and dotted.split(".")[0] not in _CONSTANT_NAMES.keys() | _FUNCTIONS.keys():
                    found.append((node.col_offset, dotted))
        ordered: list[str] = []
        for _, dotted in sorted(found):
            if dotted not in ordered:
                ordered.append(dotted)
        return ordered

    def evaluate(self, lookup: Lookup) -> Any:
        try:
            return _Evaluator(lookup).visit(self._tree)
        except ExprError:
            raise
        except KeyError as e:
            raise ExprError(f"blackboard has no key {e.args[0]!r}") from None
        except Exception as e:  # noqa: BLE001 - a type mismatch such as 'a' < 3: report, do not crash the tick
            raise ExprError(f"cannot evaluate {self.text!r}: {e}") from None

    def __str__(self) -> str:
        return self.text


def parse(text: str) -> Expression:
    """Parse ``text`` or raise :class:`ExprError` with the offending column."""
    if not isinstance(text, str) or not text.strip():
        raise ExprError("expression is empty")
    if len(text) > MAX_LENGTH:
        raise ExprError(f"expression longer than {MAX_LENGTH} characters")
    try:
        tree = ast.parse(text.strip(), mode="eval").body
    except SyntaxError as e:
        raise ExprError(f"syntax error in expression: {e.msg}", e.offset or 1) from None
    except (RecursionError, MemoryError, ValueError):
        raise ExprError("expression too complex") from None
    _check(tree)
    return Expression(text.strip(), tree)


_ALLOWED = (
    ast.BoolOp, ast.And, ast.Or, ast.UnaryOp, ast.Not, ast.USub, ast.UAdd, ast.BinOp, ast.Compare,
    ast.Constant, ast.Name, ast.Attribute, ast.Subscript, ast.List, ast.Tuple, ast.Load, ast.Call,
    *_BINARY, *_COMPARE,
)


def _check(tree: ast.expr) -> None:
    for node in ast.walk(tree):
        if not isinstance(node, _ALLOWED):
            col = getattr(node, "col_offset", 0) + 1
            raise ExprError(f"'{type(node).__name__}' is not allowed in an expression", col)
        if isinstance(node, ast.Call) and (
                not isinstance(node.func, ast.Name) or node.func.id not in _FUNCTIONS or node.keywords):
            raise ExprError(
                    f"only these functions may be called: {', '.join(_FUNCTIONS)}", node.col_offset + 1
                )
        if isinstance(node, ast.Attribute) and node.attr.startswith("_"):
            raise ExprError(f"private name '{node.attr}' is not allowed", node.col_offset + 1)
        if isinstance(node, ast.Name) and node.id.startswith("_"):
            raise ExprError(f"private name '{node.id}' is not allowed", node.col_offset + 1)
        if isinstance(node, ast.Subscript) and not isinstance(node.slice, ast.Constant):
            raise ExprError("only constant indexes are allowed, e.g. visits['kitchen']", node.col_offset + 1)


def _dotted(node: ast.AST) -> str | None:
    parts: list[str] = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if isinstance(node, ast.Name):
        parts.append(node.id)
        return ".".join(reversed(parts))
    return None


class _Evaluator:
    """Evaluates a checked expression tree: one small method per node kind, found by type."""

    def __init__(self, lookup: Lookup) -> None:
        self.lookup = lookup
        self._by_type: dict[type, Callable[[Any], Any]] = {
            ast.Constant: lambda node: node.value,
            ast.Name: self._name, ast.Attribute: self._name, ast.Subscript: self._subscript,
            ast.BoolOp: self._bool_op, ast.UnaryOp: self._unary, ast.BinOp: self._binary,
            ast.Compare: self._compare, ast.List: self._sequence, ast.Tuple: self._sequence, ast.Call: self._call,
        }

    def visit(self, node: ast.AST) -> Any:
        handler = self._by_type.get(type(node))
        if handler is None:
            raise ExprError(f"'{type(node).__name__}' is not allowed in an expression")
        return handler(node)

    def _name(self, node: ast.Name | ast.Attribute) -> Any:
        dotted = _dotted(node)
        if dotted in _CONSTANT_NAMES:
            return _CONSTANT_NAMES[dotted]
        if dotted is not None:
            return self.lookup(dotted)
        assert isinstance(node, ast.Attribute)  # a bare name is always dotted
        return _get(self.visit(node.value), node.attr)

    def _subscript(self, node: ast.Subscript) -> Any:
        return _get(self.visit(node.value), node.slice.value)  # type: ignore[attr-defined]

    def _bool_op(self, node: ast.BoolOp) -> Any:
        """``and`` / ``or`` with Python's short circuit: the deciding value is the result."""
        stop_when = not isinstance(node.op, ast.And)  # `and` stops at a falsy value, `or` at a truthy one
        result: Any = not stop_when
        for v in node.values:
            result = self.visit(v)
            if bool(result) == stop_when:
                return result
        return result

    def _unary(self, node: ast.UnaryOp) -> Any:
        value = self.visit(node.operand)
        if isinstance(node.op, ast.Not):
            return not value
        return -value if isinstance(node.op, ast.USub) else +value

    def _binary(self, node: ast.BinOp) -> Any:
        return _BINARY[type(node.op)](self.visit(node.left), self.visit(node.right))

    def _compare(self, node: ast.Compare) -> bool:
        left = self.visit(node.left)
        for op, comparator in zip(node.ops, node.comparators, strict=True):
            right = self.visit(comparator)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True

    def _sequence(self, node: ast.List | ast.Tuple) -> list[Any]:
        return [self.visit(e) for e in node.elts]

    def _call(self, node: ast.Call) -> Any:
        return _FUNCTIONS[node.func.id](*[self.visit(a) for a in node.args])  # type: ignore[attr-defined]


def _get(container: Any, key: Any) -> Any:
    """``container[key]`` for mappings and sequences, else a public attribute."""
    if isinstance(container, dict):
        return container[key]
    if isinstance(container, (list, tuple)) and isinstance(key, int):
        return container[key]
    if isinstance(key, str) and not key.startswith("_") and hasattr(container, key):
        return getattr(container, key)
    raise KeyError(key)


def resolve_dotted(root: Any, dotted: str) -> Any:
    """Follow ``a.b.c`` through dicts and attributes; raises KeyError naming the full key."""
    value = root
    for part in dotted.split("."):
        try:
            value = _get(value, part)
        except (KeyError, IndexError):
            raise KeyError(dotted) from None
    return value
