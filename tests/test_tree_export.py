"""Writing a tree back as YAML loses nothing and stays readable."""

from __future__ import annotations

import re
import textwrap
from pathlib import Path

import pytest
import yaml

from stuart_bt.tree.export import to_yaml
from stuart_bt.tree.loader import load_tree, load_tree_text
from stuart_bt.tree.spec import TreeSpec

TREES = Path(__file__).parent / "data" / "trees"
GOOD_TREES = sorted(p.name for p in TREES.glob("*.yaml"))


def summary(spec: TreeSpec) -> list[tuple[str, str, dict]]:
    return [(n.path, n.kind, n.params) for n in spec.walk()]


def round_trip(spec: TreeSpec) -> TreeSpec:
    return load_tree_text(to_yaml(spec), file=spec.file)


@pytest.mark.parametrize("name", GOOD_TREES)
def test_every_good_tree_round_trips(name):
    spec = load_tree(TREES / name)
    again = round_trip(spec)
    assert summary(again) == summary(spec)
    assert (again.blackboard, again.description, again.params) == (spec.blackboard, spec.description, spec.params)
    assert again.markers_file == spec.markers_file


def test_text_tree_round_trips_without_a_file():
    spec = load_tree_text(textwrap.dedent("""\
        root:
          selector:
            name: main
            memory: true
            children:
              - guard: {condition: "battery > 20", child: {navigate: {x: 1, y: 2}}}
              - parallel: {policy: selected, selected: [b], children: [{wait: 1}, {stop: {name: b}}]}
              - speak: {text: "${who}", name: hello}
              - speak: Bye
        """))
    assert summary(load_tree_text(to_yaml(spec))) == summary(spec)


def test_includes_are_inlined_with_their_names_written():
    text = to_yaml(load_tree(TREES / "tour.yaml"))
    assert "include:" not in text
    doc = yaml.safe_load(text)
    children = doc["root"]["sequence"]["children"]
    assert [next(iter(c.values()))["name"] for c in children[1:]] == ["station_1", "station_2", "station_3", "home"]


def test_leaves_with_only_their_shorthand_parameter_are_written_short():
    spec = load_tree_text(
        "root: {sequence: [{speak: {text: Hello}}, {wait: {seconds: 2}}, {speak: {text: x, wait: false}}]}\n")
    doc = yaml.safe_load(to_yaml(spec))
    assert doc["root"] == {"sequence": {"name": "root", "children": [
        {"speak": "Hello"}, {"wait": 2}, {"speak": {"text": "x", "wait": False}}]}}


def test_names_are_written_only_where_the_automatic_name_differs():
    spec = load_tree_text("root:\n  sequence:\n    name: t\n    children:\n"
                          "      - speak: {text: a, name: speak_1}\n      - speak: {text: b, name: hi}\n")
    doc = yaml.safe_load(to_yaml(spec))
    assert doc["root"]["sequence"]["children"] == [{"speak": "a"}, {"speak": {"name": "hi", "text": "b"}}]


def test_output_is_block_style_in_written_order():
    text = to_yaml(load_tree(TREES / "all_constructs.yaml"))
    assert list(yaml.safe_load(text)) == ["description", "markers", "blackboard", "root"]
    assert not re.search(r"[:-] [{\[](?![}\]])", text), "no flow-style mappings or lists"
    assert "  stop: {}" in text or "- stop: {}" in text


def test_markers_and_file_parameters_stay_relative_to_the_tree_file():
    doc = yaml.safe_load(to_yaml(load_tree(TREES / "all_constructs.yaml")))
    assert doc["markers"] == "../markers.json"
    subfolder = to_yaml(load_tree(TREES / "with_subfolder.yaml"))
    assert "file: gestures/bow.json" in subfolder


def test_file_paths_written_in_a_subfolder_are_rewritten_to_point_at_the_same_file(tmp_path):
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "bow.json").write_text("{}")
    (tmp_path / "parts" / "bow.yaml").write_text("root: {gesture: {file: bow.json}}\n")
    (tmp_path / "main.yaml").write_text("root: {include: parts/bow.yaml}\n")
    spec = load_tree(tmp_path / "main.yaml")
    again = round_trip(spec)
    assert again.root.params == {"file": "parts/bow.json"}
