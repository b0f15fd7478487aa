"""Plans told to people: the decomposition as a text tree (``stuart-bt plan`` prints it).

Each compound task shows the method chosen and, under it, every method tried and rejected with
the reason (the precondition clause and the values it read, or the failure that made the
planner back up). Each primitive shows its step number, the skill call it becomes and the
effects the planner predicted. A tree from a failed search marks the task that failed and why.
"""

from __future__ import annotations

import math
from typing import Any

from .plan import Plan, PlanningFailed, TaskNode
from .values import format_value, short

MAX_INDENT = 40  # deeper levels are drawn at this indentation, marked with their depth
UNICODE = {"tee": "├─ ", "last": "└─ ", "pipe": "│  ", "gap": "   ", "no": "✗", "to": "→", "then": "⇒"}
ASCII = {"tee": "|- ", "last": "`- ", "pipe": "|  ", "gap": "   ", "no": "x", "to": "->", "then": "=>"}


def explain(plan: Plan | PlanningFailed, *, rejections: bool = True, effects: bool = True,
            ascii: bool = False) -> str:
    """A plan, or a search that failed, as a text tree: each task with the method chosen and the
    methods tried and rejected (``rejections``), each step with its skill call and predicted
    ``effects``; box-drawing characters unless ``ascii``."""
    return render_tree(plan.root, rejections=rejections, effects=effects, ascii=ascii)


def render_tree(root: TaskNode, *, rejections: bool = True, effects: bool = True, ascii: bool = False) -> str:
    """The tree under ``root`` as lines of text (iterative: any depth)."""
    g = ASCII if ascii else UNICODE
    lines: list[str] = [_label(root, g, effects)]
    stack: list[tuple[TaskNode, str, bool]] = [(c, "", i == len(root.children) - 1)
                                               for i, c in enumerate(root.children)][::-1]
    _notes(root, "", g, rejections, lines)
    while stack:
        node, prefix, last = stack.pop()
        deep = f"[depth {node.depth}] " if node.depth > MAX_INDENT else ""
        lines.append(prefix + (g["last"] if last else g["tee"]) + deep + _label(node, g, effects))
        inner = prefix if node.depth >= MAX_INDENT else prefix + (g["gap"] if last else g["pipe"])
        _notes(node, inner, g, rejections, lines)
        children = node.children
        for i in range(len(children) - 1, -1, -1):
            stack.append((children[i], inner, i == len(children) - 1))
    return "\n".join(lines)


def _notes(node: TaskNode, inner: str, g: dict[str, str], rejections: bool, lines: list[str]) -> None:
    """Rejected methods just under a task's line; for a task that failed, every method's
    rejection with the failures below it in full."""
    bar = g["pipe"] if node.children else g["gap"]
    if node.kind == "compound" and node.status == "failed" and node.failure is not None:
        for text in node.failure.lines(mark=g["no"])[1:]:
            lines.append(f"{inner}{bar}{text[2:]}")
    elif rejections:
        for attempt in node.rejected:
            lines.append(f"{inner}{bar}{g['no']} {attempt.summary()}")


def _call(node: TaskNode) -> str:
    """The task as text with long arguments cut (the skill call after it shows them in full)."""
    return f"{node.name}({', '.join(_clip(format_value(v)) for v in node.args.values())})"


def _clip(text: str, width: int = 40) -> str:
    return text if len(text) <= width else text[:width - 4] + "...'"[-4 if text.endswith("'") else -3:]


def _label(node: TaskNode, g: dict[str, str], effects: bool) -> str:
    if node.kind == "mission":
        return "mission" if node.children else "mission (nothing to do)"
    if node.kind == "compound":
        if node.status == "failed" and node.failure is not None:
            return f"{node.call}  {g['no']} {node.failure.message}"
        if node.method is None:
            return f"{node.call}  (not reached)"
        return f"{node.call}  [{node.method}]"
    if node.status == "failed" and node.failure is not None:
        return f"{node.call}  {g['no']} {node.failure.message}"
    if node.status != "planned":
        return f"{node.call}  (not reached)"
    text = f"{node.step}. {_call(node)} {g['to']} {skill_call(node)}"
    if node.optional:
        text += "  [optional]"
    if node.skip_if:
        text += f"  [skip if {node.skip_if}]"
    if effects and node.changes:
        text += f"  {g['then']} {describe_changes(node.changes)}"
    return text


def skill_call(node: TaskNode) -> str:
    args = node.skill_args or {}
    return f"{node.skill}({', '.join(f'{k}={_arg(v)}' for k, v in args.items())})"


def _arg(value: Any) -> str:
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:.3f}".rstrip("0").rstrip(".")
    if isinstance(value, str):
        return repr(value)
    return format_value(value)


def steps_text(steps: list[TaskNode]) -> str:
    return "\n".join(f"{n.step:>3}. {skill_call(n)}" + ("  [optional]" if n.optional else "")
                     + (f"  [skip if {n.skip_if}]" if n.skip_if else "") for n in steps)


def describe_changes(changes: list[tuple[str, Any]] | None) -> str:
    """``at='kitchen', held=null, -objects['bottle']`` for the explanation."""
    if not changes:
        return ""
    parts = []
    for target, value in changes:
        parts.append(target if target.startswith("-") else f"{target}={short(value)}")
    return ", ".join(parts)
