"""The YAML tree language loads into the right TreeSpec: kinds, paths, params, includes."""

from __future__ import annotations

import os
import textwrap
from pathlib import Path

import pytest

from stuart_bt.tree.errors import TreeLoadError
from stuart_bt.tree.loader import load_tree, load_tree_text
from stuart_bt.tree.spec import Location, TreeSpec

REPO = Path(__file__).parent.parent
DATA = Path(__file__).parent / "data"
TREES = DATA / "trees"
MARKERS = DATA / "markers.json"


def load(text: str, **kw) -> TreeSpec:
    return load_tree_text(textwrap.dedent(text), file="t.yaml", **kw)


def paths(spec: TreeSpec) -> list[str]:
    return [n.path for n in spec.walk()]


def test_compact_sequence_of_shorthand_leaves():
    spec = load("""
        root:
          sequence:
            - navigate: kitchen
            - speak: "Hello"
            - wait: 2
            - condition: "battery > 20"
    """)
    assert spec.root.kind == "sequence"
    assert [(n.kind, n.params) for n in spec.root.children] == [
        ("navigate", {"marker": "kitchen"}),
        ("speak", {"text": "Hello"}),
        ("wait", {"seconds": 2}),
        ("condition", {"expr": "battery > 20"}),
    ]


def test_root_is_named_after_the_file_stem_or_root_for_text(tmp_path):
    tree = tmp_path / "greeting.yaml"
    tree.write_text("root: {speak: hi}\n")
    assert load_tree(tree).root.path == "greeting"
    assert load_tree_text("root: {speak: hi}\n").root.path == "root"


def test_child_segments_use_kind_when_unique_and_kind_n_when_repeated():
    spec = load("""
        root:
          sequence:
            - navigate: kitchen
            - speak: one
            - navigate: dock
            - stop: {}
    """)
    assert paths(spec) == ["t", "t/navigate_1", "t/speak", "t/navigate_2", "t/stop"]


def test_explicit_names_become_segments_and_numbering_still_counts_them():
    spec = load("""
        root:
          sequence:
            name: tour
            children:
              - speak: {text: hi, name: greet}
              - speak: bye
              - selector:
                  name: fallback
                  children: [{stop: {}}]
    """)
    assert paths(spec) == ["tour", "tour/greet", "tour/speak_2", "tour/fallback", "tour/fallback/stop"]
    assert spec.find("tour/greet").name == "greet"


def test_defaults_are_not_filled_in():
    spec = load("root: {speak: hi}\n")
    assert spec.root.params == {"text": "hi"}


def test_empty_and_null_leaf_bodies_have_no_params():
    spec = load("root: {sequence: [{stop: {}}, {stop: null}]}\n")
    assert [c.params for c in spec.root.children] == [{}, {}]


def test_composite_options_are_kept_and_memory_is_not_defaulted():
    spec = load("""
        root:
          sequence:
            memory: false
            children:
              - selector: {memory: true, children: [{stop: {}}]}
              - parallel: {policy: one, synchronise: false, children: [{stop: {}}]}
              - selector: [{stop: {}}]
    """)
    assert spec.root.params == {"memory": False}
    assert [c.params for c in spec.root.children] == [
        {"memory": True}, {"policy": "one", "synchronise": False}, {}
    ]


def test_every_decorator_keeps_its_options_and_single_child():
    spec = load("""
        root:
          sequence:
            - retry: {times: 3, child: {stop: {}}}
            - repeat: {times: -1, child: {stop: {}}}
            - timeout: {seconds: 5, child: {stop: {}}}
            - inverter: {child: {stop: {}}}
            - force_success: {child: {stop: {}}}
            - force_failure: {child: {stop: {}}}
            - oneshot: {on: success, child: {stop: {}}}
            - guard: {condition: "battery > 10", child: {stop: {}}}
            - delay: {seconds: 1.5, child: {stop: {}}}
    """)
    got = {c.kind: (c.params, [g.path for g in c.children]) for c in spec.root.children}
    assert got["retry"] == ({"times": 3}, ["t/retry/stop"])
    assert got["repeat"][0] == {"times": -1}
    assert got["timeout"][0] == {"seconds": 5}
    assert got["inverter"][0] == {}
    assert got["oneshot"][0] == {"on": "success"}
    assert got["guard"][0] == {"condition": "battery > 10"}
    assert got["delay"][0] == {"seconds": 1.5}
    assert all(len(c.children) == 1 for c in spec.root.children)


def test_leaf_name_and_timeout():
    spec = load("root: {pick: {object: cup, arm: left, timeout: 30, name: grab}}\n")
    assert spec.root.path == "grab"
    assert spec.root.params == {"object": "cup", "arm": "left", "timeout": 30}


