"""Loaded trees become the right py_trees behaviours, and our clock-driven decorators behave."""

from __future__ import annotations

import textwrap

import py_trees
import pytest
from py_trees.common import OneShotPolicy, ParallelPolicy, Status

from stuart_bt.core.blackboard import Blackboard
from stuart_bt.core.clock import ManualClock
from stuart_bt.tree.builder import BuildError, build
from stuart_bt.tree.decorators import Delay, Guard, Timeout
from stuart_bt.tree.loader import load_tree_text
from stuart_bt.tree.spec import NodeSpec

LETTERS = {"S": Status.SUCCESS, "F": Status.FAILURE, "R": Status.RUNNING}


class Scripted(py_trees.behaviour.Behaviour):
    """A fake leaf: returns its script's statuses one per tick (the last repeats); logs ticks and stops."""

    def __init__(self, spec: NodeSpec, script: str, log: list[str]) -> None:
        super().__init__(name="unnamed")
        self.spec = spec
        self.script = list(script)
        self.log = log

    def update(self) -> Status:
        self.log.append(f"tick {self.spec.path}")
        letter = self.script.pop(0) if len(self.script) > 1 else self.script[0]
        return LETTERS[letter]

    def terminate(self, new_status: Status) -> None:
        if new_status == Status.INVALID:
            self.log.append(f"stop {self.spec.path}")


class Rig:
    """A tree built from YAML text with scripted leaves, a manual clock and a blackboard."""

    def __init__(self, text: str, scripts: dict[str, str] | None = None, **initial) -> None:
        self.spec = load_tree_text(textwrap.dedent(text))
        self.scripts = scripts or {}
        self.log: list[str] = []
        self.clock = ManualClock()
        self.blackboard = Blackboard(initial=initial)
        self.root = build(self.spec, self.leaf, self.clock, self.blackboard)

    def leaf(self, spec: NodeSpec) -> Scripted:
        return Scripted(spec, self.scripts.get(spec.path, "S"), self.log)

    def tick(self, at: float | None = None) -> Status:
        if at is not None:
            self.clock.set(at)
        self.root.tick_once()
        return self.root.status

    def find(self, path: str) -> py_trees.behaviour.Behaviour:
        return next(b for b in self.root.iterate() if b.spec_path == path)


# --- structure -------------------------------------------------------------------------------

def test_composites_have_catalogue_memory_defaults_and_explicit_overrides():
    rig = Rig("""\
        root:
          sequence:
            - sequence: [{stop: {}}]
            - selector: [{stop: {}}]
            - sequence: {memory: false, children: [{stop: {}}]}
            - selector: {memory: true, children: [{stop: {}}]}
        """)
    built = rig.root.children
    assert isinstance(rig.root, py_trees.composites.Sequence) and rig.root.memory is True
    assert [type(b).__name__ for b in built] == ["Sequence", "Selector", "Sequence", "Selector"]
    assert [b.memory for b in built] == [True, False, False, True]


def test_parallel_policies():
    rig = Rig("""\
        root:
          sequence:
            - parallel: [{stop: {}}, {wait: 1}]
            - parallel: {policy: one, children: [{stop: {}}]}
            - parallel:
                policy: selected
                synchronise: false
                selected: [go]
                children: [{navigate: {marker: dock, name: go}}, {speak: hi}]
        """)
    all_, one, selected = (b.policy for b in rig.root.children)
    assert isinstance(all_, ParallelPolicy.SuccessOnAll) and all_.synchronise is True
    assert isinstance(one, ParallelPolicy.SuccessOnOne)
    assert isinstance(selected, ParallelPolicy.SuccessOnSelected) and selected.synchronise is False
    assert selected.children == [rig.find("root/parallel_3/go")]


