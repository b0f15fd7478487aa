"""The plan line ``chat`` and ``mission`` print when a mission's tree starts:
``plan      mission 1: go_to [navigate]; wave [gesture]``, each top-level task and the skills it
decomposed into. The executor's events name only the top-level tasks, so the line is made from
the compiled tree, which :class:`TreeWatchingExecutor` hands over as each mission tree starts
(and again after a repair: the new plan).
"""

from __future__ import annotations

from collections.abc import Callable

from ..mission.executor import Mission, MissionExecutor, MissionOptions
from ..run.executor import RunOutcome
from ..tree.spec import NodeSpec, TreeSpec

TreeWatcher = Callable[[TreeSpec, Mission], None]


class TreeWatchingExecutor(MissionExecutor):
    """A mission executor that shows ``on_tree`` every mission tree before it runs (not the
    speech-only trees of replies and explanations, which are not missions)."""

    def __init__(self, options: MissionOptions, on_tree: TreeWatcher) -> None:
        super().__init__(options)
        self._on_tree = on_tree

    def _run_tree(self, spec: TreeSpec, mission: Mission | None) -> tuple[RunOutcome, set[str], str | None]:
        if mission is not None:
            self._on_tree(spec, mission)
        return super()._run_tree(spec, mission)


def plan_line(spec: TreeSpec, mission: Mission) -> str:
    """The line as printed, after the 10 columns where the other lines have their clock time."""
    return f"plan      mission {mission.id}: {decomposition(spec)}"


def decomposition(spec: TreeSpec) -> str:
    """The compiled tree in one line: each top-level task and the skills it decomposed into."""
    parts = []
    for task in spec.root.children or [spec.root]:
        skills = [n.kind for n in _leaves(task) if n.kind != "condition"]
        parts.append(f"{task.name} [{' > '.join(skills)}]" if task.children else task.name)
    return "; ".join(parts)


def _leaves(node: NodeSpec) -> list[NodeSpec]:
    if not node.children:
        return [node]
    return [leaf for child in node.children for leaf in _leaves(child)]
