"""Include parameters: declaring them, binding ``with:`` arguments, substituting them into values.

A subtree file declares ``params``; an ``include`` passes arguments under ``with:``. Inside the
included file, a whole value ``$p`` or a template ``${p}`` naming a declared parameter is
replaced while loading, so the expanded tree holds plain values. Every other ``$key`` stays a
run-time blackboard reference. Values remember where they were written (:class:`Val`), so a
bad argument is reported at the ``with:`` entry that gave it, not inside the subtree, and a
relative file path stays relative to the file it was written in.
"""

from __future__ import annotations

import copy
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from yaml.nodes import MappingNode, Node, ScalarNode

from ..core.blackboard import REF, TEMPLATE
from ..core.catalogue import PARAM_TYPES
from ..core.suggest import did_you_mean
from .errors import ErrorLog
from .values import check_value
from .yaml_source import BadValue, location, named_items, to_python

PARAM_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
DECLARATION_KEYS = ("type", "default", "doc", "choices")


@dataclass(frozen=True)
class Declared:
    """One declared include parameter; ``default_node`` is ``None`` when it is required."""

    name: str
    type: str
    default: Any
    default_node: Node | None
    doc: str | None
    choices: tuple[str, ...]

    @property
    def required(self) -> bool:
        return self.default_node is None

    def default_value(self, file: str) -> Val:
        """The default as an argument's value (only for a parameter that has one)."""
        assert self.default_node is not None, f"parameter {self.name!r} is required: it has no default"
        return Val(self.default, self.default_node, file, self.type)

    def as_written(self) -> dict[str, Any]:
        out: dict[str, Any] = {"type": self.type}
        if not self.required:
            out["default"] = self.default
        if self.doc is not None:
            out["doc"] = self.doc
        if self.choices:
            out["choices"] = list(self.choices)
        return out


@dataclass(frozen=True)
class Val:
    """A value after substitution, with the node and file where it was written.

    ``param_type`` is the declared type of the include parameter it came from whole, if any:
    that type was already checked at the argument, so a leaf need not check it again.
    """

    value: Any
    node: Node
    file: str
    param_type: str | None = None


class Scope:
    """The include parameters visible in one file instance, and where that file lives."""

    def __init__(self, file: str, base_dir: Path, args: dict[str, Val],
                 chain: tuple[tuple[Path, str], ...] = ()) -> None:
        self.file = file
        self.base_dir = base_dir
        self.args = args
        self.chain = chain  # (resolved, as shown) for each file from the top-level tree down to this one

    def value(self, node: Node) -> Val:
        """The plain value of ``node`` with declared parameters substituted; raises BadValue."""
        raw = to_python(node, self.file)
        if isinstance(raw, str):
            m = REF.match(raw)
            if m and m.group(1) in self.args:
                arg = self.args[m.group(1)]
                return Val(copy.deepcopy(arg.value), arg.node, arg.file, arg.param_type)
        return Val(self._substitute(raw), node, self.file)

    def _substitute(self, value: Any) -> Any:
        if isinstance(value, str):
            m = REF.match(value)
            if m and m.group(1) in self.args:
                return copy.deepcopy(self.args[m.group(1)].value)
            return "$$".join(TEMPLATE.sub(self._fill, part) for part in value.split("$$"))
        if isinstance(value, list):
            return [self._substitute(v) for v in value]
        if isinstance(value, dict):
            return {k: self._substitute(v) for k, v in value.items()}
        return value

    def _fill(self, m: re.Match[str]) -> str:
        arg = self.args.get(m.group(1))
        if arg is None:
            return m.group(0)
        ref = REF.match(arg.value) if isinstance(arg.value, str) else None
        if ref:  # a blackboard reference passed as argument stays a run-time template
            return "${" + ref.group(1) + "}"
        if isinstance(arg.value, float):
            return f"{arg.value:g}"
        return str(arg.value)


def base_dir_of(file: str) -> Path:
    """Folder that relative paths in ``file`` start from; text without a file uses the cwd."""
    return Path(".") if file.startswith("<") else Path(os.path.dirname(file) or ".")


def read_declarations(node: Node, scope: Scope, log: ErrorLog) -> dict[str, Declared]:
    """The ``params:`` block of a tree file."""
    if not isinstance(node, MappingNode):
        log.add(location(scope.file, node), "'params' must be a mapping: name: {type: ..., default: ..., doc: ...}")
        return {}
    declared: dict[str, Declared] = {}
    for key, value in named_items(node, scope.file, log):
        name = key.value
        if not PARAM_NAME.match(name):
            log.add(location(scope.file, key), f"parameter name {name!r} must be letters, digits and '_'")
            continue
        item = _declaration(name, value, scope, log)
        if item is not None:
            declared[name] = item
    return declared