def test_every_construct_file_loads_with_expected_paths_and_params():
    spec = load_tree(TREES / "all_constructs.yaml")
    assert spec.description.startswith("Every node kind")
    assert spec.find("everything/step_forward").params == {"dx": 0.5}
    assert spec.find("everything/navigate_2").params == {"x": 1.5, "y": -2, "yaw": 0.5, "tolerance": 0.2}
    assert spec.find("everything/gesture_2").params == {"sequence": ["clap", "high five"], "wait": False}
    assert spec.find("everything/speak_2").params == {"text": "$greeting", "wait": False}
    assert spec.find("everything/walk_and_talk").params["selected"] == ["go"]
    assert spec.find("everything/walk_and_talk/go").kind == "navigate"
    assert spec.find("everything/powered/navigate").params == {"marker": "dock"}
    kinds = {n.kind for n in spec.walk()}
    assert kinds >= {"sequence", "selector", "parallel", "retry", "repeat", "timeout", "inverter",
                     "force_success", "force_failure", "oneshot", "guard", "delay", "navigate", "turn",
                     "pick", "release", "gesture", "speak", "find", "wait", "stop", "condition", "set", "log"}


def test_locations_are_one_based_and_params_remember_theirs():
    spec = load("""
        root:
          sequence:
            - speak: {text: hi, wait: false}
    """)
    speak = spec.root.children[0]
    assert speak.location == Location("t.yaml", 4, 7)
    assert speak.param_locations == {"text": Location("t.yaml", 4, 21), "wait": Location("t.yaml", 4, 31)}


def test_top_level_keys_fill_the_tree_spec():
    spec = load_tree(TREES / "all_constructs.yaml")
    assert spec.blackboard == {"battery": 80, "visitor": "Ada"}
    assert spec.markers_file == os.path.normpath(TREES / ".." / "markers.json")
    assert spec.params == {}
    assert spec.file == str(TREES / "all_constructs.yaml")


def test_markers_file_argument_overrides_the_tree_key(tmp_path):
    other = tmp_path / "other.json"
    other.write_text('{"frame": "map", "markers": {"lab": {"x": 1, "y": 2}}}')
    tree = tmp_path / "t.yaml"
    tree.write_text(f"markers: {MARKERS}\nroot: {{navigate: lab}}\n")
    assert load_tree(tree, markers_file=other).markers_file == str(other)
    with pytest.raises(TreeLoadError, match="unknown marker 'lab'"):
        load_tree(tree)


def test_include_substitutes_arguments_and_names_roots_after_the_file_stem():
    spec = load_tree(TREES / "tour.yaml")
    assert [c.path for c in spec.root.children] == [
        "tour/speak", "tour/station_1", "tour/station_2", "tour/station_3", "tour/home"
    ]
    assert spec.find("tour/station_2/navigate").params == {"marker": "station_2"}
    assert spec.find("tour/station_2/present/speak").params == {"text": "This is the printers."}
    assert spec.find("tour/station_2/present/gesture").params == {"play": "clap"}


def test_nested_include_uses_declared_defaults_when_arguments_are_omitted():
    spec = load_tree(TREES / "tour.yaml")
    assert spec.find("tour/station_1/present/gesture").params == {"play": "high wave"}  # station's default
    assert spec.find("tour/station_1/present/wait").params == {"seconds": 0.5}  # present's default


def test_included_roots_record_their_file():
    spec = load_tree(TREES / "tour.yaml")
    assert spec.find("tour/station_1").include == os.path.normpath(TREES / "station.yaml")
    assert spec.find("tour/station_1/present").include == os.path.normpath(TREES / "present.yaml")
    assert spec.root.include is None


def test_includer_blackboard_values_win_and_the_rest_merge():
    spec = load_tree(TREES / "tour.yaml")
    assert spec.blackboard == {"battery": 90, "stations_seen": 0}


@pytest.mark.parametrize("written", ["Electronics bench", "electronics BENCH", "ElectronicsBench",
                                     "electronics_bench", "  electronics   bench ", "Station 4", "station_4"])
def test_a_marker_can_be_named_by_its_display_name_in_any_case_and_spacing(written):
    spec = load(f"""
        markers: {REPO / "sim" / "maps" / "lab_markers.json"}
        root:
          sequence:
            - navigate: {written!r}
            - navigate: {{marker: {written!r}, tolerance: 0.2}}
        """)
    assert [n.params["marker"] for n in spec.walk() if n.kind == "navigate"] == ["station_4", "station_4"]


def test_a_display_name_passed_to_an_include_becomes_the_marker_name():
    spec = load(f"""
        markers: {MARKERS}
        root: {{include: {{file: {TREES / "station.yaml"}, with: {{where: 3D Printers, title: printers}}}}}}
        """)
    assert spec.find("t/navigate").params == {"marker": "station_2"}


