"""Plan -> TreeSpec: the HTN decomposition as a behaviour tree the existing builder can build.

The compiled tree has the shape of the decomposition, so a node path reads like the reasons the
planner gave (``mission/fetch/get/go_near/approach``) and a failed leaf points straight at the
task to repair:

- the plan's root becomes a ``sequence`` (memory true) called ``mission``;
- every compound task becomes a ``sequence`` (memory true) named after the task; the method it
  used is kept in :attr:`CompiledMission.tasks` (a NodeSpec has no room for it);
- every primitive becomes one skill leaf (``kind`` = the skill, ``params`` = its arguments plus
  the catalogue's default ``timeout``), named after the primitive task;
- ``optional`` primitives are wrapped in ``force_success`` (a miss does not fail the mission);
- ``skip_if`` primitives become ``selector(memory) [condition(skip_if), step]``: when the
  effect already holds at run time (the object was already seen) the step is not done.

Sibling names are made unique (``navigate_to_marker``, ``navigate_to_marker_2``) so paths stay
stable and distinct. :func:`show` draws the compiled tree with :mod:`stuart_bt.tree.render`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..core.catalogue import LEAVES
from ..htn.plan import Plan, TaskNode
from ..tree.spec import Location, NodeSpec, TreeSpec

ROOT = "mission"
SOURCE = "<mission>"


@dataclass
class CompiledMission:
    """A compiled plan: the tree, and which task every node came from.

    ``tasks`` maps node paths (compound sequences, the outer node of each primitive, and its
    leaf) to the plan's TaskNode; ``top`` lists the paths of the tasks asked for, in order.
    """

    spec: TreeSpec
    tasks: dict[str, TaskNode] = field(default_factory=dict)
    top: list[str] = field(default_factory=list)

    def task_at(self, path: str) -> TaskNode | None:
        """The task a node (or any node below it) belongs to: the longest matching path."""
        while path:
            if path in self.tasks:
                return self.tasks[path]
            path = path.rpartition("/")[0]
        return None


def compile_plan(plan: Plan | TaskNode, *, preface: str | None = None, file: str = SOURCE,
                 markers_file: str | None = None) -> CompiledMission:
    """The behaviour tree for ``plan`` (a Plan, or a mission TaskNode). ``preface``: a sentence
    spoken first (used when a mission resumes or is repaired)."""
    root_task = plan.root if isinstance(plan, Plan) else plan
    out = CompiledMission(TreeSpec(NodeSpec("sequence", ROOT, ROOT, _where(), {"memory": True}), file,
                                   markers_file=markers_file))
    root = out.spec.root
    names: dict[str, int] = {}
    if preface:
        root.children.append(_leaf("speak", "preface", f"{ROOT}/preface", {"text": preface}))
        names["preface"] = 1
    for task in root_task.children:
        node = _compile(task, ROOT, names, out)
        root.children.append(node)
        out.top.append(node.path)
    return out


def _compile(task: TaskNode, parent: str, names: dict[str, int], out: CompiledMission) -> NodeSpec:
    name = _unique(task.name, names)
    path = f"{parent}/{name}"
    out.tasks[path] = task
    if task.kind != "primitive":
        node = NodeSpec("sequence", name, path, _where(), {"memory": True})
        child_names: dict[str, int] = {}
        node.children = [_compile(c, path, child_names, out) for c in task.children]
        return node
    return _primitive(task, name, path, out)


def _primitive(task: TaskNode, name: str, path: str, out: CompiledMission) -> NodeSpec:
    """One skill leaf, wrapped for ``optional`` and ``skip_if``; the outer node has the task's name."""
    skill = task.skill or "wait"
    if not task.optional and not task.skip_if:
        return _leaf(skill, name, path, dict(task.skill_args or {}))
    outer_kind = "selector" if task.skip_if else "force_success"
    outer = NodeSpec(outer_kind, name, path, _where(), {"memory": True} if task.skip_if else {})
    inner_parent = outer
    if task.skip_if:
        outer.children.append(_leaf("condition", "skip_if", f"{path}/skip_if", {"expr": task.skip_if}))
        if task.optional:
            wrapper = NodeSpec("force_success", "optional", f"{path}/optional", _where())
            outer.children.append(wrapper)
            inner_parent = wrapper
    leaf = _leaf(skill, skill, f"{inner_parent.path}/{skill}", dict(task.skill_args or {}))
    inner_parent.children.append(leaf)
    out.tasks[leaf.path] = task
    return outer


def _leaf(kind: str, name: str, path: str, params: dict[str, Any]) -> NodeSpec:
    timeout = LEAVES[kind].default_timeout if kind in LEAVES else math.inf
    if math.isfinite(timeout) and "timeout" not in params:
        params["timeout"] = timeout
    return NodeSpec(kind, name, path, _where(), params)


def _unique(name: str, names: dict[str, int]) -> str:
    count = names.get(name, 0) + 1
    names[name] = count
    return name if count == 1 else f"{name}_{count}"


def _where() -> Location:
    return Location(SOURCE, 1, 1)


def show(plan: Plan, fmt: str = "unicode") -> str:
    """The compiled tree drawn as text (for ``stuart-bt plan --show``)."""
    from ..tree.render import render

    drawn = render(compile_plan(plan).spec, fmt)
    return drawn if isinstance(drawn, str) else drawn.decode("utf-8")
