"""The loaded form of a tree: plain data between the YAML loader and the py_trees builder.

A :class:`TreeSpec` is what ``validate`` checks, ``show`` draws, ``show --format yaml`` writes
back, and :mod:`stuart_bt.tree.builder` turns into py_trees behaviours. Every node keeps where
it came from (file, line, column) and its stable path (``tour/station_3/speak``) so that errors,
logs, reports and tests can all name it the same way.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class Location:
    """A place in a source file; line and column are 1-based, as editors show them."""

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


@dataclass
class NodeSpec:
    """One node: a composite, a decorator or a leaf.

    ``params`` holds the options exactly as given after include parameters were substituted
    (defaults are not filled in, so the tree exports back as written). Values may still be
    blackboard references (``"$key"``) or templates (``"... ${key} ..."``), resolved at run time.
    """

    kind: str
    name: str
    path: str
    location: Location
    params: dict[str, Any] = field(default_factory=dict)
    children: list[NodeSpec] = field(default_factory=list)
    param_locations: dict[str, Location] = field(default_factory=dict)
    include: str | None = None  # for the root of an included subtree: the file it came from

    def walk(self) -> Iterator[NodeSpec]:
        """This node and every descendant, depth first, parents before children."""
        yield self
        for child in self.children:
            yield from child.walk()

    def find(self, path: str) -> NodeSpec | None:
        return next((n for n in self.walk() if n.path == path), None)


@dataclass
class TreeSpec:
    """A whole tree file after loading, includes expanded."""

    root: NodeSpec
    file: str
    markers_file: str | None = None
    blackboard: dict[str, Any] = field(default_factory=dict)  # initial blackboard values
    params: dict[str, dict[str, Any]] = field(default_factory=dict)  # declared include parameters
    description: str | None = None

    def walk(self) -> Iterator[NodeSpec]:
        return self.root.walk()

    def find(self, path: str) -> NodeSpec | None:
        return self.root.find(path)
