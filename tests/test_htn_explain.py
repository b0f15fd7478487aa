"""Plans explain themselves: the decomposition as text, methods chosen and rejected with their
reasons, failures nested to the root cause, JSON, and the ``stuart-bt plan`` command."""

from __future__ import annotations

import argparse
import json
import textwrap
from pathlib import Path

import pytest

from stuart_bt.cli.plan import add_command
from stuart_bt.htn import Planner, PlanningFailed, explain, load_domain_text, parse_task_text

ERRANDS = textwrap.dedent("""\
    domain: errands
    state:
      at: {default: entrance}
      held: {default: null}
      markers: {default: {entrance: {}, kitchen: {}, office: {}}}
      door_open: {default: false}
    primitives:
      go:
        params: {place: place}
        pre: place in markers
        skill: navigate
        args: {marker: place}
        effects: {at: place}
      open_door:
        pre: held == null
        skill: gesture
        args: {play: "'hands up'"}
        effects: {door_open: true}
      knock:
        skill: speak
        args: {text: "'knock knock'"}
      enter:
        pre: door_open
        skill: navigate
        args: {dx: 1.0}
    tasks:
      visit:
        params: {place: place}
        methods:
          - name: already_there
            pre: at == place
            do: []
          - name: walk_in
            do: [go(place), get_in]
      get_in:
        methods:
          - name: knock_and_wait
            do: [knock, enter]
          - name: open_it
            do: [open_door, enter]
    """)


def plan_text(task: str, **state: object) -> str:
    domain = load_domain_text(ERRANDS)
    return explain(Planner(domain).plan(parse_task_text(task), {**domain.initial_state(), **state}))


def test_the_explanation_shows_methods_chosen_rejected_and_the_steps_with_their_effects() -> None:
    assert plan_text("visit(office)") == textwrap.dedent("""\
        mission
        └─ visit(office)  [walk_in]
           │  ✗ already_there: at == place is false (at='entrance', place='office')
           ├─ 1. go(office) → navigate(marker='office')  ⇒ at='office'
           └─ get_in()  [open_it]
              │  ✗ knock_and_wait: a subtask failed: enter(): precondition not met: door_open is false (door_open=false)
              ├─ 2. open_door() → gesture(play='hands up')  ⇒ door_open=true
              └─ 3. enter() → navigate(dx=1)""")


def test_rejections_and_effects_can_be_left_out_and_ascii_drawn() -> None:
    domain = load_domain_text(ERRANDS)
    plan = Planner(domain).plan(parse_task_text("visit(office)"))
    assert explain(plan, rejections=False, effects=False, ascii=True) == textwrap.dedent("""\
        mission
        `- visit(office)  [walk_in]
           |- 1. go(office) -> navigate(marker='office')
           `- get_in()  [open_it]
              |- 2. open_door() -> gesture(play='hands up')
              `- 3. enter() -> navigate(dx=1)""")


def test_a_failure_is_explained_down_to_its_root_cause() -> None:
    domain = load_domain_text(ERRANDS)
    with pytest.raises(PlanningFailed) as caught:
        Planner(domain).plan(parse_task_text("visit(office)"), {**domain.initial_state(), "held": "tray"})
    assert str(caught.value) == textwrap.dedent("""\
        no plan for visit(office):
          get_in(): no method works
            ✗ knock_and_wait: a subtask failed:
              enter(): precondition not met: door_open is false (door_open=false)
            ✗ open_it: a subtask failed:
              open_door(): precondition not met: held == null is false (held='tray')""")
    assert explain(caught.value) == textwrap.dedent("""\
        mission
        └─ visit(office)  [walk_in]
           │  ✗ already_there: at == place is false (at='entrance', place='office')
           ├─ 1. go(office) → navigate(marker='office')  ⇒ at='office'
           └─ get_in()  [open_it]
              │  ✗ knock_and_wait: a subtask failed: enter(): precondition not met: door_open is false (door_open=false)
              ├─ open_door()  ✗ precondition not met: held == null is false (held='tray')
              └─ enter()  (not reached)""")


