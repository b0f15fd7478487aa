"""The HTN planner's semantics on small domains: method order, preconditions with bound
parameters, effects seen by later steps, backtracking (below and across tasks), budgets, deep
plans without recursion, determinism."""

from __future__ import annotations

import json

import pytest

from stuart_bt.core.errors import StuartError
from stuart_bt.htn import (
    HookRegistry,
    Plan,
    Planner,
    PlannerInputError,
    PlanningBudgetExceeded,
    PlanningFailed,
    State,
    TaskArgumentError,
    TaskCall,
    explain,
    load_domain_text,
    parse_task_text,
)

KITCHEN = """
domain: kitchen
ack_with: say
state:
  at: {default: entrance}
  held: {default: null}
  objects: {default: {bottle: kitchen, cup: workbench}}
  markers: {default: {entrance: {x: 0, y: 0}, kitchen: {x: 3, y: 1}, workbench: {x: 1, y: -2}}}
  trail: {default: []}
primitives:
  say:
    params: {text: string}
    skill: speak
    args: {text: text}
  go:
    params: {place: place}
    pre: place in markers
    skill: navigate
    args: {marker: place}
    effects: {at: place, trail: "trail + [place]"}
  pick:
    params: {obj: object}
    pre: held == null and objects[obj] == at
    skill: pick
    args: {object: obj}
    effects: {held: obj}
    remove: ["objects[obj]"]
  drop:
    params: {obj: object}
    pre: held == obj
    skill: release
    effects: {held: null, "objects[obj]": at}
  wave:
    pre: held == null
    skill: gesture
    args: {play: "'high wave'"}
tasks:
  fetch:
    params: {obj: object, place: place}
    methods:
      - name: holding
        pre: held == obj
        do: [go(place), drop(obj)]
      - name: known
        pre: obj in objects
        do: ["go(objects[obj])", pick(obj), go(place), drop(obj)]
  greet:
    methods:
      - name: wave_first
        do: [wave, say('hello')]
      - name: just_say
        do: [say('hello')]
"""


def kitchen(**kw: object) -> Planner:
    return Planner(load_domain_text(KITCHEN), **kw)  # type: ignore[arg-type]


def skills(plan: Plan) -> list[str]:
    return [f"{s.skill} {json.dumps(s.skill_args, sort_keys=True)}" for s in plan.primitives()]


# -- order, preconditions, effects ---------------------------------------------------------------------
def test_methods_are_tried_in_order_and_the_first_applicable_one_is_used() -> None:
    plan = kitchen().plan(parse_task_text("greet"))
    greet = plan.tasks[0]
    assert greet.method == "wave_first"
    assert greet.rejected == []
    assert [s.call for s in plan.primitives()] == ["wave()", "say(hello)"]


def test_a_precondition_reads_bound_parameters_and_state_variables() -> None:
    plan = kitchen().plan(parse_task_text("fetch(bottle, workbench)"))
    fetch = plan.tasks[0]
    assert fetch.method == "known"
    [rejected] = fetch.rejected
    assert rejected.method == "holding" and rejected.kind == "precondition"
    assert str(rejected.reason) == "held == obj is false (held=null, obj='bottle')"


def test_effects_are_seen_by_later_steps_and_the_final_state_is_predicted() -> None:
    plan = kitchen().plan(parse_task_text("fetch(bottle, workbench)"))
    assert skills(plan) == [
        'navigate {"marker": "kitchen"}',      # go(objects[obj]): the index is the bound parameter
        'pick {"object": "bottle"}',           # pre objects[obj] == at holds after the walk
        'navigate {"marker": "workbench"}',
        "release {}",                          # pre held == obj holds after the pick
    ]
    assert plan.state["held"] is None
    assert plan.state["objects"] == {"bottle": "workbench", "cup": "workbench"}
    assert plan.state["trail"] == ["kitchen", "workbench"]


def test_a_second_task_plans_against_the_state_the_first_one_leaves() -> None:
    plan = kitchen().plan(parse_task_text("fetch(bottle, workbench); fetch(bottle, entrance)"))
    second = plan.tasks[1]
    assert second.children[0].call == "go(workbench)"  # where the first fetch put the bottle
    assert plan.state["objects"]["bottle"] == "entrance"


def test_the_callers_state_is_never_changed() -> None:
    state = State(at="entrance", held=None, objects={"bottle": "kitchen"},
                  markers={"entrance": {}, "kitchen": {}, "workbench": {}}, trail=[])
    before = {k: (dict(v) if isinstance(v, dict) else v) for k, v in state.items()}
    kitchen().plan(parse_task_text("fetch(bottle, workbench)"), state)
    assert dict(state) == before


