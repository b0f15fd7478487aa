"""``stuart-bt plan``: plan a task (or an utterance) with the HTN domain and explain the plan:
the decomposition, the methods chosen and rejected, the steps, and with ``--show`` the tree it
compiles to. It sits with the missions because it runs their first stages (parse, plan, compile)."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ..core.jsonfile import to_json
from ..htn.explain import explain, steps_text


def add_command(subparsers: Any) -> argparse.ArgumentParser:
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


class _Refused(Exception):
    """What to print on stderr before the command exits with 1."""


def cmd_plan(args: argparse.Namespace) -> int:
    from ..htn.planner import DEFAULT_MAX_EXPANSIONS, DEFAULT_TIME_LIMIT, Planner

    try:
        domain = _domain(args.domain)
        state = _start_state(domain, args)
        tasks = _tasks(args.task, domain)
    except _Refused as e:
        print(e, file=sys.stderr)
        return 1
    planner = Planner(domain, backtracking=not args.no_backtracking,
                      max_expansions=args.max_expansions or DEFAULT_MAX_EXPANSIONS,
                      time_limit=args.time_limit or DEFAULT_TIME_LIMIT)
    plan = _plan_or_explain_why_not(planner, tasks, state, args)
    if plan is None:
        return 1
    if args.json:
        print(to_json(plan.to_dict(), indent=2))
        return 0
    _print_plan(plan, args)
    return 0


def _domain(path: str | None) -> Any:
    from ..htn.load import load_domain
    from ..tasks import project_domain
    from ..tree.errors import TreeLoadError

    try:
        if path:
            from stuart_bt.tasks.hooks import HOOKS

            return load_domain(path, HOOKS)
        return project_domain()
    except TreeLoadError as e:
        raise _Refused("\n".join(str(error) for error in e.errors)) from None


def _start_state(domain: Any, args: argparse.Namespace) -> Any:
    from ..htn.state import State, StateFileError, lab_world, with_marker_names

    try:
        if args.state:
            return domain.initial_state(overrides=with_marker_names(dict(State.load(args.state))))
        return domain.initial_state(lab_world(start=args.start))
    except (StateFileError, ValueError) as e:
        raise _Refused(f"stuart-bt: {e}") from None


def _tasks(text: str, domain: Any) -> list[Any]:
    """The TaskCalls the planner takes: from task text (or a JSON list of TaskIntents), or from
    the intents an utterance is parsed into."""
    from ..htn.values import TaskArgumentError

    try:
        if not _is_utterance(text, domain):
            return domain.calls_from_text(text)
        from ..language import Parser

        parsed = Parser(require_wake=False).parse(text)
        if not parsed.intents:
            raise _Refused(f"stuart-bt: no command in {text!r} (it reads as conversation)")
        return domain.calls_from_intents([intent.to_dict() for intent in parsed.intents])
    except TaskArgumentError as e:
        raise _Refused(f"stuart-bt: {e}") from None


def _plan_or_explain_why_not(planner: Any, tasks: Any, state: Any, args: argparse.Namespace) -> Any:
    """The plan, or ``None`` after saying why there is none (and what was planned so far)."""
    from ..htn.plan import PlanningBudgetExceeded, PlanningFailed
    from ..htn.values import TaskArgumentError

    try:
        return planner.plan(tasks, state)
    except TaskArgumentError as e:
        print(f"stuart-bt: {e}", file=sys.stderr)
    except PlanningFailed as e:
        if args.json:
            print(to_json(e.to_dict(), indent=2))
        else:
            print(str(e))
            if any(n.status == "planned" and n.kind != "mission" for n in e.root.walk()):
                print("\ndecomposition so far:")
                print(explain(e, ascii=args.ascii))
    except PlanningBudgetExceeded as e:
        if args.json:
            print(to_json(e.to_dict(), indent=2))
        print(f"stuart-bt: {e}", file=sys.stderr)
    return None


def _print_plan(plan: Any, args: argparse.Namespace) -> None:
    steps = plan.primitives()
    s = plan.stats
    print(f"plan for {', '.join(t.call for t in plan.tasks)}: {len(steps)} steps "
          f"({s.expansions} expansions, {s.backtracks} backtracks, {s.seconds * 1000:.2f} ms)\n")
    print(explain(plan, rejections=not args.no_rejections, ascii=args.ascii))
    print("\nsteps:")
    print(steps_text(steps))
    if args.show:
        from ..mission.compiler import show

        print("\ntree:")
        print(show(plan, "ascii" if args.ascii else "unicode"))


def _is_utterance(text: str, domain: Any) -> bool:
    """Task text looks like ``fetch(bottle, workbench)``, a task name, or JSON; anything else is
    taken as what someone said ("Hey Stuart, go to the kitchen")."""
    stripped = text.strip()
    if stripped.startswith(("[", "{")) or "(" in stripped:
        return False
    return not all(domain.get(part.strip()) is not None for part in stripped.split(";") if part.strip())
