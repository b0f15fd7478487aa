"""Reading the expressions a domain file writes inside its YAML: preconditions, values, hook
calls and text templates, compiled against the names in scope, with errors at the column of
the expression where they are.

Primitives and methods both use these (a precondition reads the same in either), so they sit
below both readers: :mod:`.read_primitives` and :mod:`.read_methods`.
"""

from __future__ import annotations

import ast
from collections.abc import Sequence

from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from .domain import MISSING, ParamDef, StateVarDef
from .expressions import Clause, Expr, Scope, Value, _CompileError, compile_expr, parse_template
from .hooks import Hook, HookRegistry
from .misnamed import misnamed
from .read_yaml import Items, YamlReader
from .values import format_value


class ExpressionReader(YamlReader):
    """Compiles expressions against a task's parameters and the declared state variables.

    ``state_vars`` and ``params`` are filled by the first pass over the file (:mod:`.load`), so
    an expression may name a task's parameter or a state variable declared anywhere in it.
    """

    def __init__(self, file: str, hooks: HookRegistry) -> None:
        super().__init__(file)
        self.hooks = hooks
        self.state_vars: dict[str, StateVarDef] = {}
        self.params: dict[str, list[ParamDef]] = {}

    def scope(self, tname: str) -> Scope:
        return Scope(f"{tname!r}", tuple(p.name for p in self.params.get(tname, [])), frozenset(self.state_vars))

    def open_task(self, section: str, tname: str, node: Node, keys: Sequence[str]) -> tuple[str, Items, Scope] | None:
        """A task body's path, its entries (unknown keys reported) and the scope its expressions
        see; None when the body is not a mapping (reported too)."""
        path = f"{section}.{tname}"
        spec = self.items(node, path, keys)
        if not isinstance(node, MappingNode):
            return None
        return path, spec, self.scope(tname)

    def compile(self, text: str, scope: Scope, node: Node, path: str, offset: int = 0) -> Expr | None:
        try:
            return compile_expr(text, scope)
        except _CompileError as e:
            self.err(node, e.message, path, offset + e.column)
            return None

    # conditions --------------------------------------------------------------------------------------
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
            if expr is not None:
                membership = _membership(stripped, part, scope)
                clauses.append(Clause(segment, expr, membership=membership, location=self.loc(node)))
        return clauses

    def read_hook_clause(self, node: MappingNode, scope: Scope, path: str) -> Clause | None:
        hook, args = self.read_hook_call(node, scope, path, "condition")
        if hook is None:
            return None
        shown = ", ".join(f"{k}={v.text}" for k, v in args.items())
        return Clause(f"hook {hook.name}({shown})", hook=hook, hook_args=args, location=self.loc(node))

    # hooks -------------------------------------------------------------------------------------------
    def read_hook_call(self, node: MappingNode, scope: Scope, path: str,
                       kind: str) -> tuple[Hook | None, dict[str, Value]]:
        """``{hook: NAME, args: {...}}``: the registered hook of ``kind`` and its arguments; with
        no ``args:``, the hook's parameters are bound by name to the task's parameters."""
        spec = self.items(node, path, ("hook", "args"))
        if "hook" not in spec:
            self.err(node, "expected {hook: NAME, args: {...}}", path)
            return None, {}
        hook = self.find_hook(spec["hook"][1], path, kind)
        if hook is None:
            return None, {}
        if "args" in spec:
            args = self.read_hook_args(hook, spec["args"][1], scope, path)
        else:
            args = {p: Value("expr", p, expr=compile_expr(p, scope)) for p in hook.params if p in scope.bound}
        missing = [p for p in hook.required if p not in args]
        if missing:
            self.err(node, f"hook {hook.name!r} needs {', '.join(map(repr, missing))}"
                           f"{'' if 'args' in spec else ' (no task parameter of that name; give args:)'}", path)
            return None, {}
        return hook, args

    def find_hook(self, where: Node, path: str, kind: str) -> Hook | None:
        """The registered hook named at ``where``, when it is one of ``kind``."""
        hname = self.text(where, path, "a hook name")
        if hname is None:
            return None
        hook = self.hooks.get(hname)
        if hook is None:
            self.err(where, misnamed(f"unknown {kind} hook", hname, self.hooks.names(kind), "registered"), path)
            return None
        if hook.kind != kind:
            self.err(where, f"hook {hname!r} is a {hook.kind} hook; a {kind} hook is needed here", path)
            return None
        return hook

    def read_hook_args(self, hook: Hook, node: Node, scope: Scope, path: str) -> dict[str, Value]:
        args: dict[str, Value] = {}
        for aname, (akey, avalue) in self.items(node, f"{path}.args").items():
            if aname not in hook.params and not hook.accepts_any:
                self.err(akey, misnamed(f"hook {hook.name!r} has no parameter", aname, hook.params, "parameters"),
                         path)
                continue
            value = self.read_value(avalue, scope, f"{path}.args.{aname}")
            if value is not None:
                args[aname] = value
        return args

    # values ------------------------------------------------------------------------------------------
    def read_value(self, node: Node, scope: Scope, path: str) -> Value | None:
        """An expression (text), a literal (any other scalar or list), ``{format: TEMPLATE}`` or a
        function hook call."""
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
                template = self.template(text, scope, fnode, path) if text is not None else None
                return None if template is None or text is None else Value("format", text, template=template)
        if isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:str":
            expr = self.compile(str(node.value), scope, node, path)
            return None if expr is None else Value("expr", expr.text, expr=expr)
        literal = self.python(node, path)
        if literal is MISSING:
            return None
        return Value("literal", format_value(literal), literal=literal)

    def read_template(self, node: Node, scope: Scope, path: str) -> list[str | Expr] | None:
        text = self.text(node, path, "a text template")
        return None if text is None else self.template(text, scope, node, path)

    def template(self, text: str, scope: Scope, node: Node, path: str) -> list[str | Expr] | None:
        try:
            return parse_template(text, scope)
        except _CompileError as e:
            self.err(node, e.message, path, e.column)
            return None


def _membership(text: str, part: ast.expr, scope: Scope) -> tuple[Expr, Expr] | None:
    """For ``x in y``, both sides compiled, so a failed check can say which element was missing."""
    if not (isinstance(part, ast.Compare) and len(part.ops) == 1 and isinstance(part.ops[0], ast.In)):
        return None
    left = ast.get_source_segment(text, part.left) or ast.unparse(part.left)
    right = ast.get_source_segment(text, part.comparators[0]) or ast.unparse(part.comparators[0])
    try:
        return compile_expr(left, scope), compile_expr(right, scope)
    except _CompileError:
        return None
