"""Task values as people write them: a task call (``fetch(bottle, workbench)``), its arguments,
and the short text a value is shown as in explanations and errors.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from typing import Any

from ..core.errors import StuartError

MISSING: Any = type("Missing", (), {"__repr__": lambda self: "<missing>"})()  # a parameter with no default
RESERVED = {"true", "false", "null", "True", "False", "None", "len", "abs", "min", "max", "round"}

_BARE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


class TaskArgumentError(StuartError, ValueError):
    """A task called with the wrong arguments, an unknown task, or task text that does not parse."""


@dataclass(frozen=True)
class TaskCall:
    """A task and its argument values: what a user asks for, or one subtask of a method."""

    name: str
    args: tuple[Any, ...] = ()
    kwargs: tuple[tuple[str, Any], ...] = ()

    @classmethod
    def parse(cls, text: str) -> TaskCall:
        """Exactly one task from its text, ``fetch(bottle, workbench)``: the converter for a
        caller that holds one task as text (the planner takes only TaskCalls); raises
        TaskArgumentError for text that does not read as one task. Several tasks, or TaskIntents
        as JSON: :meth:`Domain.calls_from_text`."""
        calls = parse_task_text(text)
        if len(calls) != 1:
            raise TaskArgumentError(f"expected one task, got {len(calls)} in {text!r}")
        return calls[0]

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