def _declaration(name: str, node: Node, scope: Scope, log: ErrorLog) -> Declared | None:
    if isinstance(node, ScalarNode) and node.tag.endswith(":null"):
        return Declared(name, "any", None, None, None, ())
    if not isinstance(node, MappingNode):
        log.add(location(scope.file, node),
                f"parameter {name!r} must be a mapping: {{type: ..., default: ..., doc: ...}}")
        return None
    fields: dict[str, tuple[Any, Node]] = {}
    for key, value in named_items(node, scope.file, log):
        if key.value not in DECLARATION_KEYS:
            log.add(location(scope.file, key),
                    f"unknown key {key.value!r} in parameter {name!r}{did_you_mean(key.value, DECLARATION_KEYS)}")
            continue
        try:
            fields[key.value] = (to_python(value, scope.file), value)
        except BadValue as e:
            log.extend([e.error])
    type_, type_node = fields.get("type", ("any", node))
    if type_ not in PARAM_TYPES:
        log.add(location(scope.file, type_node), f"unknown parameter type {type_!r}"
                f"{did_you_mean(str(type_), PARAM_TYPES)}; expected one of {', '.join(PARAM_TYPES)}")
        return None
    choices, choices_node = fields.get("choices", ([], node))
    if type_ != "choice" and "choices" in fields:
        log.add(location(scope.file, choices_node), f"'choices' of parameter {name!r} only apply to type: choice")
        return None
    if type_ == "choice" and (not isinstance(choices, list) or not choices
                              or not all(isinstance(c, str) for c in choices)):
        log.add(location(scope.file, choices_node),
                f"parameter {name!r} of type choice needs 'choices': a list of names")
        return None
    doc, doc_node = fields.get("doc", (None, node))
    if doc is not None and not isinstance(doc, str):
        log.add(location(scope.file, doc_node), f"'doc' of parameter {name!r} must be text")
    default, default_node = fields.get("default", (None, None))
    if default_node is not None:
        for where, message in check_value(type_, default, default_node, scope.file, scope.base_dir, choices):
            log.add(where, f"default of parameter {name!r}: {message}")
    return Declared(name, type_, default, default_node, doc if isinstance(doc, str) else None, tuple(choices))


def defaults(declared: dict[str, Declared], file: str) -> dict[str, Val]:
    """Arguments for a file loaded on its own: declared defaults; required ones stay ``$name``."""
    return {d.name: d.default_value(file) for d in declared.values() if not d.required}


def bind(
    declared: dict[str, Declared],
    with_node: Node | None,
    includer: Scope,
    included_file: str,
    at: Node,
    log: ErrorLog,
    path: str,
) -> dict[str, Val]:
    """Arguments for one include: check each ``with:`` entry against the declarations."""
    given: dict[str, tuple[Val, Node]] = {}
    if with_node is not None and not (isinstance(with_node, ScalarNode) and with_node.tag.endswith(":null")):
        if not isinstance(with_node, MappingNode):
            log.add(location(includer.file, with_node), "'with' must be a mapping of parameter: value", path)
            return {}
        for key, value in named_items(with_node, includer.file, log, path):
            name = key.value
            if name not in declared:
                known = f"; it declares {', '.join(declared)}" if declared else "; it declares no parameters"
                log.add(location(includer.file, key), f"unknown argument {name!r} for {included_file}"
                        f"{did_you_mean(name, declared)}{known}", path)
                continue
            try:
                given[name] = (includer.value(value), key)
            except BadValue as e:
                log.add(e.error.location, e.error.message, path)
    args: dict[str, Val] = {}
    for d in declared.values():
        if d.name in given:
            val, _ = given[d.name]
            if _check_argument(d, val, included_file, log, path):
                args[d.name] = Val(val.value, val.node, val.file, d.type)
        elif d.required:
            log.add(location(includer.file, with_node if isinstance(with_node, MappingNode) else at),
                    f"missing argument {d.name!r} for {included_file} (a required parameter)", path)
        else:
            args[d.name] = d.default_value(included_file)
    return args


def _check_argument(d: Declared, val: Val, included_file: str, log: ErrorLog, path: str) -> bool:
    if val.param_type == d.type and d.type != "choice":
        return True
    problems = check_value(d.type, val.value, val.node, val.file, base_dir_of(val.file), d.choices)
    for where, message in problems:
        log.add(where, f"argument {d.name!r} for {included_file}: {message}", path)
    return not problems


