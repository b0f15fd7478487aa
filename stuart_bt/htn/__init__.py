"""HTN planning for Stuart: a YAML task domain, a backtracking planner, plans explained in words.

    from stuart_bt.htn import Planner, TaskCall, explain
    from stuart_bt.tasks import project_domain
    from stuart_bt.htn.state import lab_world

    domain = project_domain()                             # tasks/domain.yaml + tasks/hooks.py
    calls = [TaskCall.parse("fetch(bottle, workbench)")]  # the planner takes a list of TaskCall
    plan = Planner(domain).plan(calls, domain.initial_state(lab_world()))
    print(explain(plan))                                  # the decomposition, methods chosen and rejected
    for step in plan.primitives():                        # what the compiler turns into leaves
        print(step.skill, step.skill_args)

See docs/htn.md for the domain language and the semantics.
"""

from .domain import Domain
from .explain import explain, render_tree
from .hooks import Hook, HookRegistry
from .load import DomainLoadError, load_domain, load_domain_text
from .plan import Failure, MethodAttempt, Plan, PlanningBudgetExceeded, PlanningFailed, PlanStats, TaskNode
from .planner import Planner, PlannerInputError
from .state import State, lab_world
from .values import TaskArgumentError, TaskCall, parse_task_text

__all__ = [
    "Domain", "DomainLoadError", "Failure", "Hook", "HookRegistry", "MethodAttempt", "Plan", "PlanStats", "Planner",
    "PlannerInputError",
    "PlanningBudgetExceeded", "PlanningFailed", "State", "TaskArgumentError", "TaskCall", "TaskNode",
    "lab_world", "load_domain", "load_domain_text", "parse_task_text",
    "explain", "render_tree",
]