def test_the_json_form_keeps_the_tree_the_steps_and_the_rejections() -> None:
    doc = json.loads(json.dumps(Planner(load_domain_text(ERRANDS)).plan(parse_task_text("visit(office)")).to_dict()))
    assert doc["ok"] is True and doc["tasks"] == ["visit(office)"]
    assert [(s["step"], s["skill"], s["args"]) for s in doc["steps"]] == [
        (1, "navigate", {"marker": "office"}), (2, "gesture", {"play": "hands up"}), (3, "navigate", {"dx": 1.0})]
    get_in = next(n for n in doc["nodes"] if n["name"] == "get_in")
    assert get_in["method"] == "open_it"
    [rejected] = get_in["rejected"]
    assert rejected["method"] == "knock_and_wait" and rejected["kind"] == "subtask"
    assert rejected["failure"]["task"] == "enter()"
    assert doc["nodes"][get_in["parent"]]["name"] == "visit"
    assert doc["state"]["door_open"] is True


# -- the CLI command ------------------------------------------------------------------------------------
def run_cli(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    parser = argparse.ArgumentParser(prog="stuart-bt")
    add_command(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(argv)
    code = args.func(args)
    out, err = capsys.readouterr()
    return code, out, err


def test_plan_prints_the_decomposition_and_the_steps(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(capsys, "plan", "navigate_to_marker(kitchen)")
    assert code == 0
    assert out.startswith("plan for navigate_to_marker(kitchen): 2 steps (")
    assert "└─ navigate_to_marker(kitchen)  [walk]\n   │  ✗ already_there: at == place is false " \
           "(at='entrance', place='kitchen')" in out
    assert out.endswith("steps:\n  1. speak(text='Navigating to the kitchen')\n  2. navigate(marker='kitchen')\n")


def test_plan_takes_a_json_list_of_task_intents(capsys: pytest.CaptureFixture[str]) -> None:
    intents = json.dumps([{"action": "navigate_to_marker", "target": "kitchen", "raw_text": "go to the kitchen"},
                          {"action": "gesture", "target": "wave"}])
    code, out, _ = run_cli(capsys, "plan", intents, "--json")
    doc = json.loads(out)
    assert code == 0
    assert doc["tasks"] == ["navigate_to_marker(kitchen)", "gesture(wave)"]
    assert [s["args"] for s in doc["steps"]] == [
        {"text": "Navigating to the kitchen"}, {"marker": "kitchen"}, {"text": "Doing a wave"}, {"play": "wave"}]


def test_plan_reads_a_start_state_file(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    state = tmp_path / "state.json"
    state.write_text(json.dumps({"at": "dock", "held": "cup", "markers": {"dock": {"x": 0, "y": 0, "yaw": 0},
                                                                       "desk": {"x": 2, "y": 0, "yaw": 0}}}))
    code, out, _ = run_cli(capsys, "plan", "fetch(cup, desk)", "--state", str(state), "--no-rejections")
    assert code == 0
    assert "fetch(cup, desk)  [already_holding]" in out
    assert "acknowledge('Fetching the cup for the desk')" in out  # names filled in from the marker names
    assert "✗" not in out


def test_plan_exits_1_with_the_reason_when_there_is_no_plan(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(capsys, "plan", "navigate_to_marker(kitchn)")
    assert code == 1
    assert out.splitlines()[:4] == [
        "no plan for navigate_to_marker(kitchn):",
        "  navigate_to_marker(kitchn): no method applies",
        "    ✗ already_there: at == place is false (at='entrance', place='kitchn')",
        ("    ✗ walk: place in markers is false (place='kitchn', markers={entrance, charging_dock, kitchen, bathroom, "
         "workbench, station_1, +5 more}) (did you mean 'kitchen'?)"),
    ]
    code, out, _ = run_cli(capsys, "plan", "navigate_to_marker(kitchn)", "--json")
    assert code == 1 and json.loads(out)["ok"] is False


def test_plan_reports_bad_task_text_and_bad_state_files(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, _, err = run_cli(capsys, "plan", "gesture(high wave)")
    assert code == 1 and "quote names with spaces" in err
    bad = tmp_path / "state.json"
    bad.write_text("{not json")
    code, _, err = run_cli(capsys, "plan", "greet", "--state", str(bad))
    assert code == 1 and f"{bad}:1:2: not valid JSON" in err