def test_decorators_map_to_py_trees_types():
    rig = Rig("""\
        root:
          sequence:
            - retry: {times: 3, child: {stop: {}}}
            - repeat: {times: -1, child: {stop: {}}}
            - inverter: {child: {stop: {}}}
            - force_success: {child: {stop: {}}}
            - force_failure: {child: {stop: {}}}
            - oneshot: {child: {stop: {}}}
            - oneshot: {on: success, child: {stop: {}}}
            - timeout: {seconds: 1, child: {stop: {}}}
            - delay: {seconds: 1, child: {stop: {}}}
            - guard: {condition: "true", child: {stop: {}}}
        """)
    b = rig.root.children
    assert isinstance(b[0], py_trees.decorators.Retry) and b[0].num_failures == 3
    assert isinstance(b[1], py_trees.decorators.Repeat) and b[1].num_success == -1
    assert isinstance(b[2], py_trees.decorators.Inverter)
    assert isinstance(b[3], py_trees.decorators.FailureIsSuccess)
    assert isinstance(b[4], py_trees.decorators.SuccessIsFailure)
    assert b[5].policy == OneShotPolicy.ON_COMPLETION and b[6].policy == OneShotPolicy.ON_SUCCESSFUL_COMPLETION
    assert [type(x) for x in b[7:]] == [Timeout, Delay, Guard]


def test_every_behaviour_has_its_spec_path_and_last_segment_as_name():
    rig = Rig("root:\n  sequence:\n    name: tour\n    children:\n      - speak: {text: hi, name: greet}\n"
              "      - retry: {times: 2, child: {stop: {}}}\n")
    assert [(b.spec_path, b.name) for b in rig.root.iterate()] == [
        ("tour/greet", "greet"), ("tour/retry/stop", "stop"), ("tour/retry", "retry"), ("tour", "tour")
    ]


def test_leaves_come_from_the_factory_with_their_node_spec():
    rig = Rig("root: {sequence: [{speak: hi}, {wait: 2}]}\n")
    assert [(leaf.spec.kind, leaf.spec.params) for leaf in rig.root.children] == [
        ("speak", {"text": "hi"}), ("wait", {"seconds": 2})
    ]


def test_a_single_node_spec_can_be_built():
    rig = Rig("root: {sequence: [{speak: hi}]}\n")
    behaviour = build(rig.spec.root.children[0], rig.leaf, rig.clock, rig.blackboard)
    assert behaviour.spec_path == "root/speak"


def test_option_references_are_read_from_the_blackboard_at_build_time():
    rig = Rig("root: {retry: {times: $tries, child: {stop: {}}}}\n", tries=4)
    assert rig.root.num_failures == 4
    with pytest.raises(BuildError, match="option 'times' refers to blackboard key 'tries', which is not set"):
        Rig("root: {retry: {times: $tries, child: {stop: {}}}}\n")


# --- retry and repeat --------------------------------------------------------------------------

def test_retry_reruns_the_child_until_times_failures():
    rig = Rig("root: {retry: {times: 3, child: {pick: cup}}}\n", {"root/pick": "FFS"})
    assert [rig.tick() for _ in range(3)] == [Status.RUNNING, Status.RUNNING, Status.SUCCESS]
    rig = Rig("root: {retry: {times: 3, child: {pick: cup}}}\n", {"root/pick": "F"})
    assert [rig.tick() for _ in range(3)] == [Status.RUNNING, Status.RUNNING, Status.FAILURE]
    assert rig.log.count("tick root/pick") == 3


def test_repeat_counts_successes_and_minus_one_repeats_forever():
    rig = Rig("root: {repeat: {times: 2, child: {speak: hi}}}\n")
    assert [rig.tick() for _ in range(2)] == [Status.RUNNING, Status.SUCCESS]
    forever = Rig("root: {repeat: {times: -1, child: {speak: hi}}}\n")
    assert {forever.tick() for _ in range(50)} == {Status.RUNNING}
    assert forever.log.count("tick root/speak") == 50


# --- timeout -----------------------------------------------------------------------------------