# -- backtracking ---------------------------------------------------------------------------------------
ROUTES = """
domain: routes
state:
  via: {default: null}
  log: {default: []}
  bridge_open: {default: false}
primitives:
  take:
    params: {route: string}
    skill: navigate
    args: {marker: route}
    effects: {via: route, log: "log + [route]"}
  cross:
    pre: via != 'bridge' or bridge_open
    skill: navigate
    args: {dx: 1.0}
    effects: {log: "log + ['crossed']"}
tasks:
  trip:
    methods:
      - name: by_road
        do: [choose, cross]
  choose:
    methods:
      - name: bridge
        do: [take('bridge')]
      - name: tunnel
        do: [take('tunnel')]
"""


def test_a_later_failure_makes_the_planner_try_the_next_method_of_an_earlier_task() -> None:
    plan = Planner(load_domain_text(ROUTES)).plan(parse_task_text("trip"))
    choose = plan.tasks[0].children[0]
    assert choose.method == "tunnel"
    [bridge] = choose.rejected
    assert bridge.kind == "later"                               # it worked; `cross` after it did not
    assert bridge.reason.task == "cross()"
    assert "via != 'bridge' or bridge_open is false" in bridge.reason.message
    assert plan.state["log"] == ["tunnel", "crossed"]          # the abandoned branch's effects are undone
    assert plan.stats.backtracks == 1


def test_without_backtracking_the_first_commitment_is_final_as_in_gtpyhop() -> None:
    with pytest.raises(PlanningFailed) as caught:
        Planner(load_domain_text(ROUTES), backtracking=False).plan(parse_task_text("trip"))
    assert caught.value.failure.task == "cross()"


def test_a_failure_below_a_method_rejects_it_as_a_failed_subtask() -> None:
    plan = kitchen().plan(parse_task_text("greet"), {**load_domain_text(KITCHEN).initial_state(), "held": "cup"})
    greet = plan.tasks[0]
    assert greet.method == "just_say"
    [wave_first] = greet.rejected
    assert wave_first.kind == "subtask"
    assert wave_first.summary() == ("wave_first: a subtask failed: wave(): precondition not met: "
                                    "held == null is false (held='cup')")


def test_when_nothing_works_the_failure_names_the_clause_and_the_values() -> None:
    with pytest.raises(PlanningFailed) as caught:
        kitchen().plan(parse_task_text("fetch(bottle, moon)"))
    failure = caught.value.failure
    assert failure.task == "go(moon)"
    assert failure.path == "fetch(bottle, moon) > go(moon)"
    assert "place in markers is false (place='moon', markers={entrance, kitchen, workbench})" in failure.message


# -- hooks, loops, task values -------------------------------------------------------------------------
def test_condition_and_function_hooks_are_called_with_the_state_and_bound_arguments() -> None:
    hooks = HookRegistry()
    seen: list[tuple[str, object]] = []

    @hooks.condition
    def heavy(state: State, obj: str) -> bool:
        seen.append(("heavy", obj))
        return obj in state["weights"] and state["weights"][obj] > 1.0

    @hooks.function
    def double(state: State, x: float) -> float:
        return 2 * x

    domain = load_domain_text("""
domain: hooks
state:
  weights: {default: {anvil: 50.0, feather: 0.01}}
primitives:
  lift:
    params: {obj: object}
    skill: pick
    args: {object: obj}
  step:
    params: {d: number}
    skill: navigate
    args: {dx: {hook: double, args: {x: d}}}
tasks:
  carry:
    params: {obj: object}
    methods:
      - name: two_steps
        pre: [{hook: heavy}]
        do: [step(0.5), lift(obj)]
      - name: one_step
        do: [lift(obj)]
""", hooks=hooks)
    heavy_plan = Planner(domain).plan(parse_task_text("carry(anvil)"))
    assert skills(heavy_plan) == ['navigate {"dx": 1.0}', 'pick {"object": "anvil"}']
    light_plan = Planner(domain).plan(parse_task_text("carry(feather)"))
    assert str(light_plan.tasks[0].rejected[0].reason) == "hook heavy(obj='feather') returned false"
    assert seen == [("heavy", "anvil"), ("heavy", "feather")]


def test_for_loops_and_task_values_expand_in_order() -> None:
    domain = load_domain_text("""
domain: loops
primitives:
  say:
    params: {text: string}
    skill: speak
    args: {text: text}
tasks:
  count:
    params: {words: list}
    methods:
      - name: each
        do:
          - for: w
            in: words
            do: ["say('say ' + w)"]
  do_all:
    params: {tasks: tasks}
    methods:
      - name: in_order
        do:
          - for: t
            in: tasks
            do:
              - run: t
""")
    plan = Planner(domain).plan(parse_task_text("do_all([count([one, two]), say(three)])"))
    assert [s.skill_args["text"] for s in plan.primitives()] == ["say one", "say two", "three"]


