"""Reading YAML safely while keeping every node's position.

Tree files are composed (not constructed) with a :class:`yaml.SafeLoader` subclass, so every
node keeps its start mark for error messages and nothing in a file can run code. Files are
checked against hostile or accidental shapes before the loader walks them: size, encoding,
tabs, nesting depth, alias expansion ("billion laughs") and recursive aliases, and duplicate
keys, which PyYAML would otherwise silently resolve to the last one.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from yaml.constructor import ConstructorError, SafeConstructor
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from ..core.jsonfile import NotARegularFile, read_limited
from .errors import ErrorLog, TreeError
from .spec import Location
from .yaml_errors import syntax_error

MAX_BYTES = 1024 * 1024
MAX_DEPTH = 100
MAX_NODES = 200_000
MERGE_TAG = "tag:yaml.org,2002:merge"
_SEQ_TAG = "tag:yaml.org,2002:seq"
_MAP_TAG = "tag:yaml.org,2002:map"
_CONSTRUCTOR = SafeConstructor()
_COLLECTION_TAGS = {_SEQ_TAG, _MAP_TAG, "tag:yaml.org,2002:omap", "tag:yaml.org,2002:pairs", "tag:yaml.org,2002:set"}


@dataclass
class Source:
    """One composed YAML document: its root node (``None`` if empty or unreadable) and problems.

    ``errors`` may be non-empty while ``root`` is set: duplicate keys are reported but do not
    stop the rest of the file from being checked.
    """

    file: str
    root: Node | None
    errors: list[TreeError] = field(default_factory=list)


class BadValue(Exception):
    """A YAML value that cannot become plain data (unknown tag, bad merge, unhashable key)."""

    def __init__(self, location: Location, message: str) -> None:
        super().__init__(message)
        self.error = TreeError(location, message)


class _Limit(Exception):
    def __init__(self, mark: yaml.Mark, message: str) -> None:
        super().__init__(message)
        self.mark = mark
        self.message = message


class _Loader(yaml.SafeLoader):
    """SafeLoader that refuses documents nested too deeply or with too many nodes while composing."""

    def __init__(self, stream: str) -> None:
        super().__init__(stream)
        self._depth = 0
        self._count = 0

    def compose_node(self, parent: Node | None, index: Any) -> Node | None:
        self._depth += 1
        self._count += 1
        try:
            if self._depth > MAX_DEPTH:
                raise _Limit(self.peek_event().start_mark, f"nesting deeper than {MAX_DEPTH} levels")
            if self._count > MAX_NODES:
                raise _Limit(self.peek_event().start_mark, f"more than {MAX_NODES} YAML nodes")
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1


def location(file: str, node: Node | yaml.Mark) -> Location:
    """1-based position of a node (its start) or a mark."""
    mark = node.start_mark if isinstance(node, Node) else node
    return Location(file, mark.line + 1, mark.column + 1)


def read_file(path: Path, file: str) -> Source:
    """Compose the YAML file at ``path``; ``file`` is the name used in error locations."""
    start = Location(file, 1, 1)
    try:
        size = path.stat().st_size
        if size > MAX_BYTES:
            return Source(file, None, [TreeError(start, f"file is {size} bytes; tree files are limited to 1 MB")])
        data = read_limited(path, MAX_BYTES)
    except FileNotFoundError:
        return Source(file, None, [TreeError(None, f"{file}: file not found")])
    except NotARegularFile as e:  # a FIFO would hang the loader, a device fill its memory
        return Source(file, None, [TreeError(None, f"{file}: {e}")])
    except (OSError, ValueError) as e:  # ValueError: a NUL byte in the name
        return Source(file, None, [TreeError(None, f"{file}: cannot read: {getattr(e, 'strerror', None) or e}")])
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        line = data.count(b"\n", 0, e.start) + 1
        line_start = data.rfind(b"\n", 0, e.start) + 1
        column = len(data[line_start:e.start].decode("utf-8", errors="replace")) + 1
        return Source(file, None, [TreeError(Location(file, line, column),
                                             f"byte 0x{data[e.start]:02x} is not valid UTF-8; save the file as UTF-8")])
    return read_text(text, file)


def read_text(text: str, file: str) -> Source:
    """Compose YAML ``text``, checking limits, tabs, aliases and duplicate keys."""
    if len(text.encode("utf-8", errors="replace")) > MAX_BYTES:
        too_big = TreeError(Location(file, 1, 1), "text is larger than the 1 MB limit for tree files")
        return Source(file, None, [too_big])
    bad_char = yaml.reader.Reader.NON_PRINTABLE.search(text)
    if bad_char:
        return Source(file, None, [_control_character(text, file, bad_char.start())])
    loader = _Loader(text)
    try:
        root = loader.get_single_node()
    except _Limit as e:
        return Source(file, None, [TreeError(location(file, e.mark), e.message)])
    except RecursionError:
        return Source(file, None, [TreeError(Location(file, 1, 1), f"nesting deeper than {MAX_DEPTH} levels")])
    except yaml.MarkedYAMLError as e:
        return Source(file, None, [syntax_error(e, text, file)])
    except yaml.YAMLError as e:
        return Source(file, None, [TreeError(Location(file, 1, 1), f"YAML error: {e}")])
    finally:
        loader.dispose()
    if root is None:
        return Source(file, None)
    errors: list[TreeError] = []
    try:
        _Measure(file, errors).visit(root, 1)
    except _Limit as e:
        return Source(file, None, [*errors, TreeError(location(file, e.mark), e.message)])
    if any("unsupported YAML tag" in e.message for e in errors):
        return Source(file, None, errors)  # the tagged values cannot be read: report only the tags
    return Source(file, root, errors)


def _control_character(text: str, file: str, pos: int) -> TreeError:
    line = text.count("\n", 0, pos) + 1
    column = pos - (text.rfind("\n", 0, pos) + 1) + 1
    return TreeError(Location(file, line, column), f"control character U+{ord(text[pos]):04X} is not allowed in YAML")


def tag_problem(node: Node) -> str | None:
    """Why an explicit tag is not allowed, or None: only plain YAML data types are accepted
    (a ``!!python/...`` tag, or any application tag, never reaches a constructor)."""
    if isinstance(node, MappingNode):
        ok = node.tag == _MAP_TAG
    elif isinstance(node, SequenceNode):
        ok = node.tag == _SEQ_TAG
    else:
        ok = node.tag == MERGE_TAG or (node.tag in SafeConstructor.yaml_constructors
                                       and node.tag not in _COLLECTION_TAGS)
    return None if ok else f"unsupported YAML tag {node.tag!r}; tree files hold plain data only"


class _Measure:
    """Walk the composed graph once: expanded size and depth (aliases counted each time they
    are used), recursive aliases, and duplicate keys in every mapping."""

    def __init__(self, file: str, errors: list[TreeError]) -> None:
        self.file = file
        self.errors = errors
        self.done: dict[int, tuple[int, int]] = {}  # id(node) -> (expanded size, height)
        self.active: set[int] = set()

    def _check_tag(self, node: Node) -> None:
        problem = tag_problem(node)
        if problem:
            self.errors.append(TreeError(location(self.file, node), problem))

    def visit(self, node: Node, depth: int) -> tuple[int, int]:
        key = id(node)
        if key in self.active:
            raise _Limit(node.start_mark, "a YAML alias refers to a node that contains it (recursive alias)")
        if key in self.done:
            size, height = self.done[key]
        else:
            if depth > MAX_DEPTH:
                raise _Limit(node.start_mark, f"nesting deeper than {MAX_DEPTH} levels")
            self._check_tag(node)
            self.active.add(key)
            size, height = 1, 1
            for child in _children(node):
                s, h = self.visit(child, depth + 1)
                size += s
                height = max(height, h + 1)
            self.active.discard(key)
            self.done[key] = (size, height)
            if isinstance(node, MappingNode):
                self._check_duplicates(node)
        if depth + height - 1 > MAX_DEPTH:
            raise _Limit(node.start_mark, f"nesting deeper than {MAX_DEPTH} levels (through aliases)")
        if size > MAX_NODES:
            raise _Limit(node.start_mark, f"aliases expand to more than {MAX_NODES} YAML nodes")
        return size, height

    def _check_duplicates(self, node: MappingNode) -> None:
        seen: dict[tuple[str, str], Node] = {}
        for key, _ in node.value:
            if not isinstance(key, ScalarNode) or key.tag == MERGE_TAG:
                continue
            ident = (key.tag, key.value)
            if ident in seen:
                first = location(self.file, seen[ident])
                self.errors.append(TreeError(location(self.file, key),
                                             f"duplicate key {key.value!r} (first defined at line {first.line})"))
            else:
                seen[ident] = key


def _children(node: Node) -> list[Node]:
    if isinstance(node, SequenceNode):
        return list(node.value)
    if isinstance(node, MappingNode):
        return [n for pair in node.value for n in pair]
    return []


def mapping_items(node: MappingNode, file: str) -> list[tuple[Node, Node]]:
    """Key/value pairs with YAML merge keys (``<<: *base``) applied: own keys win over merged ones."""
    own: list[tuple[Node, Node]] = []
    merged: list[tuple[Node, Node]] = []
    for key, value in node.value:
        if key.tag != MERGE_TAG:
            own.append((key, value))
            continue
        sources = value.value if isinstance(value, SequenceNode) else [value]
        for source in sources:
            if not isinstance(source, MappingNode):
                raise BadValue(location(file, source), "a merge key '<<' needs a mapping or a list of mappings")
            merged.extend(mapping_items(source, file))
    names = {_key_text(k) for k, _ in own}
    result: list[tuple[Node, Node]] = []
    for key, value in merged:
        text = _key_text(key)
        if text not in names:
            names.add(text)
            result.append((key, value))
    return result + own


def named_items(node: MappingNode, file: str, log: ErrorLog, path: str | None = None) -> list[tuple[ScalarNode, Node]]:
    """Pairs whose keys are plain names; a bad merge key or a list/mapping key is reported and skipped."""
    try:
        pairs = mapping_items(node, file)
    except BadValue as e:
        log.add(e.error.location, e.error.message, path)
        return []
    named = []
    for key, value in pairs:
        if isinstance(key, ScalarNode):
            named.append((key, value))
        else:
            log.add(location(file, key), "keys must be plain names, not lists or mappings", path)
    return named


def _key_text(node: Node) -> str | None:
    return node.value if isinstance(node, ScalarNode) else None


def to_python(node: Node, file: str) -> Any:
    """Plain data for a composed node, using the safe YAML types only."""
    if isinstance(node, ScalarNode):
        construct = SafeConstructor.yaml_constructors.get(node.tag)
        if construct is None or node.tag in _COLLECTION_TAGS:
            raise BadValue(location(file, node), f"unsupported YAML tag {node.tag!r}")
        try:
            return construct(_CONSTRUCTOR, node)
        except (ConstructorError, ValueError) as e:
            raise BadValue(location(file, node), f"bad {node.tag.rsplit(':', 1)[-1]} value: {e}") from None
    if isinstance(node, SequenceNode):
        if node.tag != _SEQ_TAG:
            raise BadValue(location(file, node), f"unsupported YAML tag {node.tag!r}")
        return [to_python(item, file) for item in node.value]
    if isinstance(node, MappingNode):
        if node.tag != _MAP_TAG:
            raise BadValue(location(file, node), f"unsupported YAML tag {node.tag!r}")
        result: dict[Any, Any] = {}
        for key, value in mapping_items(node, file):
            k = to_python(key, file)
            try:
                result[k] = to_python(value, file)
            except TypeError:
                raise BadValue(location(file, key),
                               "mapping keys must be plain values, not lists or mappings") from None
        return result
    raise BadValue(location(file, node), "unsupported YAML node")
