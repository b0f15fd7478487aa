"""The bottom of the domain file reader: YAML nodes read with their file:line:column, their
shapes checked, and every problem logged rather than raised.

A domain file is checked whole, so one load reports every problem at once (docs/htn.md): the
readers above this one never raise on bad input, they log it here and return None or an empty
value, and :mod:`.load` raises once at the end with the whole log.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import Any

from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from ..tree import yaml_source as ys
from ..tree.errors import ErrorLog
from ..tree.spec import Location
from .domain import MISSING
from .misnamed import misnamed
from .values import RESERVED

IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")

Items = dict[str, tuple[ScalarNode, Node]]  # a mapping's entries by key: (key node, value node)


class YamlReader:
    """Positions, shapes and plain values of one file's YAML nodes; problems go to ``log``."""

    def __init__(self, file: str) -> None:
        self.file = file
        self.log = ErrorLog()

    def loc(self, node: Node, column: int = 1) -> Location:
        """Where ``node`` starts; for a one-line scalar, ``column`` within its text."""
        base = ys.location(self.file, node)
        if column > 1 and isinstance(node, ScalarNode) and node.start_mark.line == node.end_mark.line \
                and node.style in (None, "'", '"'):
            return Location(self.file, base.line, base.column + (0 if node.style is None else 1) + column - 1)
        return base

    def err(self, node: Node, message: str, path: str | None, column: int = 1) -> None:
        self.log.add(self.loc(node, column), message, path)

    def items(self, node: Node, path: str, allowed: Sequence[str] | None = None) -> Items:
        """A mapping's entries; unknown keys (when ``allowed`` is given) are reported and left out."""
        if not isinstance(node, MappingNode):
            self.err(node, f"expected a mapping, got {shape(node)}", path)
            return {}
        out: Items = {}
        for key, value in ys.named_items(node, self.file, self.log, path):
            name = str(key.value)
            if allowed is not None and name not in allowed:
                self.err(key, misnamed("unknown key", name, allowed, "expected"), path)
                continue
            out[name] = (key, value)
        return out

    def text(self, node: Node, path: str, what: str = "text") -> str | None:
        if isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:str":
            return str(node.value)
        self.err(node, f"expected {what}, got {shape(node)}", path)
        return None

    def doc(self, spec: Items, path: str) -> str:
        """The optional ``doc:`` text of a definition, '' when absent or not text."""
        return (self.text(spec["doc"][1], path) or "") if "doc" in spec else ""

    def python(self, node: Node, path: str) -> Any:
        """The node as a plain Python value; MISSING (after logging why) when it is not one."""
        try:
            return ys.to_python(node, self.file)
        except ys.BadValue as e:
            self.log.add(e.error.location, e.error.message, path)
            return MISSING

    def read_flag(self, node: Node, name: str, path: str) -> bool:
        value = self.python(node, path)
        if not isinstance(value, bool):
            self.err(node, f"'{name}' must be true or false", path)
            return False
        return value

    def name_ok(self, key: ScalarNode, what: str, path: str) -> bool:
        """Whether a defined name can be used in expressions: a plain identifier, not a reserved word."""
        name = str(key.value)
        if not IDENT.match(name) or name in RESERVED:
            self.err(key, f"{what} {name!r} must be a plain name (letters, digits, '_', not starting with '_' "
                          f"or a digit, not one of {', '.join(sorted(RESERVED))})", path)
            return False
        return True


def shape(node: Node) -> str:
    """A node's shape as an error message names it: 'a mapping', "str 'x'", 'nothing (null)'."""
    if isinstance(node, MappingNode):
        return "a mapping"
    if isinstance(node, SequenceNode):
        return "a list"
    if isinstance(node, ScalarNode):
        tag = node.tag.rsplit(":", 1)[-1]
        return f"{tag} {node.value!r}" if tag != "null" else "nothing (null)"
    return "something else"
