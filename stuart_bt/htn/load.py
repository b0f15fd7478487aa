"""Reading a domain file: every key checked at file:line:column with did-you-mean, all problems
reported at once, nothing half loaded (docs/htn.md).

This module reads the file's top level (its name, state variables and which tasks it declares)
and hands each task's body to the readers below it, one job each, bottom first:
:mod:`.misnamed` (the "no such name" wording), :mod:`.read_yaml` (nodes, positions, shapes),
:mod:`.read_expressions` (preconditions, values, hooks, templates), :mod:`.read_primitives`
and :mod:`.read_methods`.
"""

from __future__ import annotations

from pathlib import Path

from yaml.nodes import MappingNode, Node, ScalarNode

from ..tree import yaml_source as ys
from ..tree.errors import ErrorLog, TreeLoadError
from ..tree.spec import Location
from .domain import MISSING, PARAM_TYPES, Definition, Domain, ParamDef, PrimitiveDef, StateVarDef
from .hooks import HookRegistry
from .misnamed import misnamed
from .read_methods import MethodReader
from .read_primitives import PrimitiveReader
from .read_yaml import Items

TOP_KEYS = ("domain", "description", "state", "primitives", "tasks", "ack_with")


class DomainLoadError(TreeLoadError):
    """The domain file could not be loaded; ``errors`` lists every problem, in reading order."""


def load_domain(path: str | Path, hooks: HookRegistry | None = None) -> Domain:
    """Load and check a domain file; raises :class:`DomainLoadError` listing every problem."""
    file = str(path)
    return _Loader(file, hooks or HookRegistry()).load(ys.read_file(Path(path), file))


def load_domain_text(text: str, file: str = "<domain>", hooks: HookRegistry | None = None) -> Domain:
    return _Loader(file, hooks or HookRegistry()).load(ys.read_text(text, file))


class _Loader(PrimitiveReader, MethodReader):
    """Two passes over the file: first every task's name, kind and parameters (so a body may
    call a task defined further down), then every body; then the checks across tasks."""

    def load(self, source: ys.Source) -> Domain:
        self.log.extend(source.errors)
        if source.root is None:
            if not source.errors:
                self.log.add(Location(self.file, 1, 1), "the domain file is empty")
            raise DomainLoadError(self.log.in_reading_order())
        top = self.items(source.root, "domain", TOP_KEYS)
        name = self.text(top["domain"][1], "domain") if "domain" in top else None
        if "domain" not in top:
            self.log.add(Location(self.file, 1, 1), "missing 'domain: NAME' at the top")
        description = self.text(top["description"][1], "description") if "description" in top else ""
        ack_with = (self.text(top["ack_with"][1], "ack_with") if "ack_with" in top else None) or "acknowledge"
        if "state" in top:
            self.read_state(top["state"][1])
        sections = self.declare_tasks(top)
        definitions = self.define_tasks(sections)
        self.check_ack(ack_with, definitions)
        if self.log:
            raise DomainLoadError(self.log.in_reading_order())
        return Domain(name or "domain", self.file, self.state_vars, definitions, self.hooks, ack_with,
                      description or "")

    def declare_tasks(self, top: Items) -> dict[str, Items]:
        """First pass: every task's name, kind and parameters, so bodies may name tasks that
        are defined later in the file."""
        sections: dict[str, Items] = {}
        for section in ("primitives", "tasks"):
            sections[section] = self.items(top[section][1], section) if section in top else {}
            for tname, (key, value) in sections[section].items():
                if not self.name_ok(key, "task", section):
                    continue
                if tname in self.kinds:
                    self.err(key, f"task {tname!r} is defined twice (as a primitive and as a compound task)", section)
                    continue
                self.kinds[tname] = "primitive" if section == "primitives" else "compound"
                self.params[tname] = self.read_params(value, f"{section}.{tname}")
        if not sections["tasks"] and not sections["primitives"]:
            self.log.add(Location(self.file, 1, 1), "the domain defines no tasks ('primitives:' and 'tasks:')")
        return sections

    def define_tasks(self, sections: dict[str, Items]) -> dict[str, Definition]:
        """Second pass: each declared task's body."""
        definitions: dict[str, Definition] = {}
        for tname, (key, value) in sections["primitives"].items():
            prim = self.read_primitive(tname, key, value) if self.kinds.get(tname) == "primitive" else None
            if prim is not None:
                definitions[tname] = prim
        for tname, (key, value) in sections["tasks"].items():
            task = self.read_task(tname, key, value) if self.kinds.get(tname) == "compound" else None
            if task is not None:
                definitions[tname] = task
        return definitions

    def read_state(self, node: Node) -> None:
        for vname, (key, value) in self.items(node, "state").items():
            path = f"state.{vname}"
            if not self.name_ok(key, "state variable", "state"):
                continue
            if isinstance(value, ScalarNode) and value.tag == "tag:yaml.org,2002:null":
                self.state_vars[vname] = StateVarDef(vname)
                continue
            spec = self.items(value, path, ("default", "doc"))
            default = self.python(spec["default"][1], path) if "default" in spec else None
            self.state_vars[vname] = StateVarDef(vname, None if default is MISSING else default, self.doc(spec, path))

    def read_params(self, task_node: Node, path: str) -> list[ParamDef]:
        """A task's ``params:``, read ahead of its body (which the second pass reads, reporting
        its problems, so this pass logs nothing about the rest of the task)."""
        if not isinstance(task_node, MappingNode):
            return []
        entries = {str(k.value): (k, v) for k, v in ys.named_items(task_node, self.file, ErrorLog(), path)}
        if "params" not in entries:
            return []
        ppath = f"{path}.params"
        params = []
        for pname, (key, value) in self.items(entries["params"][1], ppath).items():
            if not self.name_ok(key, "parameter", ppath):
                continue
            if pname in self.state_vars:
                self.err(key, f"parameter {pname!r} would hide the state variable of that name; rename it", ppath)
            param = self.read_param(pname, value, ppath)
            if param is not None:
                params.append(param)
        return params

    def read_param(self, pname: str, value: Node, ppath: str) -> ParamDef | None:
        """``name: TYPE`` or ``name: {type: TYPE, default: VALUE, doc: TEXT}``; None when the
        type is not text (an unknown type name keeps the parameter, typed 'any')."""
        if isinstance(value, MappingNode):
            spec = self.items(value, f"{ppath}.{pname}", ("type", "default", "doc"))
            tnode = spec["type"][1] if "type" in spec else None
            ptype = self.text(tnode, ppath, "a type name") if tnode is not None else "any"
            default = self.python(spec["default"][1], ppath) if "default" in spec else MISSING
            doc = self.doc(spec, ppath)
            where = tnode if tnode is not None else value
        else:
            ptype, default, doc, where = self.text(value, ppath, "a type name"), MISSING, "", value
        if ptype is None:
            return None
        if ptype not in PARAM_TYPES:
            self.err(where, misnamed("unknown type", ptype, PARAM_TYPES, "types"), ppath)
            ptype = "any"  # keep the parameter: uses of it are not errors too
        return ParamDef(pname, ptype, default, doc)

    def check_ack(self, ack_with: str, definitions: dict[str, Definition]) -> None:
        if not self.ack_uses:
            return
        prim = definitions.get(ack_with)
        if isinstance(prim, PrimitiveDef) and len(prim.params) == 1 and prim.params[0].type == "string":
            return
        node, path = self.ack_uses[0]
        self.err(node, f"'ack' needs a primitive {ack_with!r} with one string parameter (the text to say); "
                       f"define it under 'primitives:' or name another with 'ack_with:'", path)

