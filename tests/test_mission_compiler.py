"""Plans compiled to trees: the tree has the decomposition's shape, its paths read like it, and
the planner's run-time hints (optional, skip_if) and the catalogue's timeouts are in it."""

from __future__ import annotations

import py_trees
import pytest
from py_trees.common import Status

from stuart_bt.core.blackboard import Blackboard
from stuart_bt.core.clock import ManualClock
from stuart_bt.core.world import KnownObject
from stuart_bt.htn import Planner, lab_world
from stuart_bt.mission.compiler import compile_plan, show
from stuart_bt.tasks import project_domain
from stuart_bt.tree.builder import build


@pytest.fixture(scope="module")
def plan_for():
    domain = project_domain()
    state = domain.initial_state(lab_world())
    return lambda text: Planner(domain).plan(domain.calls_from_text(text), state)


def shape(node) -> list:
    label = f"{node.kind} {node.path}"
    return [label, *[shape(c) for c in node.children]] if node.children else label


def test_fetch_compiles_to_one_sequence_per_compound_and_one_leaf_per_step(plan_for):
    compiled = compile_plan(plan_for("fetch(bottle, workbench)"))

    assert shape(compiled.spec.root) == [
        "sequence mission",
        ["sequence mission/fetch",
         "speak mission/fetch/acknowledge",
         ["sequence mission/fetch/get",
          ["sequence mission/fetch/get/go_near", "approach mission/fetch/get/go_near/approach"],
          "find mission/fetch/get/look", "pick mission/fetch/get/pick_object"],
         "navigate mission/fetch/go_to",
         "release mission/fetch/put_down"]]
    assert all(n.params.get("memory") is True for n in compiled.spec.walk() if n.kind == "sequence")
    assert compiled.top == ["mission/fetch"]
    assert compiled.tasks["mission/fetch/get"].method == "go_and_pick"


def test_leaves_carry_the_skill_arguments_and_the_catalogue_timeout(plan_for):
    spec = compile_plan(plan_for("fetch(bottle, workbench)")).spec

    assert spec.find("mission/fetch/acknowledge").params == {
        "text": "Fetching the bottle for the workbench", "timeout": 120.0}
    assert spec.find("mission/fetch/go_to").params == {"marker": "workbench", "timeout": 180.0}
    assert spec.find("mission/fetch/get/pick_object").params == {"object": "bottle", "timeout": 90.0}


def test_optional_and_skip_if_steps_are_wrapped_so_a_miss_is_no_failure_and_a_seen_object_is_not_looked_for(plan_for):
    spec = compile_plan(plan_for("find(banana)")).spec
    glance = spec.find("mission/find/search/scan/glance")
    turn = spec.find("mission/find/search/scan/scan_turn")

    assert shape(glance) == ["selector mission/find/search/scan/glance",
                             "condition mission/find/search/scan/glance/skip_if",
                             ["force_success mission/find/search/scan/glance/optional",
                              "find mission/find/search/scan/glance/optional/find"]]
    assert glance.params == {"memory": True}
    assert glance.children[0].params == {"expr": "'banana' in world.objects"}
    assert shape(turn) == ["selector mission/find/search/scan/scan_turn",
                           "condition mission/find/search/scan/scan_turn/skip_if",
                           "turn mission/find/search/scan/scan_turn/turn"]


def test_repeated_tasks_get_distinct_paths(plan_for):
    compiled = compile_plan(plan_for("navigate_to_marker(kitchen); navigate_to_marker(bathroom)"))

    assert compiled.top == ["mission/navigate_to_marker", "mission/navigate_to_marker_2"]
    assert compiled.spec.find("mission/navigate_to_marker_2/go_to").params["marker"] == "bathroom"


def test_the_builder_builds_the_compiled_tree_and_skip_if_skips_a_step_whose_effect_holds(plan_for):
    spec = compile_plan(plan_for("find(banana)")).spec
    started: list[str] = []

    class Fake(py_trees.behaviour.Behaviour):
        def __init__(self, node):
            super().__init__(node.name)
            self.node = node

        def update(self):
            if self.node.kind == "condition":
                return Status.SUCCESS if "banana" in bb.world.objects else Status.FAILURE
            started.append(self.node.path)
            if self.node.kind == "find":
                bb.world.objects["banana"] = KnownObject("banana", 1.0, 2.0, 0.8)
            return Status.SUCCESS

    bb = Blackboard()
    root = build(spec, Fake, ManualClock(), bb)
    tree = py_trees.trees.BehaviourTree(root)
    for _ in range(50):
        tree.tick()
        if root.status != Status.RUNNING:
            break

    assert root.status == Status.SUCCESS
    assert started == ["mission/find/acknowledge", "mission/find/search/scan/glance/optional/find",
                       "mission/find/search/scan/scan/scan/scan/look", "mission/find/view"], \
        "after the first glance saw it, the other turns and glances were skipped"


def test_show_draws_the_compiled_tree_with_task_names(plan_for):
    text = show(plan_for("fetch(bottle, workbench)"))

    assert text.splitlines()[0].startswith("[->] mission")
    assert "approach object=bottle" in text and "navigate marker=workbench" in text
