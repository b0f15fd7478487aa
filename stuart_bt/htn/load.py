"""Reading a domain file: every key checked at file:line:column with did-you-mean, all problems
reported at once, nothing half loaded (docs/htn.md).
"""

from __future__ import annotations

import ast
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from ..core import expr as bbexpr
from ..core.catalogue import LEAVES, SKILLS  # primitives bind to skill leaves (daemon leaves, wait, stop)
from ..core.suggest import did_you_mean
from ..tree import yaml_source as ys
from ..tree.errors import ErrorLog, TreeLoadError
from ..tree.spec import Location
from .domain import (
    MISSING,
    PARAM_TYPES,
    CallTemplate,
    Definition,
    Domain,
    ForTemplate,
    MethodDef,
    ParamDef,
    PrimitiveDef,
    RunTemplate,
    StateVarDef,
    Subtask,
    Target,
    TaskDef,
    check_skill_args,
)
from .expressions import Clause, Expr, Scope, SkipIf, Value, _CompileError, compile_expr, parse_template
from .hooks import Hook, HookRegistry
from .values import RESERVED, format_value

_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")

TOP_KEYS = ("domain", "description", "state", "primitives", "tasks", "ack_with")

PRIMITIVE_KEYS = ("doc", "params", "skill", "args", "pre", "effects", "remove", "optional", "skip_if")

TASK_KEYS = ("doc", "params", "intent", "ack", "methods")

METHOD_KEYS = ("name", "doc", "pre", "do", "ack")


class DomainLoadError(TreeLoadError):
    """The domain file could not be loaded; ``errors`` lists every problem, in reading order."""


def load_domain(path: str | Path, hooks: HookRegistry | None = None) -> Domain:
    """Load and check a domain file; raises :class:`DomainLoadError` listing every problem."""
    file = str(path)
    return _Loader(file, hooks or HookRegistry()).load(ys.read_file(Path(path), file))


def load_domain_text(text: str, file: str = "<domain>", hooks: HookRegistry | None = None) -> Domain:
    return _Loader(file, hooks or HookRegistry()).load(ys.read_text(text, file))


