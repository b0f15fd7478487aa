"""The generated JSON Schema is committed, valid, accepts every good tree and rejects bad ones."""

from __future__ import annotations

import json
import re
from pathlib import Path

import jsonschema
import pytest
import yaml

from stuart_bt.tree.errors import TreeLoadError
from stuart_bt.tree.loader import load_tree
from stuart_bt.tree.schema import main, tree_schema

ROOT = Path(__file__).parent.parent
TREES = Path(__file__).parent / "data" / "trees"
GOOD = sorted(p for p in TREES.rglob("*.yaml") if "bad" not in p.parts)
SCHEMA_REJECTS = [
    "unknown_kind.yaml", "unknown_param.yaml", "decorator_without_child.yaml", "empty_sequence.yaml",
    "wrong_type.yaml", "two_alternatives.yaml", "unknown_top_key.yaml", "bad_choice.yaml",
]


class EditorLoader(yaml.SafeLoader):
    """Reads YAML as editors' language servers do (YAML 1.2 booleans), so ``on:`` stays a key."""


EditorLoader.yaml_implicit_resolvers = {
    first: [(tag, rx) for tag, rx in resolvers if tag != "tag:yaml.org,2002:bool"]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()
}
EditorLoader.add_implicit_resolver("tag:yaml.org,2002:bool", re.compile(r"^(?:true|True|TRUE|false|False|FALSE)$"),
                                   list("tTfF"))


def read(path: Path) -> object:
    return yaml.load(path.read_text(encoding="utf-8"), Loader=EditorLoader)


@pytest.fixture(scope="module")
def validator() -> jsonschema.Draft202012Validator:
    return jsonschema.Draft202012Validator(tree_schema())


def test_committed_schema_is_current():
    committed = json.loads((ROOT / "docs" / "tree.schema.json").read_text(encoding="utf-8"))
    assert committed == tree_schema(), "run: python -m stuart_bt.tree.schema -o docs/tree.schema.json"


def test_schema_is_valid_draft_2020_12():
    jsonschema.Draft202012Validator.check_schema(tree_schema())


def test_command_writes_the_schema(tmp_path):
    out = tmp_path / "schema.json"
    assert main(["-o", str(out)]) == 0
    assert json.loads(out.read_text(encoding="utf-8")) == tree_schema()


@pytest.mark.parametrize("path", GOOD, ids=lambda p: str(p.relative_to(TREES)))
def test_good_trees_validate(validator, path):
    load_tree(path)  # the loader accepts it too
    errors = [e.message for e in validator.iter_errors(read(path))]
    assert errors == []


@pytest.mark.parametrize("name", SCHEMA_REJECTS)
def test_bad_trees_do_not_validate(validator, name):
    path = TREES / "bad" / name
    with pytest.raises(TreeLoadError):
        load_tree(path)
    assert not validator.is_valid(read(path))


def test_references_are_accepted_for_typed_parameters(validator):
    tree = {"root": {"sequence": [{"wait": "$pause"}, {"retry": {"times": "$n", "child": {"pick": {
        "object": "cup", "arm": "$arm"}}}}, {"gesture": "${mood} wave"}]}}
    assert validator.is_valid(tree)
    assert not validator.is_valid({"root": {"wait": "pause"}})


def test_gesture_spellings_the_loader_accepts_validate(validator):
    assert validator.is_valid({"root": {"gesture": "High_Wave"}})
    assert validator.is_valid({"root": {"gesture": {"sequence": ["x-ray", "xray", "shake hands"]}}})
    assert not validator.is_valid({"root": {"gesture": "high wav"}})


def test_leaf_kinds_carry_their_docs_for_editors():
    defs = tree_schema()["$defs"]
    assert defs["kind_navigate"]["description"].startswith("Walk to a named marker")
    mapping = defs["kind_navigate"]["anyOf"][1]
    assert mapping["properties"]["marker"]["description"] == "Marker name or display name from the marker file."
    assert defs["kind_pick"]["anyOf"][1]["properties"]["arm"]["anyOf"][0] == {"enum": ["auto", "left", "right"]}
