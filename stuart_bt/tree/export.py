"""Writing a loaded tree back as YAML: includes inlined, every node path reproducible.

Used by ``show --format yaml`` to see what a tree with includes really runs, and by tests to
check that the loader loses nothing: loading the output (with the same ``file`` as the
original, so relative paths start in the same folder) gives an equal tree. A node's ``name``
is written only where the automatic name would differ, and a leaf holding just its shorthand
parameter is written in the short form (``speak: Hello``), so the output stays readable.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import yaml

from ..core.catalogue import COMPOSITES, DECORATORS, LEAVES
from .include_params import base_dir_of
from .naming import child_segments
from .spec import NodeSpec, TreeSpec


class _Dumper(yaml.SafeDumper):
    """Indents list items under their key, which reads better for nested children."""

    def increase_indent(self, flow: bool = False, indentless: bool = False) -> None:
        super().increase_indent(flow, False)


def to_yaml(spec: TreeSpec, relative_to: str | os.PathLike[str] | None = None) -> str:
    """The expanded tree as YAML text. Relative paths (markers, gesture files) are written
    relative to ``relative_to`` (the folder the text will be saved in), else ``spec.file``'s folder."""
    doc: dict[str, Any] = {}
    base = Path(relative_to) if relative_to is not None else base_dir_of(spec.file)
    if spec.description is not None:
        doc["description"] = spec.description
    if spec.markers_file is not None:
        doc["markers"] = _relative(spec.markers_file, str(base))
    if spec.blackboard:
        doc["blackboard"] = spec.blackboard
    if spec.params:
        doc["params"] = spec.params
    doc["root"] = _Exporter(str(base)).node(spec.root, auto_name=None)
    return yaml.dump(doc, Dumper=_Dumper, sort_keys=False, default_flow_style=False, allow_unicode=True, width=100)


def _relative(path: str, base: str) -> str:
    return os.path.relpath(os.path.abspath(path), os.path.abspath(base)).replace(os.sep, "/")


class _Exporter:
    def __init__(self, base: str) -> None:
        self.base = base

    def node(self, spec: NodeSpec, auto_name: str | None) -> dict[str, Any]:
        named = spec.name != auto_name
        params = self.params(spec)
        if spec.kind in COMPOSITES:
            children = self.children(spec.children)
            if not named and not params:
                return {spec.kind: children}
            return {spec.kind: {**_name(spec, named), **params, "children": children}}
        if spec.kind in DECORATORS:
            child = self.node(spec.children[0], spec.children[0].kind) if spec.children else {}
            return {spec.kind: {**_name(spec, named), **params, "child": child}}
        shorthand = LEAVES[spec.kind].shorthand
        if not named and shorthand and list(params) == [shorthand] and _is_scalar(params[shorthand]):
            return {spec.kind: params[shorthand]}
        return {spec.kind: {**_name(spec, named), **params}}

    def children(self, children: list[NodeSpec]) -> list[dict[str, Any]]:
        autos = child_segments([None] * len(children), [c.kind for c in children])
        return [self.node(c, auto) for c, auto in zip(children, autos, strict=True)]

    def params(self, spec: NodeSpec) -> dict[str, Any]:
        """Parameters as loaded; file paths (relative to the file each was written in) are made
        relative to the exported file's folder."""
        leaf = LEAVES.get(spec.kind)
        if leaf is None:
            return dict(spec.params)
        out = {}
        for name, value in spec.params.items():
            param = leaf.param(name)
            if param is not None and param.type == "path" and isinstance(value, str) and "$" not in value:
                written_in = spec.param_locations.get(name, spec.location).file
                value = _relative(os.path.join(base_dir_of(written_in), value), self.base)
            out[name] = value
        return out


def _name(spec: NodeSpec, named: bool) -> dict[str, str]:
    return {"name": spec.name} if named else {}


def _is_scalar(value: Any) -> bool:
    return isinstance(value, (str, int, float, bool))
