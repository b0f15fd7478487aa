"""A JSON Schema (draft 2020-12) for tree files, generated from the catalogue.

Editors with a YAML language server use it for completion, hover docs and red squiggles
while typing; ``stuart-bt validate`` remains the full check (markers, files, expressions,
include parameters). Every parameter also accepts a ``$key`` blackboard reference, as the
loader does. The committed copy lives at docs/tree.schema.json::

    python -m stuart_bt.tree.schema -o docs/tree.schema.json
"""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path
from typing import Any

from ..core import gestures
from ..core.catalogue import COMPOSITES, DECORATORS, LEAVES, PARAM_TYPES, LeafSpec, NodeKind, Param
from .include_params import DECLARATION_KEYS
from .treefile import VERSION

_NODE = {"$ref": "#/$defs/node"}
_NAME = {"type": "string", "pattern": "^[^/]+$", "description": "Path segment of this node (no '/')."}


def tree_schema() -> dict[str, Any]:
    """The schema as a dict, ready for ``json.dumps``."""
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "stuart_bt behaviour tree",
        "description": "A behaviour tree for the Unitree G1 (see docs/trees.md).",
        "type": "object",
        "properties": {
            "version": {"const": VERSION, "description": "Language version; only 1 exists."},
            "description": {"type": "string", "description": "What the tree does, for people."},
            "markers": {"type": "string", "description": "Marker file (JSON), relative to this tree file."},
            "blackboard": {"type": "object", "description": "Initial blackboard values."},
            "params": {
                "type": "object",
                "description": "Parameters this file takes when included (include ... with:).",
                "additionalProperties": {"$ref": "#/$defs/param_declaration"},
            },
            "root": {**_NODE, "description": "The root node."},
        },
        "required": ["root"],
        "additionalProperties": False,
        "$defs": {
            "node": _node_schema(),
            "reference": {
                "type": "string",
                "pattern": r"^\$[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z0-9_]+)*$",
                "description": "A blackboard reference ($key), resolved when the node starts.",
            },
            "template": {
                "type": "string",
                "pattern": r"\$\{[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z0-9_]+)*\}",
                "description": "Text with ${key} templates, filled in when the node starts.",
            },
            "param_declaration": {
                "type": ["object", "null"],
                "properties": {
                    "type": {"enum": list(PARAM_TYPES)},
                    "default": {},
                    "doc": {"type": "string"},
                    "choices": {"type": "array", "items": {"type": "string"}, "minItems": 1},
                },
                "propertyNames": {"enum": list(DECLARATION_KEYS)},
            },
            **{f"kind_{name}": schema for name, schema in _kind_schemas().items()},
        },
    }


def _node_schema() -> dict[str, Any]:
    kinds = [*COMPOSITES, *DECORATORS, *LEAVES, "include"]
    return {
        "type": "object",
        "description": "One node: a mapping with exactly one key, its kind.",
        "properties": {k: {"$ref": f"#/$defs/kind_{k}"} for k in kinds},
        "additionalProperties": False,
        "minProperties": 1,
        "maxProperties": 1,
    }


def _kind_schemas() -> dict[str, dict[str, Any]]:
    schemas = {name: _composite(kind) for name, kind in COMPOSITES.items()}
    schemas.update({name: _decorator(kind) for name, kind in DECORATORS.items()})
    schemas.update({name: _leaf(leaf) for name, leaf in LEAVES.items()})
    schemas["include"] = {
        "description": "Insert another tree file's root here; 'with' passes its declared params.",
        "anyOf": [
            {"type": "string", "description": "File path, relative to this file."},
            {
                "type": "object",
                "properties": {"file": {"type": "string"}, "name": _NAME, "with": {"type": "object"}},
                "required": ["file"],
                "additionalProperties": False,
            },
        ],
    }
    return schemas


def _composite(kind: NodeKind) -> dict[str, Any]:
    children = {"type": "array", "items": _NODE, "minItems": 1, "description": "Child nodes, in order."}
    return {
        "description": kind.doc,
        "anyOf": [
            children,
            {
                "type": "object",
                "properties": {"name": _NAME, "children": children, **_params(kind.params)},
                "required": ["children"],
                "additionalProperties": False,
            },
        ],
    }