def test_timeout_stops_the_child_and_fails_at_the_limit():
    rig = Rig("root: {timeout: {seconds: 5, child: {navigate: dock}}}\n", {"root/navigate": "R"})
    assert [rig.tick(at=t) for t in (0, 2, 4.9)] == [Status.RUNNING] * 3
    assert rig.tick(at=5) == Status.FAILURE
    assert rig.log == ["tick root/navigate"] * 3 + ["stop root/navigate"]
    assert rig.root.failure_reason == "timed out after 5 s"
    assert rig.find("root/navigate").status == Status.INVALID


def test_timeout_passes_through_a_child_that_finishes_in_time():
    rig = Rig("root: {timeout: {seconds: 5, child: {navigate: dock}}}\n", {"root/navigate": "RS"})
    assert [rig.tick(at=t) for t in (0, 4)] == [Status.RUNNING, Status.SUCCESS]
    assert rig.root.failure_reason == ""


def test_timeout_restarts_its_clock_when_run_again():
    rig = Rig("root: {timeout: {seconds: 5, child: {navigate: dock}}}\n", {"root/navigate": "RS"})
    rig.tick(at=0)
    rig.tick(at=4)
    rig.find("root/navigate").script = list("R")
    assert [rig.tick(at=t) for t in (100, 104)] == [Status.RUNNING, Status.RUNNING]
    assert rig.tick(at=105) == Status.FAILURE


def test_timeout_reports_a_failing_child():
    rig = Rig("root: {timeout: {seconds: 5, child: {navigate: dock}}}\n", {"root/navigate": "F"})
    assert rig.tick(at=0) == Status.FAILURE
    assert rig.root.failure_reason == "navigate failed"


# --- delay -------------------------------------------------------------------------------------

def test_delay_waits_clock_time_before_ticking_the_child():
    rig = Rig("root: {delay: {seconds: 1.5, child: {speak: hi}}}\n", {"root/speak": "RS"})
    assert [rig.tick(at=t) for t in (10, 11, 11.4)] == [Status.RUNNING] * 3
    assert rig.log == []
    assert [rig.tick(at=t) for t in (11.5, 12)] == [Status.RUNNING, Status.SUCCESS]
    assert rig.log == ["tick root/speak"] * 2


def test_delay_waits_again_on_the_next_run():
    rig = Rig("root: {delay: {seconds: 1, child: {speak: hi}}}\n")
    assert [rig.tick(at=t) for t in (0, 1, 1.5, 2.4, 2.5)] == [
        Status.RUNNING, Status.SUCCESS, Status.RUNNING, Status.RUNNING, Status.SUCCESS
    ]


# --- guard -------------------------------------------------------------------------------------

def test_guard_runs_the_child_while_the_condition_holds():
    rig = Rig("root: {guard: {condition: \"battery > 20\", child: {navigate: dock}}}\n",
              {"root/navigate": "RRS"}, battery=80)
    assert [rig.tick() for _ in range(3)] == [Status.RUNNING, Status.RUNNING, Status.SUCCESS]
    assert rig.root.failure_reason == ""


def test_guard_stops_the_child_when_the_condition_stops_holding():
    rig = Rig("root: {guard: {condition: \"battery > 20\", child: {navigate: dock}}}\n",
              {"root/navigate": "R"}, battery=80)
    assert rig.tick() == Status.RUNNING
    rig.blackboard.set("battery", 15)
    assert rig.tick() == Status.FAILURE
    assert rig.log == ["tick root/navigate", "stop root/navigate"]
    assert rig.root.failure_reason == "guard 'battery > 20' no longer holds"


def test_guard_that_does_not_hold_never_starts_the_child():
    rig = Rig("root: {guard: {condition: \"battery > 20\", child: {navigate: dock}}}\n", battery=5)
    assert rig.tick() == Status.FAILURE
    assert rig.log == []
    assert rig.root.failure_reason == "guard 'battery > 20' does not hold"


def test_guard_evaluation_error_fails_with_the_error_as_reason():
    rig = Rig("root: {guard: {condition: \"x > 1\", child: {stop: {}}}}\n")
    assert rig.tick() == Status.FAILURE
    assert rig.root.failure_reason == "guard 'x > 1' could not be evaluated: blackboard has no key 'x'"
