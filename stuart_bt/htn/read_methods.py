"""Reading a domain file's ``tasks:``: compound tasks, their ordered methods, and each method's
subtasks (``task(args)`` calls, ``{for: ...}`` loops and ``{run: ...}`` task values).

A subtask call is checked against the called task's parameters here, when the file loads, so
a method that calls a task that does not exist, or calls it with the wrong arguments, is an
error at its file:line:column rather than a planning failure later.
"""

from __future__ import annotations

import ast
from collections.abc import Callable

from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from ..tree.spec import Location
from .domain import CallTemplate, ForTemplate, MethodDef, ParamDef, RunTemplate, Subtask, TaskDef
from .expressions import Expr, Scope, _CompileError, compile_expr
from .hooks import HookRegistry
from .misnamed import misnamed
from .read_expressions import ExpressionReader
from .read_yaml import IDENT
from .values import RESERVED

TASK_KEYS = ("doc", "params", "intent", "ack", "methods")

METHOD_KEYS = ("name", "doc", "pre", "do", "ack")

Report = Callable[[str, str, int], None]  # (message, path, column within the subtask's text)


class MethodReader(ExpressionReader):
    """Reads one compound task's body. ``kinds`` (every task's name, from the first pass) lets a
    method call a task defined further down the file; ``ack_uses`` records where an ``ack:`` is
    written, for the check that the domain can say it."""

    def __init__(self, file: str, hooks: HookRegistry) -> None:
        super().__init__(file, hooks)
        self.kinds: dict[str, str] = {}  # task name -> "primitive" | "compound"
        self.ack_uses: list[tuple[Node, str]] = []

    # compound tasks ----------------------------------------------------------------------------------
    def read_task(self, tname: str, key: ScalarNode, node: Node) -> TaskDef | None:
        opened = self.open_task("tasks", tname, node, TASK_KEYS)
        if opened is None:
            return None
        path, spec, scope = opened
        ack = self.read_ack(spec["ack"][1], scope, path) if "ack" in spec else None
        intent = self.read_intent(spec["intent"][1], tname, f"{path}.intent") if "intent" in spec else None
        methods: list[MethodDef] = []
        if "methods" not in spec:
            self.err(key, f"task {tname!r} needs 'methods:' (a list of {{name, pre, do}})", path)
        else:
            methods = self.read_methods(tname, spec["methods"][1], scope, path)
        return TaskDef(tname, self.params.get(tname, []), methods, ack, intent, self.doc(spec, path), self.loc(key))

    def read_methods(self, tname: str, node: Node, scope: Scope, path: str) -> list[MethodDef]:
        if not isinstance(node, SequenceNode) or not node.value:
            self.err(node, "'methods' must be a non-empty list of {name, pre, do}", path)
            return []
        methods: list[MethodDef] = []
        seen: set[str] = set()
        for i, item in enumerate(node.value):
            method = self.read_method(tname, item, scope, f"{path}.methods[{i}]")
            if method is None:
                continue
            if method.name in seen:
                self.err(item, f"method name {method.name!r} is used twice in task {tname!r}", path)
                continue
            seen.add(method.name)
            methods.append(method)
        return methods

    def read_ack(self, node: Node, scope: Scope, path: str) -> list[str | Expr] | None:
        self.ack_uses.append((node, path))
        return self.read_template(node, scope, f"{path}.ack")

    def read_intent(self, node: Node, tname: str, path: str) -> dict[str, str]:
        """Which TaskIntent field fills which parameter, when the task is one the language can ask for."""
        if isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:null":
            return {}
        names = [p.name for p in self.params.get(tname, [])]
        out: dict[str, str] = {}
        for pname, (pkey, fnode) in self.items(node, path).items():
            if pname not in names:
                self.err(pkey, misnamed(f"task {tname!r} has no parameter", pname, names), path)
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
        ack = self.read_ack(spec["ack"][1], scope, path) if "ack" in spec else None
        return MethodDef(mname, pre, subtasks, ack, self.doc(spec, path), self.loc(node))

    # subtasks ----------------------------------------------------------------------------------------
    def read_subtasks(self, node: Node, scope: Scope, path: str) -> list[Subtask]:
        flow = self.flow_calls(node)
        if flow is not None:
            calls = [self.read_call(text, node, scope, path, at) for text, at in flow]
            return [c for c in calls if c is not None]
        items = node.value if isinstance(node, SequenceNode) else [node]
        out: list[Subtask] = []
        for item in items:
            sub = self.read_subtask(item, scope, path)
            if sub is not None:
                out.append(sub)
        return out

    def read_subtask(self, item: Node, scope: Scope, path: str) -> Subtask | None:
        if not isinstance(item, MappingNode):
            text = self.text(item, path, "a subtask such as go_to(place)")
            return self.read_call(text, item, scope, path) if text is not None else None
        keys = {str(k.value) for k, _ in item.value if isinstance(k, ScalarNode)}
        if "for" in keys:
            return self.read_for(item, scope, path)
        if "run" in keys:
            return self.read_run(item, scope, path)
        self.err(item, "a subtask is 'task(args)', {for: VAR, in: LIST, do: [...]} or {run: TASK}", path)
        return None

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
        """``task(arg, key=arg)``: the task must exist and the arguments fit its parameters.
        ``at``: where the call is in the file, for a call read out of a flow list."""
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
            report(misnamed("unknown task", name, self.kinds), path)
            return None
        ok = _arguments_fit(name, self.params.get(name, []), arg_nodes, kw_nodes, report, path)

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
        if not IDENT.match(var) or var in RESERVED or var in scope.bound or var in scope.state_vars:
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


def _arguments_fit(name: str, params: list[ParamDef], arg_nodes: list[ast.expr], kw_nodes: list[ast.keyword],
                   report: Report, path: str) -> bool:
    """Whether a call's positional and keyword arguments fit the task's parameters; every misfit
    is reported (too many, unknown or repeated names), and a missing one when the rest fit."""
    names = [p.name for p in params]
    signature = f"{name}({', '.join(names)})"
    ok = True
    if len(arg_nodes) > len(params):
        report(f"{signature} takes {len(params)} argument(s), got {len(arg_nodes)}", path, 1)
        ok = False
    given = set(names[:len(arg_nodes)])
    for kw in kw_nodes:
        if kw.arg is None or kw.arg not in names:
            report(misnamed(f"{signature} has no parameter", kw.arg, names), path, kw.col_offset + 1)
            ok = False
        elif kw.arg in given:
            report(f"{signature}: {kw.arg!r} given twice", path, kw.col_offset + 1)
            ok = False
        given.add(str(kw.arg))
    missing = [p.name for p in params if p.required and p.name not in given]
    if missing and ok:
        report(f"{signature}: missing {', '.join(map(repr, missing))}", path, 1)
        ok = False
    return ok
