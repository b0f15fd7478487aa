"""Turning composed YAML nodes into :class:`NodeSpec`: kinds, options, leaf parameters, names
and includes, reporting every problem with its place and node path.

Siblings are read in two steps: first each child's kind and name (its "head"), so that every
child knows its path segment; then each child's body. That way errors inside a child already
carry the same path the running tree will use.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from ..core.blackboard import is_reference, template_names
from ..core.catalogue import COMPOSITES, DECORATORS, LEAVES, NodeKind, Param
from ..core.suggest import did_you_mean
from .errors import ErrorLog
from .include_params import Scope, Val, base_dir_of, bind
from .leafcheck import missing_or_conflicting
from .naming import child_segments
from .spec import Location, NodeSpec
from .treefile import TreeFile
from .values import check_value, describe, is_file, names_in
from .yaml_source import MAX_DEPTH, MAX_NODES, BadValue, location, named_items

ALL_KINDS = (*COMPOSITES, *DECORATORS, *LEAVES, "include")
TIMEOUT = Param("timeout", "seconds", "Fail the leaf if it runs longer than this (clock time).")
INCLUDE_KEYS = ("file", "name", "with")
_RANGES: dict[tuple[str, str], tuple[Callable[[int], bool], str]] = {
    ("retry", "times"): (lambda v: v >= 1, "at least 1"),
    ("repeat", "times"): (lambda v: v >= 1 or v == -1, "at least 1, or -1 to repeat forever"),
}


@dataclass
class Head:
    """A node's kind and name, read before its body."""

    kind: str
    key: Node  # the kind key, where the node is said to be
    body: Node
    name: str | None = None
    name_node: Node | None = None
    base: str = ""  # for automatic naming: the kind, or an included file's stem
    include_file: Val | None = None
    include_with: Node | None = None


@dataclass(frozen=True)
class MarkerUse:
    """A marker name to check once the marker file is known (and to replace by the marker's
    name when it was written as a display name)."""

    name: str
    location: Location
    spec: NodeSpec
    param: str

    @property
    def what(self) -> str:
        return f"parameter {self.param!r} for {self.spec.kind}"


OpenFile = Callable[[Path, str], TreeFile | None]


