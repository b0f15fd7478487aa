"""The top level of one tree file: ``root`` and the keys around it.

Reading it is separate from reading nodes because an included file is opened once however
often it is included: its top-level problems are reported once, and its declared parameters
are reused for every ``include`` of it.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

from yaml.nodes import MappingNode, Node, ScalarNode

from ..core.suggest import did_you_mean
from .errors import ErrorLog
from .include_params import Declared, Scope, base_dir_of, read_declarations
from .spec import Location
from .values import describe
from .yaml_source import BadValue, Source, location, named_items, to_python

TOP_KEYS = ("version", "description", "markers", "blackboard", "params", "root")
VERSION = 1


@dataclass
class TreeFile:
    """What a tree file says besides its nodes; ``markers`` is already relative to the cwd."""

    file: str
    root: Node | None = None
    description: str | None = None
    markers: str | None = None
    markers_location: Location | None = None
    blackboard: dict[str, Any] = field(default_factory=dict)
    declared: dict[str, Declared] = field(default_factory=dict)


def read_tree_file(source: Source, log: ErrorLog) -> TreeFile | None:
    """Check the top-level mapping of ``source``; ``None`` when the file has no usable content."""
    log.extend(source.errors)
    file = source.file
    if source.root is None:
        if not source.errors:
            log.add(Location(file, 1, 1), "file is empty: expected a mapping with a 'root' node")
        return None
    if not isinstance(source.root, MappingNode):
        got = "a list" if not isinstance(source.root, ScalarNode) else f"the text {source.root.value!r}"
        log.add(location(file, source.root), f"expected a mapping with a 'root' node at the top of the file, got {got}")
        return None
    tree = TreeFile(file)
    for key, value in named_items(source.root, file, log):
        name = key.value
        if name not in TOP_KEYS:
            log.add(location(file, key), f"unknown top-level key {name!r}"
                    f"{did_you_mean(name, TOP_KEYS) or '; expected one of ' + ', '.join(TOP_KEYS)}")
        elif name == "root":
            tree.root = value
        elif name == "params":
            tree.declared = read_declarations(value, Scope(file, base_dir_of(file), {}), log)
        else:
            try:
                _set_plain(tree, name, value, to_python(value, file), log)
            except BadValue as e:
                log.extend([e.error])
    if tree.root is None:
        log.add(location(file, source.root), "missing 'root': a tree file needs one root node")
    return tree


def _set_plain(tree: TreeFile, name: str, node: Node, value: Any, log: ErrorLog) -> None:
    here = location(tree.file, node)
    if name == "version":
        if value != VERSION or isinstance(value, bool) or not isinstance(value, int):
            log.add(here, f"unsupported version {describe(value)}; this loader reads version {VERSION}")
    elif name == "description":
        if not isinstance(value, str):
            log.add(here, f"'description' must be text, got {describe(value)}")
        else:
            tree.description = value
    elif name == "markers":
        if not isinstance(value, str) or not value.strip():
            log.add(here, f"'markers' must be the path of a marker file, got {describe(value)}")
        else:
            tree.markers = os.path.normpath(os.path.join(base_dir_of(tree.file), value))
            tree.markers_location = here
    elif not isinstance(value, dict):
        log.add(here, f"'blackboard' must be a mapping of key: initial value, got {describe(value)}")
    else:
        tree.blackboard = {str(k): v for k, v in value.items()}