def test_included_marker_file_is_used_when_the_includer_has_none(tmp_path):
    (tmp_path / "sub.yaml").write_text(f"markers: {MARKERS}\nroot: {{navigate: kitchen}}\n")
    (tmp_path / "main.yaml").write_text("root: {include: sub.yaml}\n")
    spec = load_tree(tmp_path / "main.yaml")
    assert spec.markers_file == str(MARKERS)


def test_list_argument_substituted_whole_keeps_its_list_type(tmp_path):
    (tmp_path / "moves.yaml").write_text(
        "params: {moves: {type: gestures}}\nroot: {gesture: {sequence: $moves}}\n")
    (tmp_path / "main.yaml").write_text(
        "root: {include: {file: moves.yaml, with: {moves: [clap, hug]}}}\n")
    assert load_tree(tmp_path / "main.yaml").root.params == {"sequence": ["clap", "hug"]}


def test_blackboard_references_pass_through_includes_as_run_time_references(tmp_path):
    (tmp_path / "say.yaml").write_text(
        "params: {who: {type: string}}\n"
        "root: {sequence: [{speak: \"Hi ${who}, battery ${battery}\"}, {speak: $who}, {wait: $pause}]}\n")
    (tmp_path / "main.yaml").write_text("root: {include: {file: say.yaml, with: {who: $visitor}}}\n")
    spec = load_tree(tmp_path / "main.yaml")
    assert [c.params["text"] if "text" in c.params else c.params["seconds"] for c in spec.root.children] == [
        "Hi ${visitor}, battery ${battery}", "$visitor", "$pause"
    ]


def test_include_as_plain_string_and_explicit_name(tmp_path):
    (tmp_path / "hello.yaml").write_text("root: {speak: hello}\n")
    (tmp_path / "main.yaml").write_text(
        "root:\n  sequence:\n    - include: hello.yaml\n    - include: {file: hello.yaml, name: again}\n"
        "    - sequence: [{include: hello.yaml}]\n")
    spec = load_tree(tmp_path / "main.yaml")
    # the stem is numbered like a kind: the named include still counts as a 'hello' sibling
    assert paths(spec) == ["main", "main/hello_1", "main/again", "main/sequence", "main/sequence/hello"]


def test_path_argument_stays_relative_to_the_file_that_wrote_it():
    spec = load_tree(TREES / "with_subfolder.yaml")
    gesture = spec.find("show_clip/gesture")
    assert gesture.params == {"file": "gestures/bow.json"}
    assert gesture.param_locations["file"].file == str(TREES / "with_subfolder.yaml")
    assert gesture.location.file == str(TREES / "sub" / "clip.yaml")
    assert spec.find("show_clip/speak").params == {"text": "Watch this"}


def test_file_loaded_alone_uses_defaults_and_keeps_required_params_as_references():
    spec = load_tree(TREES / "standalone_params.yaml")
    assert spec.root.params == {"text": "Hi ${who}"}
    assert spec.params["who"] == {"type": "string", "doc": "Required; read from the blackboard when run alone."}
    assert spec.params["greeting"] == {"type": "string", "default": "Hi"}


def test_include_cycle_is_reported_with_the_chain():
    with pytest.raises(TreeLoadError) as caught:
        load_tree(TREES / "bad" / "cycle_a.yaml")
    (error,) = caught.value.errors
    a, b = os.path.normpath(TREES / "bad" / "cycle_a.yaml"), os.path.normpath(TREES / "bad" / "cycle_b.yaml")
    assert error.message == f"include cycle: {a} -> {b} -> {a}"
    assert (error.location.file, error.location.line) == (b, 3)


def test_text_includes_are_relative_to_the_current_directory(monkeypatch):
    monkeypatch.chdir(TREES)
    spec = load_tree_text("root: {include: {file: present.yaml, with: {text: hi}}}\n")
    assert spec.root.include == "present.yaml"
    assert spec.find("root/speak").params == {"text": "hi"}


def test_relative_paths_stay_relative(monkeypatch):
    monkeypatch.chdir(DATA.parent.parent)
    spec = load_tree("tests/data/trees/tour.yaml")
    assert spec.file == "tests/data/trees/tour.yaml"
    assert spec.markers_file == "tests/data/markers.json"
    assert spec.find("tour/home").include == "tests/data/trees/station.yaml"


def test_yaml_anchors_and_merge_keys_work():
    spec = load("""
        root:
          sequence:
            - speak: &polite {text: hello, wait: false}
            - speak: {<<: *polite, text: goodbye}
    """)
    assert [c.params for c in spec.root.children] == [
        {"text": "hello", "wait": False}, {"wait": False, "text": "goodbye"}
    ]


def test_on_key_of_oneshot_is_read_as_a_name_not_a_boolean():
    spec = load("root: {oneshot: {on: completion, child: {stop: {}}}}\n")
    assert spec.root.params == {"on": "completion"}