class _Loader:
    def __init__(self, file: str, hooks: HookRegistry) -> None:
        self.file = file
        self.hooks = hooks
        self.log = ErrorLog()
        self.state_vars: dict[str, StateVarDef] = {}
        self.params: dict[str, list[ParamDef]] = {}
        self.kinds: dict[str, str] = {}  # task name -> "primitive" | "compound"
        self.ack_uses: list[tuple[Node, str]] = []

    # helpers -----------------------------------------------------------------------------------------
    def loc(self, node: Node, column: int = 1) -> Location:
        """Where ``node`` starts; for a one-line scalar, ``column`` within its text."""
        base = ys.location(self.file, node)
        if column > 1 and isinstance(node, ScalarNode) and node.start_mark.line == node.end_mark.line \
                and node.style in (None, "'", '"'):
            return Location(self.file, base.line, base.column + (0 if node.style is None else 1) + column - 1)
        return base

    def err(self, node: Node, message: str, path: str | None, column: int = 1) -> None:
        self.log.add(self.loc(node, column), message, path)

    def items(self, node: Node, path: str, allowed: Sequence[str] | None = None) -> dict[str, tuple[ScalarNode, Node]]:
        if not isinstance(node, MappingNode):
            self.err(node, f"expected a mapping, got {_shape(node)}", path)
            return {}
        out: dict[str, tuple[ScalarNode, Node]] = {}
        for key, value in ys.named_items(node, self.file, self.log, path):
            name = str(key.value)
            if allowed is not None and name not in allowed:
                self.err(key, f"unknown key {name!r}{did_you_mean(name, allowed)} "
                              f"(expected: {', '.join(allowed)})", path)
                continue
            out[name] = (key, value)
        return out

    def text(self, node: Node, path: str, what: str = "text") -> str | None:
        if isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:str":
            return str(node.value)
        self.err(node, f"expected {what}, got {_shape(node)}", path)
        return None

    def python(self, node: Node, path: str) -> Any:
        try:
            return ys.to_python(node, self.file)
        except ys.BadValue as e:
            self.log.add(e.error.location, e.error.message, path)
            return MISSING

    def name_ok(self, key: ScalarNode, what: str, path: str) -> bool:
        name = str(key.value)
        if not _IDENT.match(name) or name in RESERVED:
            self.err(key, f"{what} {name!r} must be a plain name (letters, digits, '_', not starting with '_' "
                          f"or a digit, not one of {', '.join(sorted(RESERVED))})", path)
            return False
        return True

    # the file ----------------------------------------------------------------------------------------
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

    def declare_tasks(self, top: dict[str, tuple[ScalarNode, Node]]) -> dict[str, dict[str, tuple[ScalarNode, Node]]]:
        """First pass: every task's name, kind and parameters, so bodies may name tasks that
        are defined later in the file."""
        sections: dict[str, dict[str, tuple[ScalarNode, Node]]] = {}
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

    def define_tasks(self, sections: dict[str, dict[str, tuple[ScalarNode, Node]]]) -> dict[str, Definition]:
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
            doc = (self.text(spec["doc"][1], path) or "") if "doc" in spec else ""
            self.state_vars[vname] = StateVarDef(vname, None if default is MISSING else default, doc)

    def read_params(self, task_node: Node, path: str) -> list[ParamDef]:
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
            if isinstance(value, MappingNode):
                spec = self.items(value, f"{ppath}.{pname}", ("type", "default", "doc"))
                tnode = spec.get("type", (None, None))[1]
                ptype = self.text(tnode, ppath, "a type name") if tnode is not None else "any"
                default = self.python(spec["default"][1], ppath) if "default" in spec else MISSING
                doc = (self.text(spec["doc"][1], ppath) or "") if "doc" in spec else ""
                where = tnode if tnode is not None else value
            else:
                ptype, default, doc, where = self.text(value, ppath, "a type name"), MISSING, "", value
            if ptype is None:
                continue
            if ptype not in PARAM_TYPES:
                self.err(where, f"unknown type {ptype!r}{did_you_mean(ptype, PARAM_TYPES)} "
                                f"(types: {', '.join(PARAM_TYPES)})", ppath)
                ptype = "any"  # keep the parameter: uses of it are not errors too
            params.append(ParamDef(pname, ptype, default, doc))
        return params

    def scope(self, tname: str) -> Scope:
        return Scope(f"{tname!r}", tuple(p.name for p in self.params.get(tname, [])), frozenset(self.state_vars))

    # compiled pieces ---------------------------------------------------------------------------------
    def compile(self, text: str, scope: Scope, node: Node, path: str, offset: int = 0) -> Expr | None:
        try:
            return compile_expr(text, scope)
        except _CompileError as e:
            self.err(node, e.message, path, offset + e.column)
            return None

    def read_conditions(self, node: Node, scope: Scope, path: str) -> list[Clause]:
        items = node.value if isinstance(node, SequenceNode) else [node]
        clauses: list[Clause] = []
        for item in items:
            if isinstance(item, MappingNode):
                clause = self.read_hook_clause(item, scope, path)
                if clause is not None:
                    clauses.append(clause)
                continue
            text = self.text(item, path, "an expression or {hook: name}")
            if text is None:
                continue
            clauses += self.split_clauses(text, scope, item, path)
        return clauses

    def split_clauses(self, text: str, scope: Scope, node: Node, path: str) -> list[Clause]:
        """``a and b and c`` becomes three clauses, so a rejection can name the one that failed."""
        stripped = text.strip()
        lead = len(text) - len(text.lstrip())
        try:
            tree = ast.parse(stripped, mode="eval").body
        except SyntaxError as e:
            self.err(node, f"syntax error in expression {stripped!r}: {e.msg}", path, lead + (e.offset or 1))
            return []
        parts = tree.values if isinstance(tree, ast.BoolOp) and isinstance(tree.op, ast.And) else [tree]
        clauses = []
        for part in parts:
            segment = ast.get_source_segment(stripped, part) or ast.unparse(part)
            expr = self.compile(segment, scope, node, path, lead + part.col_offset)
            if expr is None:
                continue
            membership = None
            if isinstance(part, ast.Compare) and len(part.ops) == 1 and isinstance(part.ops[0], ast.In):
                left = ast.get_source_segment(stripped, part.left) or ast.unparse(part.left)
                right = ast.get_source_segment(stripped, part.comparators[0]) or ast.unparse(part.comparators[0])
                try:
                    membership = (compile_expr(left, scope), compile_expr(right, scope))
                except _CompileError:
                    membership = None
            clauses.append(Clause(segment, expr, membership=membership, location=self.loc(node)))
        return clauses

    def read_hook_clause(self, node: MappingNode, scope: Scope, path: str) -> Clause | None:
        hook, args = self.read_hook_call(node, scope, path, "condition")
        if hook is None:
            return None
        shown = ", ".join(f"{k}={v.text}" for k, v in args.items())
        return Clause(f"hook {hook.name}({shown})", hook=hook, hook_args=args, location=self.loc(node))

    def read_hook_call(self, node: MappingNode, scope: Scope, path: str,
                       kind: str) -> tuple[Hook | None, dict[str, Value]]:
        spec = self.items(node, path, ("hook", "args"))
        if "hook" not in spec:
            self.err(node, "expected {hook: NAME, args: {...}}", path)
            return None, {}
        hname = self.text(spec["hook"][1], path, "a hook name")
        if hname is None:
            return None, {}
        hook = self.hooks.get(hname)
        where = spec["hook"][1]
        if hook is None:
            known = self.hooks.names(kind)
            self.err(where, f"unknown {kind} hook {hname!r}{did_you_mean(hname, known)} "
                            f"(registered: {', '.join(known) or 'none'})", path)
            return None, {}
        if hook.kind != kind:
            self.err(where, f"hook {hname!r} is a {hook.kind} hook; a {kind} hook is needed here", path)
            return None, {}
        args: dict[str, Value] = {}
        if "args" in spec:
            for aname, (akey, avalue) in self.items(spec["args"][1], f"{path}.args").items():
                if aname not in hook.params and not hook.accepts_any:
                    self.err(akey, f"hook {hname!r} has no parameter {aname!r}{did_you_mean(aname, hook.params)} "
                                   f"(parameters: {', '.join(hook.params) or 'none'})", path)
                    continue
                value = self.read_value(avalue, scope, f"{path}.args.{aname}")
                if value is not None:
                    args[aname] = value
        else:  # bind the hook's parameters by name from the task's parameters
            for pname in hook.params:
                if pname in scope.bound:
                    args[pname] = Value("expr", pname, expr=compile_expr(pname, scope))
        missing = [p for p in hook.required if p not in args]
        if missing:
            self.err(node, f"hook {hname!r} needs {', '.join(map(repr, missing))}"
                           f"{'' if 'args' in spec else ' (no task parameter of that name; give args:)'}", path)
            return None, {}
        return hook, args

    def read_value(self, node: Node, scope: Scope, path: str) -> Value | None:
        if isinstance(node, MappingNode):
            keys = {str(k.value) for k, _ in node.value if isinstance(k, ScalarNode)}
            if "hook" in keys:
                hook, args = self.read_hook_call(node, scope, path, "function")
                if hook is None:
                    return None
                return Value("hook", f"{hook.name}(...)", hook=hook, hook_args=args)
            if keys == {"format"}:
                fnode = node.value[0][1]
                text = self.text(fnode, path, "a template")
                if text is None:
                    return None
                try:
                    return Value("format", text, template=parse_template(text, scope))
                except _CompileError as e:
                    self.err(fnode, e.message, path, e.column)
                    return None
        if isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:str":
            expr = self.compile(str(node.value), scope, node, path)
            return None if expr is None else Value("expr", expr.text, expr=expr)
        literal = self.python(node, path)
        if literal is MISSING:
            return None
        return Value("literal", format_value(literal), literal=literal)

    def read_template(self, node: Node, scope: Scope, path: str) -> list[str | Expr] | None:
        text = self.text(node, path, "a text template")
        if text is None:
            return None
        try:
            return parse_template(text, scope)
        except _CompileError as e:
            self.err(node, e.message, path, e.column)
            return None

    # primitives --------------------------------------------------------------------------------------
    def read_primitive(self, tname: str, key: ScalarNode, node: Node) -> PrimitiveDef | None:
        path = f"primitives.{tname}"
        spec = self.items(node, path, PRIMITIVE_KEYS)
        if not isinstance(node, MappingNode):
            return None
        scope = self.scope(tname)
        skill = self.read_skill(tname, key, spec, path)
        if skill is None:
            return None
        args = self.read_skill_args(skill, key, spec, scope, path)
        pre = self.read_conditions(spec["pre"][1], scope, f"{path}.pre") if "pre" in spec else []
        effects = self.read_effects(spec["effects"][1], scope, path) if "effects" in spec else []
        remove = self.read_remove(spec["remove"][1], scope, path) if "remove" in spec else []
        optional = self.read_flag(spec["optional"][1], "optional", path) if "optional" in spec else False
        skip_if = self.read_skip_if(spec["skip_if"][1], scope, path) if "skip_if" in spec else None
        doc = (self.text(spec["doc"][1], path) or "") if "doc" in spec else ""
        return PrimitiveDef(tname, self.params.get(tname, []), skill, args, pre, effects, remove, optional, skip_if,
                            doc, self.loc(key))

    def read_skill(self, tname: str, key: ScalarNode, spec: dict[str, tuple[ScalarNode, Node]],
                   path: str) -> str | None:
        if "skill" not in spec:
            self.err(key, f"primitive {tname!r} needs 'skill:' (one of {', '.join(SKILLS)})", path)
            return None
        skill = self.text(spec["skill"][1], path, "a skill name")
        if skill is not None and skill not in SKILLS:
            self.err(spec["skill"][1], f"unknown skill {skill!r}{did_you_mean(skill, SKILLS)} "
                                       f"(skills: {', '.join(SKILLS)})", path)
            return None
        return skill

    def read_skill_args(self, skill: str, key: ScalarNode, spec: dict[str, tuple[ScalarNode, Node]], scope: Scope,
                        path: str) -> dict[str, Value] | Value:
        """The leaf's parameters: a mapping checked against the skill's catalogue entry, or one
        hook call that returns them (``args: {hook: ...}`` for a skill with no ``hook`` parameter)."""
        if "args" not in spec:
            problem = check_skill_args(skill, [])
            if problem:
                self.err(key, f"{problem}: give them under 'args:'", path)
            return {}
        anode = spec["args"][1]
        keys = {str(k.value) for k, _ in getattr(anode, "value", []) if isinstance(k, ScalarNode)}
        if isinstance(anode, MappingNode) and "hook" in keys and LEAVES[skill].param("hook") is None:
            hook_value = self.read_value(anode, scope, f"{path}.args")
            return hook_value if hook_value is not None else {}
        values: dict[str, Value] = {}
        complete = True
        for aname, (akey, avalue) in self.items(anode, f"{path}.args").items():
            if LEAVES[skill].param(aname) is None:
                self.err(akey, f"skill {skill!r} has no parameter {aname!r}"
                               f"{did_you_mean(aname, LEAVES[skill].param_names)} "
                               f"(parameters: {', '.join(LEAVES[skill].param_names) or 'none'})", path)
                complete = False
                continue
            value = self.read_value(avalue, scope, f"{path}.args.{aname}")
            if value is not None:
                values[aname] = value
            else:
                complete = False
        problem = check_skill_args(skill, values) if complete else None
        if problem:
            self.err(anode, problem, path)
        return values

    def read_effects(self, node: Node, scope: Scope, path: str) -> list[tuple[Target, Value]]:
        effects: list[tuple[Target, Value]] = []
        for tkey, (tnode, vnode) in self.items(node, f"{path}.effects").items():
            target = self.read_target(tkey, tnode, scope, f"{path}.effects")
            value = self.read_value(vnode, scope, f"{path}.effects.{tkey}")
            if target is not None and value is not None:
                effects.append((target, value))
        return effects

    def read_remove(self, node: Node, scope: Scope, path: str) -> list[Target]:
        remove: list[Target] = []
        for item in node.value if isinstance(node, SequenceNode) else [node]:
            text = self.text(item, f"{path}.remove", "a target such as objects[obj]")
            target = self.read_target(text, item, scope, f"{path}.remove") if text else None
            if target is not None and target.key is None:
                self.err(item, f"'remove' takes keys of mapping variables, e.g. {target.var}[obj]", f"{path}.remove")
            elif target is not None:
                remove.append(target)
        return remove

    def read_flag(self, node: Node, name: str, path: str) -> bool:
        value = self.python(node, path)
        if not isinstance(value, bool):
            self.err(node, f"'{name}' must be true or false", path)
            return False
        return value

    def read_target(self, text: str | None, node: Node, scope: Scope, path: str) -> Target | None:
        if text is None:
            return None
        try:
            tree = ast.parse(text.strip(), mode="eval").body
        except SyntaxError:
            tree = None
        if isinstance(tree, ast.Name):
            var, key = tree.id, None
        elif isinstance(tree, ast.Subscript) and isinstance(tree.value, ast.Name):
            var = tree.value.id
            index = ast.get_source_segment(text.strip(), tree.slice) or ast.unparse(tree.slice)
            key = self.compile(index, scope, node, path)
            if key is None:
                return None
        else:
            self.err(node, f"effect target {text!r} must be a state variable or one key of one: at, objects[obj]", path)
            return None
        if var not in self.state_vars:
            self.err(node, f"effect on {var!r}, which is not a declared state variable"
                           f"{did_you_mean(var, self.state_vars)}", path)
            return None
        return Target(var, key, text.strip())

    def read_skip_if(self, node: Node, scope: Scope, path: str) -> SkipIf | None:
        text = self.text(node, path, "a blackboard expression")
        if text is None:
            return None
        try:
            bbexpr.parse(text)
            tree = ast.parse(text.strip(), mode="eval").body
        except (bbexpr.ExprError, SyntaxError) as e:
            self.err(node, f"skip_if: {getattr(e, 'message', None) or e}", path, getattr(e, "column", 1))
            return None
        return SkipIf(text.strip(), tree, frozenset(scope.bound))

    # compound tasks ----------------------------------------------------------------------------------
    def read_task(self, tname: str, key: ScalarNode, node: Node) -> TaskDef | None:
        path = f"tasks.{tname}"
        spec = self.items(node, path, TASK_KEYS)
        if not isinstance(node, MappingNode):
            return None
        scope = self.scope(tname)
        ack = None
        if "ack" in spec:
            ack = self.read_template(spec["ack"][1], scope, f"{path}.ack")
            self.ack_uses.append((spec["ack"][1], path))
        intent = self.read_intent(spec["intent"][1], tname, f"{path}.intent") if "intent" in spec else None
        methods: list[MethodDef] = []
        if "methods" not in spec:
            self.err(key, f"task {tname!r} needs 'methods:' (a list of {{name, pre, do}})", path)
        else:
            mnode = spec["methods"][1]
            if not isinstance(mnode, SequenceNode) or not mnode.value:
                self.err(mnode, "'methods' must be a non-empty list of {name, pre, do}", path)
            else:
                seen: dict[str, Node] = {}
                for i, item in enumerate(mnode.value):
                    method = self.read_method(tname, item, scope, f"{path}.methods[{i}]")
                    if method is None:
                        continue
                    if method.name in seen:
                        self.err(item, f"method name {method.name!r} is used twice in task {tname!r}", path)
                        continue
                    seen[method.name] = item
                    methods.append(method)
        doc = (self.text(spec["doc"][1], path) or "") if "doc" in spec else ""
        return TaskDef(tname, self.params.get(tname, []), methods, ack, intent, doc, self.loc(key))

    def read_intent(self, node: Node, tname: str, path: str) -> dict[str, str]:
        if isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:null":
            return {}
        names = [p.name for p in self.params.get(tname, [])]
        out: dict[str, str] = {}
        for pname, (pkey, fnode) in self.items(node, path).items():
            if pname not in names:
                self.err(pkey, f"task {tname!r} has no parameter {pname!r}{did_you_mean(pname, names)}", path)
                continue
            fld = self.text(fnode, path, "a TaskIntent field name (target, x, y, yaw, raw_text)")
            if fld is not None:
                out[pname] = fld
        return out

    def read_method(self, tname: str, node: Node, scope: Scope, path: str) -> MethodDef | None:
        spec = self.items(node, path, METHOD_KEYS)
        if not isinstance(node, MappingNode):
            return None
        if "name" not in spec:
            self.err(node, "a method needs 'name:'", path)
            return None
        mname = self.text(spec["name"][1], path, "a method name")
        if mname is None:
            return None
        path = f"tasks.{tname}/{mname}"
        pre = self.read_conditions(spec["pre"][1], scope, f"{path}.pre") if "pre" in spec else []
        subtasks: list[Subtask] = []
        if "do" not in spec:
            self.err(node, f"method {mname!r} needs 'do:' (a list of subtasks; [] for nothing)", path)
        else:
            subtasks = self.read_subtasks(spec["do"][1], scope, f"{path}.do")
        ack = None
        if "ack" in spec:
            ack = self.read_template(spec["ack"][1], scope, f"{path}.ack")
            self.ack_uses.append((spec["ack"][1], path))
        doc = (self.text(spec["doc"][1], path) or "") if "doc" in spec else ""
        return MethodDef(mname, pre, subtasks, ack, doc, self.loc(node))

    def read_subtasks(self, node: Node, scope: Scope, path: str) -> list[Subtask]:
        flow = self.flow_calls(node)
        if flow is not None:
            calls = [self.read_call(text, node, scope, path, at) for text, at in flow]
            return [c for c in calls if c is not None]
        items = node.value if isinstance(node, SequenceNode) else [node]
        out: list[Subtask] = []
        for item in items:
            sub: Subtask | None
            if isinstance(item, MappingNode):
                keys = {str(k.value) for k, _ in item.value if isinstance(k, ScalarNode)}
                if "for" in keys:
                    sub = self.read_for(item, scope, path)
                elif "run" in keys:
                    sub = self.read_run(item, scope, path)
                else:
                    self.err(item, "a subtask is 'task(args)', {for: VAR, in: LIST, do: [...]} or {run: TASK}", path)
                    sub = None
            else:
                text = self.text(item, path, "a subtask such as go_to(place)")
                sub = self.read_call(text, item, scope, path) if text is not None else None
            if sub is not None:
                out.append(sub)
        return out

    def flow_calls(self, node: Node) -> list[tuple[str, Location]] | None:
        """``do: [go_to(place), step(x, y, yaw)]`` read from the source text as one list, since
        YAML alone would split ``step(x, y, yaw)`` at its commas. None: not such a list."""
        if not (isinstance(node, SequenceNode) and node.flow_style and node.value
                and all(isinstance(i, ScalarNode) and i.style is None for i in node.value)):
            return None
        start, end = node.start_mark, node.end_mark
        if not isinstance(start.buffer, str):
            return None
        raw = start.buffer[start.index:end.index]
        try:
            tree = ast.parse(raw, mode="eval").body
        except SyntaxError:
            return None
        if not isinstance(tree, ast.List):
            return None
        out = []
        for elt in tree.elts:
            text = ast.get_source_segment(raw, elt) or ast.unparse(elt)
            column = (start.column if elt.lineno == 1 else 0) + elt.col_offset + 1
            out.append((text, Location(self.file, start.line + elt.lineno, column)))
        return out

    def read_call(self, text: str, node: Node, scope: Scope, path: str,
                  at: Location | None = None) -> CallTemplate | None:
        stripped = text.strip()

        def report(message: str, path: str, column: int = 1) -> None:
            if at is not None:
                self.log.add(Location(at.file, at.line, at.column + column - 1), message, path)
            else:
                self.err(node, message, path, column)

        try:
            tree = ast.parse(stripped, mode="eval").body
        except SyntaxError as e:
            report(f"syntax error in subtask {stripped!r}: {e.msg}", path, e.offset or 1)
            return None
        if isinstance(tree, ast.Name):
            name, arg_nodes, kw_nodes = tree.id, [], []
        elif isinstance(tree, ast.Call) and isinstance(tree.func, ast.Name):
            name, arg_nodes, kw_nodes = tree.func.id, list(tree.args), list(tree.keywords)
        else:
            report(f"a subtask is written task(args), e.g. go_to(place); got {stripped!r}", path)
            return None
        if name not in self.kinds:
            report(f"unknown task {name!r}{did_you_mean(name, self.kinds)}", path)
            return None
        params = self.params.get(name, [])
        names = [p.name for p in params]
        signature = f"{name}({', '.join(names)})"
        ok = True
        if len(arg_nodes) > len(params):
            report(f"{signature} takes {len(params)} argument(s), got {len(arg_nodes)}", path)
            ok = False
        given = set(names[:len(arg_nodes)])
        for kw in kw_nodes:
            if kw.arg is None or kw.arg not in names:
                report(f"{signature} has no parameter {kw.arg!r}{did_you_mean(str(kw.arg), names)}", path,
                       kw.col_offset + 1)
                ok = False
            elif kw.arg in given:
                report(f"{signature}: {kw.arg!r} given twice", path, kw.col_offset + 1)
                ok = False
            given.add(str(kw.arg))
        missing = [p.name for p in params if p.required and p.name not in given]
        if missing and ok:
            report(f"{signature}: missing {', '.join(map(repr, missing))}", path)
            ok = False

        def compiled(part: ast.expr) -> Expr | None:
            try:
                return compile_expr(ast.get_source_segment(stripped, part) or ast.unparse(part), scope)
            except _CompileError as e:
                report(e.message, path, part.col_offset + e.column)
                return None

        args = [compiled(a) for a in arg_nodes]
        kwargs = {str(k.arg): compiled(k.value) for k in kw_nodes}
        if not ok or any(a is None for a in args) or any(v is None for v in kwargs.values()):
            return None
        return CallTemplate(name, args, kwargs, stripped, at or self.loc(node))  # type: ignore[arg-type]

    def read_for(self, node: MappingNode, scope: Scope, path: str) -> ForTemplate | None:
        spec = self.items(node, path, ("for", "in", "do"))
        if not {"for", "in", "do"} <= set(spec):
            self.err(node, "a loop is {for: VAR, in: LIST, do: [subtasks]}", path)
            return None
        var = self.text(spec["for"][1], path, "a variable name")
        if var is None:
            return None
        if not _IDENT.match(var) or var in RESERVED or var in scope.bound or var in scope.state_vars:
            self.err(spec["for"][1], f"loop variable {var!r} must be a new plain name", path)
            return None
        iter_text = self.text(spec["in"][1], path, "an expression giving a list")
        iterable = self.compile(iter_text, scope, spec["in"][1], path) if iter_text is not None else None
        body = self.read_subtasks(spec["do"][1], scope.with_bound(var), f"{path}.for_{var}")
        if iterable is None:
            return None
        return ForTemplate(var, iterable, body, self.loc(node))

    def read_run(self, node: MappingNode, scope: Scope, path: str) -> RunTemplate | None:
        spec = self.items(node, path, ("run",))
        text = self.text(spec["run"][1], path, "an expression giving a task") if "run" in spec else None
        expr = self.compile(text, scope, spec["run"][1], path) if text is not None else None
        return None if expr is None else RunTemplate(expr, self.loc(node))

    def check_ack(self, ack_with: str, definitions: dict[str, Definition]) -> None:
        if not self.ack_uses:
            return
        prim = definitions.get(ack_with)
        if isinstance(prim, PrimitiveDef) and len(prim.params) == 1 and prim.params[0].type == "string":
            return
        node, path = self.ack_uses[0]
        self.err(node, f"'ack' needs a primitive {ack_with!r} with one string parameter (the text to say); "
                       f"define it under 'primitives:' or name another with 'ack_with:'", path)


def _shape(node: Node) -> str:
    if isinstance(node, MappingNode):
        return "a mapping"
    if isinstance(node, SequenceNode):
        return "a list"
    if isinstance(node, ScalarNode):
        tag = node.tag.rsplit(":", 1)[-1]
        return f"{tag} {node.value!r}" if tag != "null" else "nothing (null)"
    return "something else"