class NodeReader:
    """Reads the nodes of a tree and its includes; problems go to ``log``."""

    def __init__(self, log: ErrorLog, open_file: OpenFile) -> None:
        self.log = log
        self.open_file = open_file
        self.markers: list[MarkerUse] = []
        self.count = 0

    def root(self, node: Node, scope: Scope, default_name: str) -> NodeSpec | None:
        head = self.head(node, scope, None)
        if head is None:
            return None
        segment = head.name or default_name
        return self.build(head, scope, segment, segment, 1)

    # --- heads -------------------------------------------------------------------------------

    def head(self, node: Node, scope: Scope, parent: str | None) -> Head | None:
        """Kind and name of a node mapping, or ``None`` (reported) when it has no single kind."""
        here = location(scope.file, node)
        if not isinstance(node, MappingNode):
            text = node.value if isinstance(node, ScalarNode) else None
            if text in ALL_KINDS:
                self.log.add(here, f"expected a node mapping, got {text!r}; write '{text}: {{}}' for a node "
                                   "without parameters", parent)
            else:
                got = "a list" if isinstance(node, SequenceNode) else "nothing" if _is_null(node) else repr(text)
                self.log.add(here, f"expected a node: a mapping with one kind key such as 'speak: Hello', got {got}",
                             parent)
            return None
        items = self.items(node, scope, parent)
        kinds = [(k, v) for k, v in items if k.value in ALL_KINDS]
        others = [k for k, _ in items if k.value not in ALL_KINDS]
        if not kinds:
            if not others:
                self.log.add(here, f"empty node: expected one kind key ({', '.join(ALL_KINDS)})", parent)
            for key in others:
                self.log.add(location(scope.file, key), _unknown_kind(key.value), parent)
            return None
        if len(kinds) > 1:
            first, second = kinds[0][0].value, kinds[1][0].value
            self.log.add(location(scope.file, kinds[1][0]), f"a node has exactly one kind key, found {first!r} and "
                         f"{second!r}; put several nodes in a sequence", parent)
            return None
        key, body = kinds[0]
        for other in others:
            self._stray_key(key.value, other, scope, parent)
        head = Head(key.value, key, body, base=key.value)
        if head.kind == "include":
            self._include_head(head, scope, parent)
        elif isinstance(body, MappingNode):
            self._name(head, body, scope, parent)
        return head

    def _stray_key(self, kind: str, key: ScalarNode, scope: Scope, parent: str | None) -> None:
        here = location(scope.file, key)
        if key.value in (*_option_names(kind), "name", "timeout", "child", "children"):
            self.log.add(here, f"unexpected key {key.value!r} beside {kind!r}: options go inside it "
                               f"({kind}: {{{key.value}: ...}})", parent)
        else:
            self.log.add(here, f"unknown node kind {key.value!r}{did_you_mean(key.value, ALL_KINDS)}; "
                               f"a node mapping has exactly one key, its kind ({kind!r} here)", parent)

    def _name(self, head: Head, body: MappingNode, scope: Scope, parent: str | None) -> None:
        for key, value in self.items(body, scope, parent):
            if key.value == "name":
                val = self.val(value, scope, parent)
                if val is None:
                    return
                if not isinstance(val.value, str) or not val.value.strip() or "/" in val.value:
                    self.log.add(location(val.file, val.node), f"a name must be non-empty text without '/', "
                                 f"got {describe(val.value)}", parent)
                    return
                head.name, head.name_node = val.value, value

    def _include_head(self, head: Head, scope: Scope, parent: str | None) -> None:
        body = head.body
        file_node: Node | None = None
        if isinstance(body, ScalarNode) and not body.tag.endswith(":null"):
            file_node = body
        elif isinstance(body, MappingNode):
            for key, value in self.items(body, scope, parent):
                if key.value == "file":
                    file_node = value
                elif key.value == "with":
                    head.include_with = value
                elif key.value != "name":
                    self.log.add(location(scope.file, key), f"unknown key {key.value!r} in include"
                                 f"{_suggest_or_list(key.value, INCLUDE_KEYS)}", parent)
            self._name(head, body, scope, parent)
        if file_node is None:
            self.log.add(location(scope.file, head.key), "include needs a file: 'include: station.yaml' or "
                         "'include: {file: station.yaml, with: {...}}'", parent)
            return
        val = self.val(file_node, scope, parent)
        if val is None:
            return
        if not isinstance(val.value, str) or not val.value.strip():
            self.log.add(location(val.file, val.node), f"include needs a file path, got {describe(val.value)}", parent)
            return
        head.include_file = val
        head.base = Path(val.value).stem or "include"

    # --- bodies ------------------------------------------------------------------------------

    def build(self, head: Head, scope: Scope, path: str, segment: str, depth: int) -> NodeSpec | None:
        self.count += 1
        here = location(scope.file, head.key)
        if self.count > MAX_NODES:
            if self.count == MAX_NODES + 1:
                self.log.add(here, f"the tree has more than {MAX_NODES} nodes after includes")
            return None
        if depth > MAX_DEPTH:
            self.log.add(here, f"nesting deeper than {MAX_DEPTH} levels (through includes)", path)
            return None
        if head.kind == "include":
            return self.include(head, scope, path, segment, depth)
        spec = NodeSpec(head.kind, segment, path, here)
        if head.kind in COMPOSITES:
            self.composite(spec, head, scope, depth)
        elif head.kind in DECORATORS:
            self.decorator(spec, head, scope, depth)
        else:
            self.leaf(spec, head, scope)
        return spec

    def composite(self, spec: NodeSpec, head: Head, scope: Scope, depth: int) -> None:
        kind = COMPOSITES[head.kind]
        children_node: Node | None = None
        if isinstance(head.body, SequenceNode):
            children_node = head.body
        elif isinstance(head.body, MappingNode):
            for key, value in self.items(head.body, scope, spec.path):
                if key.value == "children":
                    children_node = value
                elif key.value != "name":
                    self.option(spec, kind, key, value, scope, ("children", "name"))
        elif not _is_null(head.body):
            self.log.add(location(scope.file, head.body), f"{kind.name} expects a list of children or a mapping "
                         "with 'children:'", spec.path)
            return
        if isinstance(children_node, SequenceNode) and children_node.value:
            spec.children = self.children(children_node.value, scope, spec.path, depth)
        elif children_node is None or _is_null(children_node) or isinstance(children_node, SequenceNode):
            self.log.add(spec.location, f"{kind.name} needs at least one child", spec.path)
        else:
            self.log.add(location(scope.file, children_node), "'children' must be a list of nodes", spec.path)
        if kind.name == "parallel":
            self._check_selected(spec)

    def _check_selected(self, spec: NodeSpec) -> None:
        policy, selected = spec.params.get("policy", "all"), spec.params.get("selected")
        if is_reference(policy) or is_reference(selected):
            return
        where = spec.param_locations.get("selected", spec.location)
        if selected is None:
            if policy == "selected":
                self.log.add(spec.location, "parallel with policy 'selected' needs 'selected': the names of the "
                             "children that must succeed", spec.path)
            return
        if policy != "selected":
            self.log.add(where, "'selected' only applies with policy: selected", spec.path)
            return
        names = [selected] if isinstance(selected, str) else selected
        if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
            self.log.add(where, f"'selected' must be a list of child names, got {describe(selected)}", spec.path)
            return
        segments = [c.name for c in spec.children]
        for name in names:
            if name not in segments:
                self.log.add(where, f"'selected' names unknown child {name!r}{did_you_mean(name, segments)}; "
                             f"children are {', '.join(segments)}", spec.path)

    def decorator(self, spec: NodeSpec, head: Head, scope: Scope, depth: int) -> None:
        kind = DECORATORS[head.kind]
        if not isinstance(head.body, MappingNode):
            self.log.add(location(scope.file, head.body), f"{kind.name} expects a mapping with 'child: <node>'"
                         f"{_option_hint(kind)}", spec.path)
            return
        child_node: Node | None = None
        several = False
        for key, value in self.items(head.body, scope, spec.path):
            if key.value == "child":
                child_node = value
            elif key.value == "children":
                self.log.add(location(scope.file, key), f"{kind.name} takes exactly one child: write "
                             "'child: <node>' (put several nodes in a sequence)", spec.path)
                several = True
            elif key.value != "name":
                self.option(spec, kind, key, value, scope, ("child", "name"))
        for p in kind.params:
            if p.required and p.name not in spec.params:
                self.log.add(spec.location, f"missing parameter {p.name!r} for {kind.name}", spec.path)
        if child_node is None:
            if not several:
                self.log.add(spec.location, f"{kind.name} needs exactly one child under 'child:'", spec.path)
        elif isinstance(child_node, SequenceNode):
            self.log.add(location(scope.file, child_node), "'child' takes one node, not a list (put several "
                         "nodes in a sequence)", spec.path)
        else:
            child = self.head(child_node, scope, spec.path)
            if child is not None:
                segment = child.name or child.base
                built = self.build(child, scope, f"{spec.path}/{segment}", segment, depth + 1)
                spec.children = [built] if built else []

    def option(self, spec: NodeSpec, kind: NodeKind, key: ScalarNode, value: Node, scope: Scope,
               structural: tuple[str, ...]) -> None:
        param = next((p for p in kind.params if p.name == key.value), None)
        if param is None:
            names = [*structural, *_option_names(kind.name)]
            self.log.add(location(scope.file, key), f"unknown parameter {key.value!r} for {kind.name}"
                         f"{_suggest_or_list(key.value, names)}", spec.path)
            return
        val = self.param(spec, param, value, scope)
        limit = _RANGES.get((kind.name, param.name))
        if val is not None and limit and isinstance(val.value, int) and not limit[0](val.value):
            self.log.add(location(val.file, val.node), f"parameter {param.name!r} for {kind.name}: expected "
                         f"{limit[1]}, got {val.value}", spec.path)

    def leaf(self, spec: NodeSpec, head: Head, scope: Scope) -> None:
        leaf = LEAVES[head.kind]
        body = head.body
        if isinstance(body, MappingNode):
            accepted = [*leaf.param_names, "name", "timeout"]
            for key, value in self.items(body, scope, spec.path):
                if key.value == "name":
                    continue
                param = TIMEOUT if key.value == "timeout" else leaf.param(key.value)
                if param is None:
                    self.log.add(location(scope.file, key), f"unknown parameter {key.value!r} for {leaf.name}"
                                 f"{_suggest_or_list(key.value, accepted)}", spec.path)
                else:
                    self.param(spec, param, value, scope)
        elif isinstance(body, SequenceNode):
            self.log.add(location(scope.file, body), f"{leaf.name} expects a mapping of parameters"
                         f"{_shorthand_hint(leaf.shorthand)}, got a list", spec.path)
            return
        elif not _is_null(body):
            if leaf.shorthand is None:
                hint = f"write '{leaf.name}: {{}}'" if not leaf.params else \
                    f"give a mapping of parameters ({', '.join(leaf.param_names)})"
                self.log.add(location(scope.file, body), f"{leaf.name} takes no single value; {hint}", spec.path)
                return
            param = leaf.param(leaf.shorthand)
            assert param is not None
            self.param(spec, param, body, scope)
        for message in missing_or_conflicting(leaf, spec.params):
            self.log.add(spec.location, message, spec.path)

    def param(self, spec: NodeSpec, param: Param, value: Node, scope: Scope) -> Val | None:
        """Check one parameter value and store it on ``spec``."""
        val = self.val(value, scope, spec.path)
        if val is None:
            return None
        here = location(val.file, val.node)
        spec.params[param.name] = val.value
        spec.param_locations[param.name] = here
        if val.param_type == param.type and param.type != "marker":
            return val  # checked where the include argument was given
        problems = check_value(param.type, val.value, val.node, val.file, base_dir_of(val.file), param.choices)
        for where, message in problems:
            self.log.add(where, f"parameter {param.name!r} for {spec.kind}: {message}", spec.path)
        if param.type == "marker" and not problems and not is_reference(val.value) \
                and not template_names(val.value):
            self.markers.append(MarkerUse(val.value, here, spec, param.name))
        return val if not problems else None

    def children(self, nodes: list[Node], scope: Scope, parent: str, depth: int) -> list[NodeSpec]:
        heads = [h for h in (self.head(n, scope, parent) for n in nodes) if h is not None]
        segments = child_segments([h.name for h in heads], [h.base for h in heads])
        first_line: dict[str, int] = {}
        built = []
        for head, segment in zip(heads, segments, strict=True):
            where = location(scope.file, head.name_node or head.key)
            if segment in first_line:
                self.log.add(where, f"duplicate name {segment!r} among siblings (also at line "
                             f"{first_line[segment]}); sibling names must differ", parent)
                continue
            first_line[segment] = where.line
            spec = self.build(head, scope, f"{parent}/{segment}", segment, depth + 1)
            if spec is not None:
                built.append(spec)
        return built

    # --- includes ----------------------------------------------------------------------------

    def include(self, head: Head, scope: Scope, path: str, segment: str, depth: int) -> NodeSpec | None:
        if head.include_file is None:
            return None
        given = head.include_file.value
        here = location(head.include_file.file, head.include_file.node)
        shown = os.path.normpath(given if scope.file.startswith("<") else os.path.join(base_dir_of(scope.file), given))
        target = scope.base_dir / given
        if not is_file(target):
            candidates = [n for n in names_in(target.parent) if n.endswith((".yaml", ".yml"))]
            self.log.add(here, f"include file {given!r} not found: {_looked_for(target, given, scope)}"
                         f"{did_you_mean(target.name, candidates)}", path)
            return None
        resolved = target.resolve()
        roots = include_roots(scope)
        if not any(resolved.is_relative_to(root) for root in roots):
            self.log.add(here, f"include file {given!r} is outside the folders trees may include from "
                         f"({', '.join(str(r) for r in roots)}); add its folder to {SEARCH_PATH_ENV} to allow it",
                         path)
            return None
        if any(resolved == seen for seen, _ in scope.chain):
            chain = " -> ".join([*(name for _, name in scope.chain), shown])
            self.log.add(here, f"include cycle: {chain}", path)
            return None
        tree = self.open_file(resolved, shown)
        if tree is None or tree.root is None:
            return None
        args = bind(tree.declared, head.include_with, scope, shown, head.key, self.log, path)
        inner = Scope(shown, base_dir_of(shown), args, (*scope.chain, (resolved, shown)))
        root = self.head(tree.root, inner, path)
        if root is None:
            return None
        spec = self.build(root, inner, path, segment, depth)
        if spec is not None:
            spec.include = shown
        return spec

    # --- helpers -----------------------------------------------------------------------------

    def items(self, node: MappingNode, scope: Scope, path: str | None) -> list[tuple[ScalarNode, Node]]:
        return named_items(node, scope.file, self.log, path)

    def val(self, node: Node, scope: Scope, path: str | None) -> Val | None:
        try:
            return scope.value(node)
        except BadValue as e:
            self.log.add(e.error.location, e.error.message, path)
            return None


