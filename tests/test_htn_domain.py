"""Loading HTN domains: every problem reported at once as file:line:column, like tree files;
task text and TaskIntents read into task calls."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from stuart_bt.htn import DomainLoadError, HookRegistry, TaskArgumentError, TaskCall, load_domain, load_domain_text
from stuart_bt.htn.domain import PrimitiveDef, TaskDef
from stuart_bt.htn.values import parse_task_text


def errors_of(text: str, hooks: HookRegistry | None = None) -> list[str]:
    with pytest.raises(DomainLoadError) as caught:
        load_domain_text(textwrap.dedent(text), "bad.yaml", hooks)
    return [str(e) for e in caught.value.errors]


MINIMAL = """\
domain: small
state:
  held: {default: null, doc: what the robot holds}
primitives:
  say:
    params: {text: string}
    skill: speak
    args: {text: text}
tasks:
  hello:
    methods:
      - name: say_it
        do: [say('hello')]
"""


def test_a_valid_domain_has_its_tasks_parameters_methods_and_state_variables() -> None:
    domain = load_domain_text(MINIMAL, "small.yaml")
    say, hello = domain.get("say"), domain.get("hello")
    assert isinstance(say, PrimitiveDef) and say.skill == "speak" and [p.name for p in say.params] == ["text"]
    assert isinstance(hello, TaskDef) and [m.name for m in hello.methods] == ["say_it"]
    assert domain.state_vars["held"].doc == "what the robot holds"
    assert domain.initial_state() == {"held": None}


def test_every_problem_in_a_file_is_reported_with_its_line_and_column() -> None:
    errors = errors_of("""\
        domain: broken
        state:
          held: {default: null}
        primitives:
          go:
            params: {place: place}
            skill: navigat
          grab:
            params: {obj: object}
            skill: pick
            args: {objekt: obj}
          drop:
            params: {obj: object}
            pre: helf == obj
            skill: release
          wave:
            skill: gesture
            args: {play: "'wave'"}
            effects: {mood: "'happy'"}
        tasks:
          fetch:
            params: {obj: object, place: place}
            methodz: []
          bring:
            params: {obj: object}
            methods:
              - name: a
                pre: held = obj
                do: [grab(obj), go(obj, 2)]
              - name: a
                do: [grab(obj)]
              - name: b
                pre: "__import__('os')"
                do: [fly(obj)]
              - name: c
                pre: [{hook: nope}]
                do: [grab(obj, place=1)]
        """)
    assert errors == [
        ("bad.yaml:7:12: primitives.go: unknown skill 'navigat' (did you mean 'navigate'?) "
         "(skills: navigate, approach, view, turn, pick, release, gesture, speak, find, observe, wait, stop)"),
        ("bad.yaml:11:12: primitives.grab: skill 'pick' has no parameter 'objekt' (did you mean 'object'?) "
         "(parameters: object, arm)"),
        ("bad.yaml:14:10: primitives.drop.pre: unknown name 'helf': not a parameter of 'drop' (obj) "
         "nor a state variable (did you mean 'held'?)"),
        "bad.yaml:19:15: primitives.wave.effects: effect on 'mood', which is not a declared state variable",
        "bad.yaml:21:3: tasks.fetch: task 'fetch' needs 'methods:' (a list of {name, pre, do})",
        ("bad.yaml:23:5: tasks.fetch: unknown key 'methodz' (did you mean 'methods'?) "
         "(expected: doc, params, intent, ack, methods)"),
        "bad.yaml:28:19: tasks.bring/a.pre: syntax error in expression 'held = obj': invalid syntax",
        "bad.yaml:29:25: tasks.bring/a.do: go(place) takes 1 argument(s), got 2",
        "bad.yaml:30:9: tasks.bring: method name 'a' is used twice in task 'bring'",
        ("bad.yaml:33:14: tasks.bring/b.pre: only these functions may be called: len, abs, min, max, round "
         "in \"__import__('os')\""),
        "bad.yaml:34:14: tasks.bring/b.do: unknown task 'fly'",
        "bad.yaml:36:22: tasks.bring/c.pre: unknown condition hook 'nope' (registered: none)",
        "bad.yaml:37:24: tasks.bring/c.do: grab(obj) has no parameter 'place'",
    ]


def test_a_yaml_syntax_error_names_the_file_and_line(tmp_path: Path) -> None:
    path = tmp_path / "domain.yaml"
    path.write_text("domain: x\ntasks:\n  a: [unclosed\n", encoding="utf-8")
    with pytest.raises(DomainLoadError) as caught:
        load_domain(path)
    [error] = caught.value.errors
    assert str(error).startswith(f"{path}:4:1: YAML syntax error")


def test_skill_arguments_are_checked_against_the_catalogue() -> None:
    errors = errors_of("""\
        domain: d
        primitives:
          walk:
            skill: navigate
          mixed:
            skill: navigate
            args: {marker: "'kitchen'", dx: 1.0}
          speak_nothing:
            skill: speak
            args: {}
        tasks: {}
        """)
    assert errors == [
        ("bad.yaml:3:3: primitives.walk: skill 'navigate' needs one of the alternatives "
         "(marker) | (x, y, yaw) | (dx, dy, dyaw): give them under 'args:'"),
        ("bad.yaml:7:11: primitives.mixed: skill 'navigate' mixes the alternatives "
         "(marker) | (x, y, yaw) | (dx, dy, dyaw)"),
        "bad.yaml:10:11: primitives.speak_nothing: skill 'speak' needs 'text'",
    ]


def test_hooks_are_checked_for_name_kind_and_parameters() -> None:
    hooks = HookRegistry()

    @hooks.condition
    def reachable(state: object, obj: str) -> bool:
        return True

    @hooks.function
    def standoff(state: object, obj: str) -> dict[str, float]:
        return {}

    errors = errors_of("""\
        domain: d
        primitives:
          approach:
            params: {obj: object}
            pre:
              - {hook: standoff}
              - {hook: reachable, args: {thing: obj}}
              - {hook: reachabel}
            skill: navigate
            args: {hook: reachable}
        tasks: {}
        """, hooks)
    assert errors == [
        "bad.yaml:6:16: primitives.approach.pre: hook 'standoff' is a function hook; a condition hook is needed here",
        "bad.yaml:7:9: primitives.approach.pre: hook 'reachable' needs 'obj'",
        "bad.yaml:7:34: primitives.approach.pre: hook 'reachable' has no parameter 'thing' (parameters: obj)",
        ("bad.yaml:8:16: primitives.approach.pre: unknown condition hook 'reachabel' (did you mean 'reachable'?) "
         "(registered: reachable)"),
        ("bad.yaml:10:18: primitives.approach.args: hook 'reachable' is a condition hook; "
         "a function hook is needed here"),
    ]


def test_names_parameters_and_acknowledgements_are_checked() -> None:
    errors = errors_of("""\
        domain: d
        state:
          held: {default: null}
        primitives:
          say:
            params: {text: strin, held: {type: object, default: null}}
            skill: speak
            args: {text: text}
        tasks:
          greet:
            ack: "Hello {nme}"
            methods:
              - name: hi
                do: [say('hi')]
        """)
    assert errors == [
        ("bad.yaml:6:20: primitives.say.params: unknown type 'strin' (did you mean 'string'?) (types: place, object, "
         "string, gesture, number, angle, integer, boolean, list, places, task, tasks, any)"),
        "bad.yaml:6:27: primitives.say.params: parameter 'held' would hide the state variable of that name; rename it",
        ("bad.yaml:11:10: tasks.greet: 'ack' needs a primitive 'acknowledge' with one string parameter (the text to "
         "say); define it under 'primitives:' or name another with 'ack_with:'"),
        "bad.yaml:11:18: tasks.greet.ack: unknown name 'nme': not a parameter of 'greet' nor a state variable",
    ]


def test_subtasks_with_several_arguments_may_be_written_in_a_flow_list() -> None:
    domain = load_domain_text(textwrap.dedent("""\
        domain: d
        primitives:
          step:
            params: {dx: number, dy: number, dyaw: angle}
            skill: navigate
            args: {dx: dx, dy: dy, dyaw: dyaw}
        tasks:
          shuffle:
            methods:
              - name: left_right
                do: [step(0, 0.5, 0), step(0, -0.5, 0)]
        """))
    method = domain.get("shuffle").methods[0]  # type: ignore[union-attr]
    assert [s.text for s in method.subtasks] == ["step(0, 0.5, 0)", "step(0, -0.5, 0)"]
    assert [str(s.location) for s in method.subtasks] == ["<domain>:11:14", "<domain>:11:31"]


# -- task text and intents ------------------------------------------------------------------------------
def test_task_text_reads_words_numbers_lists_and_nested_tasks() -> None:
    assert parse_task_text("fetch(bottle, workbench)") == [TaskCall("fetch", ("bottle", "workbench"))]
    assert parse_task_text("move_relative(x=1.5, yaw=-0.5); turn_around") == [
        TaskCall("move_relative", (), (("x", 1.5), ("yaw", -0.5))), TaskCall("turn_around")]
    assert parse_task_text("do_all([navigate_to_marker(kitchen), gesture('high wave')])") == [
        TaskCall("do_all", ([TaskCall("navigate_to_marker", ("kitchen",)), TaskCall("gesture", ("high wave",))],))]
    with pytest.raises(TaskArgumentError, match=r"quote names with spaces: gesture\('high wave'\)"):
        parse_task_text("gesture(high wave)")
    with pytest.raises(TaskArgumentError, match="is not a value"):
        parse_task_text("fetch(bottle + 1, kitchen)")


def test_one_task_call_reads_from_its_text_and_only_one() -> None:
    assert TaskCall.parse("fetch(bottle, workbench)") == TaskCall("fetch", ("bottle", "workbench"))
    assert TaskCall.parse("turn_around") == TaskCall("turn_around")
    with pytest.raises(TaskArgumentError, match="expected one task, got 2 in 'greet; turn_around'"):
        TaskCall.parse("greet; turn_around")
    with pytest.raises(TaskArgumentError, match="quote names with spaces"):
        TaskCall.parse("gesture(high wave)")


def test_task_intents_become_the_tasks_their_actions_name() -> None:
    domain = load_domain_text(textwrap.dedent("""\
        domain: d
        primitives:
          go:
            params: {place: place}
            skill: navigate
            args: {marker: place}
        tasks:
          navigate_to_marker:
            params: {place: place}
            intent: {place: target}
            methods: [{name: walk, do: [go(place)]}]
          turn_around:
            intent: {}
            methods: [{name: nothing, do: []}]
        """))
    calls = domain.calls_from_text('[{"action": "navigate_to_marker", "target": "kitchen", "x": null, '
                                   '"raw_text": "go"}, {"action": "turn_around"}]')
    assert calls == [TaskCall("navigate_to_marker", (), (("place", "kitchen"),)), TaskCall("turn_around")]
    with pytest.raises(TaskArgumentError, match="intent 1: unknown action 'navigate_to_markr' "
                                                "\\(did you mean 'navigate_to_marker'\\?\\)"):
        domain.calls_from_intents([{"action": "navigate_to_markr", "target": "kitchen"}])