def _decorator(kind: NodeKind) -> dict[str, Any]:
    return {
        "description": kind.doc,
        "type": "object",
        "properties": {"name": _NAME, "child": {**_NODE, "description": "The decorated node."},
                       **_params(kind.params)},
        "required": ["child", *(p.name for p in kind.params if p.required)],
        "additionalProperties": False,
    }


def _leaf(leaf: LeafSpec) -> dict[str, Any]:
    timeout = Param("timeout", "seconds", f"Fail if running longer than this (default {leaf.default_timeout:g} s).")
    mapping: dict[str, Any] = {
        "type": "object",
        "properties": {"name": _NAME, **_params((*leaf.params, timeout))},
        "additionalProperties": False,
    }
    grouped = {p for group in leaf.one_of for p in group}
    required = [p.name for p in leaf.params if p.required and p.name not in grouped]
    if required:
        mapping["required"] = required
    if leaf.one_of:
        mapping["oneOf"] = [_group(leaf, group, grouped) for group in leaf.one_of]
    forms: list[dict[str, Any]] = [mapping]
    if leaf.shorthand:
        shorthand = leaf.param(leaf.shorthand)
        assert shorthand is not None
        forms.insert(0, _value(shorthand))
    if not required and not leaf.one_of:
        forms.append({"type": "null"})
    return {"description": leaf.doc, "anyOf": forms}


def _group(leaf: LeafSpec, group: tuple[str, ...], grouped: set[str]) -> dict[str, Any]:
    """Parameters of one alternative present, and none of the other alternatives'."""
    needed = [p for p in group if (param := leaf.param(p)) is not None and param.required]
    present = {"required": needed} if needed else {"anyOf": [{"required": [p]} for p in group]}
    others = sorted(grouped - set(group))
    return {"allOf": [present, {"not": {"anyOf": [{"required": [p]} for p in others]}}]}


def _params(params: tuple[Param, ...] | list[Param]) -> dict[str, Any]:
    return {p.name: _value(p) for p in params}


def _value(param: Param) -> dict[str, Any]:
    """Schema for one parameter value: its type, or a blackboard reference."""
    doc = param.doc if param.default is None else f"{param.doc} Default: {json.dumps(param.default)}."
    forms = [_typed(param), {"$ref": "#/$defs/reference"}]
    if param.type in ("choice", "gesture"):
        forms.append({"$ref": "#/$defs/template"})
    return {"description": doc, "anyOf": forms}


def _typed(param: Param) -> dict[str, Any]:
    simple: dict[str, dict[str, Any]] = {
        "string": {"type": "string"},
        "number": {"type": "number"},
        "angle": {"type": "number"},
        "integer": {"type": "integer"},
        "boolean": {"type": "boolean"},
        "seconds": {"type": "number", "minimum": 0},
        "marker": {"type": "string", "minLength": 1},
        "path": {"type": "string", "minLength": 1},
        "expression": {"type": "string", "minLength": 1},
        "any": {},
    }
    if param.type in simple:
        return simple[param.type]
    if param.type == "choice":
        return {"enum": list(param.choices)}
    if param.type == "gesture":
        return _gesture()
    return {"type": "array", "items": _gesture(), "minItems": 1}


def _gesture() -> dict[str, Any]:
    """Known names for completion, plus the spellings the loader also accepts (any case, '_' or '-')."""
    return {"anyOf": [{"enum": gestures.names()}, {"type": "string", "pattern": _spellings(gestures.names())}]}


def _spellings(names: list[str]) -> str:
    def one(name: str) -> str:
        parts = []
        for ch in name:
            if ch.isalpha():
                parts.append(f"[{ch.lower()}{ch.upper()}]")
            elif ch in " -":
                parts.append("[ _-]+")
            else:
                parts.append(re.escape(ch))
        return "".join(parts)

    return r"^\s*(" + "|".join(one(n) for n in names) + r")\s*$"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m stuart_bt.tree.schema", description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", type=Path, help="write here instead of standard output")
    args = parser.parse_args(argv)
    text = json.dumps(tree_schema(), indent=2, ensure_ascii=False) + "\n"
    if args.output:
        args.output.write_text(text, encoding="utf-8")
    else:
        print(text, end="")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