def _looked_for(target: Path, given: str, scope: Scope) -> str:
    """Where a missing include was looked for: the absolute path, and what ``given`` was taken
    relative to, so a user sees at once whether the folder or the name is wrong."""
    tried = os.path.abspath(target)
    if os.path.isabs(given):
        return f"looked for {tried}"
    origin = "the working folder" if scope.file.startswith("<") else f"the folder of {scope.file}"
    return f"looked for {tried} (relative to {origin}, {os.path.abspath(scope.base_dir)})"


def _unknown_kind(name: str) -> str:
    if name in ("name", "timeout", "child", "children"):
        return (f"{name!r} is not a node kind: a node is one kind key with its options inside it "
                f"(speak: {{text: Hello, {name}: ...}})")
    return f"unknown node kind {name!r}{did_you_mean(name, ALL_KINDS)}"


def _suggest_or_list(name: str, valid: Sequence[str]) -> str:
    """`` (did you mean 'x'?)`` when something is close, else the list of what is accepted."""
    return did_you_mean(name, valid) or f"; expected one of {', '.join(valid)}"


def _is_null(node: Node) -> bool:
    return isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:null"


def _option_names(kind: str) -> list[str]:
    if kind in LEAVES:
        return LEAVES[kind].param_names
    known = COMPOSITES.get(kind) or DECORATORS.get(kind)
    return [p.name for p in known.params] if known else list(INCLUDE_KEYS)


def _option_hint(kind: NodeKind) -> str:
    return f" and {', '.join(repr(p.name) for p in kind.params)}" if kind.params else ""


def _shorthand_hint(shorthand: str | None) -> str:
    return f" or a single {shorthand} value" if shorthand else ""


SEARCH_PATH_ENV = "STUART_BT_TREE_PATH"  # more folders trees may include from, separated like PATH


def include_roots(scope: Scope) -> list[Path]:
    """The folders an include may name a file in: the top-level tree's folder, the working
    folder, and the folders on STUART_BT_TREE_PATH. Anything else (``include: /etc/shadow``) is
    refused unread, so an error can never quote a file that is not the user's tree."""
    top = scope.chain[0][0].parent if scope.chain else Path.cwd().resolve()
    extra = [Path(p).resolve() for p in os.environ.get(SEARCH_PATH_ENV, "").split(os.pathsep) if p]
    return list(dict.fromkeys([top, Path.cwd().resolve(), *extra]))
