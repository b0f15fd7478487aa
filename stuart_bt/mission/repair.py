"""Planning what is left of a mission, and repairing it when a leaf fails.

Every plan starts from the world state *now*: a mission that starts, resumes or is repaired is
planned again from where the robot is, what it holds and what it remembers. A repair re-plans the
lowest failed compound task that still plans, followed by what was left after it at every level,
then the mission's later calls; an object that was not where memory said is forgotten first, so
the re-plan looks for it again.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from ..htn import Planner, PlanningBudgetExceeded, PlanningFailed, TaskArgumentError, TaskNode
from ..htn.values import TaskCall
from .compiler import CompiledMission, compile_plan
from .speech import cannot

if TYPE_CHECKING:
    from ..core.blackboard import Blackboard
    from ..htn.domain import Domain
    from ..htn.state import State
    from .queue import Mission

OBJECT_FAULTS = ("not_found", "unreachable")  # failures that mean: the object is not where memory says
PLANNING_ERRORS = (PlanningFailed, PlanningBudgetExceeded, TaskArgumentError)


class Replanner:
    """Plans a mission's calls from the blackboard's world state and compiles them to a tree."""

    def __init__(self, domain: Domain, blackboard: Blackboard, markers_file: Path) -> None:
        self.domain = domain
        self.blackboard = blackboard
        self.markers_file = markers_file

    def _state(self) -> State:
        return self.domain.initial_state(self.blackboard.world)

    def plan_remaining(self, m: Mission) -> tuple[CompiledMission | None, list[int], str | None]:
        """Plan the calls not done yet. When the whole list cannot be planned, the longest prefix
        that can is run and the reason for the next call is said afterwards."""
        calls = m.calls[m.done:]
        planner = Planner(self.domain, acks=not m.resumed)
        preface = "Carrying on." if m.resumed else None
        first_error: str | None = None
        for k in range(len(calls), 0, -1):
            try:
                plan = planner.plan(calls[:k], self._state())
            except PLANNING_ERRORS as e:
                if first_error is None:
                    first_error = cannot(m.texts[m.done + k - 1] if m.done + k - 1 < len(m.texts) else "",
                                         calls[k - 1], e)
                continue
            compiled = compile_plan(plan, preface=preface, markers_file=str(self.markers_file))
            return compiled, list(range(m.done, m.done + k)), first_error
        if first_error is None:
            first_error = "I have nothing to do."
        return None, [], first_error

    def repair(self, m: Mission, compiled: CompiledMission, index: list[int], failed_path: str,
               code: str | None) -> tuple[CompiledMission | None, list[int]]:
        """Re-plan the lowest failed compound task that plans from the current state, followed by
        what was left after it at every level, then the mission's remaining calls. ``code``: the
        failed leaf's daemon error code."""
        leaf = compiled.task_at(failed_path)
        top_path = next((p for p in compiled.top if failed_path == p or failed_path.startswith(p + "/")), None)
        if leaf is None or top_path is None:
            return None, []
        pos = compiled.top.index(top_path)
        call_index = index[pos]
        self.forget_misplaced(leaf, code)
        later = [(_call(compiled.tasks[p]), index[pos + 1 + i]) for i, p in enumerate(compiled.top[pos + 1:])]
        later += [(c, j) for j, c in enumerate(m.calls) if j > max(index)]
        later_calls = [c for c, _ in later]
        later_index = [j for _, j in later]
        planner = Planner(self.domain, acks=False)
        compound = leaf.parent
        while compound is not None and compound.kind != "mission":
            calls = [_call(compound), *_following(compound)]
            try:
                plan = planner.plan(calls + later_calls, self._state())
            except PLANNING_ERRORS:
                compound = compound.parent
                continue
            repaired = compile_plan(plan, markers_file=str(self.markers_file))
            return repaired, [call_index] * len(calls) + later_index
        rest = [j for j in range(call_index, len(m.calls)) if j == call_index or j > max(index)]
        try:  # last resort: the whole task that was asked for, again from here
            plan = planner.plan([m.calls[j] for j in rest], self._state())
        except PLANNING_ERRORS:
            return None, []
        return compile_plan(plan, markers_file=str(self.markers_file)), rest

    def forget_misplaced(self, task: TaskNode, code: str | None) -> None:
        """A pick or find that failed because the object was not there: forget where it was, so
        the re-plan looks for it."""
        label = (task.skill_args or {}).get("object")
        if task.skill in ("pick", "find") and label and code in OBJECT_FAULTS:
            self.blackboard.world.objects.pop(label, None)


def calls_done(compiled: CompiledMission, index: list[int], succeeded: set[str]) -> int:
    """How many of the mission's calls are finished: a call is done when every top-level entry
    of the tree that belongs to it succeeded."""
    done = 0
    for i, path in enumerate(compiled.top):
        if path not in succeeded:
            break
        if i + 1 == len(compiled.top) or index[i + 1] != index[i]:
            done = index[i] + 1
    return done


def _following(node: TaskNode) -> list[TaskCall]:
    """What was still to do after ``node`` inside its top-level task: the later siblings at
    every level up (acknowledgements left out: they were said already)."""
    out: list[TaskCall] = []
    while node.parent is not None and node.parent.kind != "mission":
        out += [_call(s) for s in _after(node) if not s.ack]
        node = node.parent
    return out


def _after(node: TaskNode) -> list[TaskNode]:
    siblings = node.parent.children if node.parent is not None else []
    return siblings[siblings.index(node) + 1:]


def _call(node: TaskNode) -> TaskCall:
    return TaskCall(node.name, tuple(node.args.values()))
