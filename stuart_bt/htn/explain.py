"""Plans told to people: the decomposition as a text tree, and the ``stuart-bt plan`` command.

Each compound task shows the method chosen and, under it, every method tried and rejected with
the reason (the precondition clause and the values it read, or the failure that made the
planner back up). Each primitive shows its step number, the skill call it becomes and the
effects the planner predicted. A tree from a failed search marks the task that failed and why.
"""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

from ..jsonfile import to_json
from .domain import format_value
from .plan import TaskNode, describe_changes

MAX_INDENT = 40  # deeper levels are drawn at this indentation, marked with their depth
UNICODE = {"tee": "├─ ", "last": "└─ ", "pipe": "│  ", "gap": "   ", "no": "✗", "to": "→", "then": "⇒"}
ASCII = {"tee": "|- ", "last": "`- ", "pipe": "|  ", "gap": "   ", "no": "x", "to": "->", "then": "=>"}


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


# -- the CLI command -----------------------------------------------------------------------------------
def add_plan_command(subparsers: Any) -> argparse.ArgumentParser:
    """Register ``stuart-bt plan TASK`` on an argparse sub-parser set."""
    p = subparsers.add_parser(
        "plan", help="plan a task with the HTN domain; print the decomposition, methods chosen and rejections",
        description="Plan a task with the HTN domain (tasks/domain.yaml) from the lab's start state.")
    p.add_argument("task", metavar="TASK",
                   help="a task expression, e.g. \"fetch(bottle, workbench)\" (several: separate with ';'), "
                        "or a JSON list of TaskIntents "
                        "'[{\"action\": \"navigate_to_marker\", \"target\": \"kitchen\"}]'")
    p.add_argument("--json", action="store_true", help="print the plan (or the failure) as JSON")
    p.add_argument("--show", action="store_true", help="also draw the behaviour tree the plan compiles to")
    p.add_argument("--state", metavar="FILE",
                   help="start state: a JSON object of state variables over the domain's defaults "
                        "(default: lab markers and objects, robot at --start)")
    p.add_argument("--start", metavar="MARKER", default="entrance", help="where the robot stands (default: entrance)")
    p.add_argument("--domain", metavar="FILE", help="domain YAML (default: the project's tasks/domain.yaml)")
    p.add_argument("--ascii", action="store_true", help="ASCII tree instead of box-drawing characters")
    p.add_argument("--no-rejections", action="store_true", help="leave out the methods tried and rejected")
    p.add_argument("--no-backtracking", action="store_true",
                   help="commit to the first applicable method (GTPyhop's default)")
    p.add_argument("--max-expansions", type=int, metavar="N", help="expansion budget")
    p.add_argument("--time-limit", type=float, metavar="S", help="time budget in seconds")
    p.set_defaults(func=cmd_plan)
    return p


def cmd_plan(args: argparse.Namespace) -> int:
    from ..tree.errors import TreeLoadError
    from .domain import TaskArgumentError, load_domain, project_domain
    from .plan import PlanningBudgetExceeded, PlanningFailed
    from .planner import DEFAULT_MAX_EXPANSIONS, DEFAULT_TIME_LIMIT, Planner
    from .state import State, StateFileError, lab_world, with_marker_names

    try:
        if args.domain:
            from stuart_bt.tasks.hooks import HOOKS

            domain = load_domain(args.domain, HOOKS)
        else:
            domain = project_domain()
    except TreeLoadError as e:
        for error in e.errors:
            print(error, file=sys.stderr)
        return 1
    try:
        if args.state:
            state = domain.initial_state(overrides=with_marker_names(dict(State.load(args.state))))
        else:
            state = domain.initial_state(lab_world(start=args.start))
    except (StateFileError, ValueError) as e:
        print(f"stuart-bt: {e}", file=sys.stderr)
        return 1
    planner = Planner(domain, backtracking=not args.no_backtracking,
                      max_expansions=args.max_expansions or DEFAULT_MAX_EXPANSIONS,
                      time_limit=args.time_limit or DEFAULT_TIME_LIMIT)
    tasks: Any = args.task
    if _is_utterance(args.task, domain):
        from ..language import Parser

        parsed = Parser(require_wake=False).parse(args.task)
        if not parsed.intents:
            print(f"stuart-bt: no command in {args.task!r} (it reads as conversation)", file=sys.stderr)
            return 1
        tasks = [intent.to_dict() for intent in parsed.intents]
    try:
        plan = planner.plan(tasks, state)
    except TaskArgumentError as e:
        print(f"stuart-bt: {e}", file=sys.stderr)
        return 1
    except PlanningFailed as e:
        if args.json:
            print(to_json(e.to_dict(), indent=2))
        else:
            print(str(e))
            if any(n.status == "planned" and n.kind != "mission" for n in e.root.walk()):
                print("\ndecomposition so far:")
                print(e.explain(ascii=args.ascii))
        return 1
    except PlanningBudgetExceeded as e:
        if args.json:
            print(to_json(e.to_dict(), indent=2))
        print(f"stuart-bt: {e}", file=sys.stderr)
        return 1
    if args.json:
        print(to_json(plan.to_dict(), indent=2))
        return 0
    steps = plan.primitives()
    s = plan.stats
    print(f"plan for {', '.join(t.call for t in plan.tasks)}: {len(steps)} steps "
          f"({s.expansions} expansions, {s.backtracks} backtracks, {s.seconds * 1000:.2f} ms)\n")
    print(plan.explain(rejections=not args.no_rejections, ascii=args.ascii))
    print("\nsteps:")
    print(steps_text(steps))
    if args.show:
        from ..mission.compiler import show

        print("\ntree:")
        print(show(plan, "ascii" if args.ascii else "unicode"))
    return 0


def _is_utterance(text: str, domain: Any) -> bool:
    """Task text looks like ``fetch(bottle, workbench)``, a task name, or JSON; anything else is
    taken as what someone said ("Hey Stuart, go to the kitchen")."""
    stripped = text.strip()
    if stripped.startswith(("[", "{")) or "(" in stripped:
        return False
    return not all(domain.get(part.strip()) is not None for part in stripped.split(";") if part.strip())