def test_the_planner_takes_a_list_of_task_calls_which_named_converters_make() -> None:
    planner = kitchen()
    by_text = skills(planner.plan(planner.domain.calls_from_text("fetch(bottle, workbench)")))
    assert skills(planner.plan([TaskCall.parse("fetch(bottle, workbench)")])) == by_text
    assert skills(planner.plan([TaskCall("fetch", ("bottle", "workbench"))])) == by_text
    assert skills(planner.plan((TaskCall("fetch", (), (("obj", "bottle"), ("place", "workbench"))),))) == by_text


@pytest.mark.parametrize(("given", "says"), [
    ("fetch(bottle, workbench)",
     "got task text 'fetch(bottle, workbench)': convert it with domain.calls_from_text(text) "
     "(or [TaskCall.parse(text)] for one task)"),
    (TaskCall("greet"), "got one TaskCall greet(): put it in a list, [call]"),
    ({"action": "greet"}, "got a TaskIntent {'action': 'greet'}: convert TaskIntents with "
                          "domain.calls_from_intents(intents)"),
    (["fetch", "bottle", "workbench"], "item 1 of the list is task text 'fetch': convert it with"),
    ([TaskCall("greet"), {"action": "greet"}], "item 2 of the list is a TaskIntent {'action': 'greet'}"),
    (None, "got NoneType None"),
])
def test_any_other_input_is_refused_with_what_was_given_and_what_is_expected(given: object, says: str) -> None:
    with pytest.raises(PlannerInputError) as caught:
        kitchen().plan(given)  # type: ignore[arg-type]
    assert str(caught.value).startswith("Planner.plan takes a list of TaskCall; ")
    assert says in str(caught.value)
    assert isinstance(caught.value, StuartError) and caught.value.code == "planner_input"


def test_unknown_tasks_and_bad_arguments_are_input_errors() -> None:
    planner = kitchen()
    with pytest.raises(TaskArgumentError, match="unknown task 'fecth' \\(did you mean 'fetch'\\?\\)"):
        planner.plan(parse_task_text("fecth(bottle, workbench)"))
    with pytest.raises(TaskArgumentError, match=r"fetch\(obj, place\): missing 'place'"):
        planner.plan(parse_task_text("fetch(bottle)"))
    with pytest.raises(TaskArgumentError, match="'obj' must be an object label, got 3"):
        planner.plan(parse_task_text("fetch(3, kitchen)"))


# -- budgets, depth, determinism ------------------------------------------------------------------------
COUNTER = """
domain: counter
state:
  count: {default: 0}
primitives:
  tick:
    skill: wait
    args: {seconds: 0}
    effects: {count: count + 1}
tasks:
  repeat:
    params: {n: integer}
    methods:
      - name: done
        pre: n == 0
        do: []
      - name: again
        pre: n > 0
        do: [tick, repeat(n - 1)]
  forever:
    methods:
      - name: again
        do: [tick, forever]
"""


def test_a_5000_step_recursive_plan_needs_no_recursion() -> None:
    plan = Planner(load_domain_text(COUNTER)).plan(parse_task_text("repeat(5000)"))
    assert len(plan.primitives()) == 5000
    assert plan.state["count"] == 5000
    assert plan.stats.max_depth == 5001
    assert explain(plan).count("tick()") == 5000                # drawn without recursion
    assert len(json.loads(json.dumps(plan.to_dict()))["nodes"]) == 10002  # flat node table: json copes


def test_the_expansion_budget_stops_the_search_and_says_how_far_it_got() -> None:
    with pytest.raises(PlanningBudgetExceeded) as caught:
        Planner(load_domain_text(COUNTER), max_expansions=100).plan(parse_task_text("forever"))
    e = caught.value
    assert e.limit == "expansions" and e.expansions == 101
    assert e.steps == 50                                          # tick, forever, tick, forever, ...
    assert e.current.startswith("forever() > forever() > forever() > ...")
    assert "expansion budget of 100 expansions used up" in str(e)


def test_the_time_budget_stops_the_search() -> None:
    with pytest.raises(PlanningBudgetExceeded) as caught:
        Planner(load_domain_text(COUNTER), time_limit=0.0).plan(parse_task_text("forever"))
    assert caught.value.limit == "seconds"
    assert caught.value.steps > 0


def test_the_same_input_gives_the_same_plan() -> None:
    def run() -> dict[str, object]:
        out = Planner(load_domain_text(ROUTES)).plan(parse_task_text("trip")).to_dict()
        out.pop("stats")
        return out

    assert run() == run()
