"""Reading a domain file's ``primitives:``: each a task bound to one skill leaf, with the leaf's
arguments checked against the skill catalogue, a precondition, effects on the predicted state,
and when the leaf may be skipped.

This is where the domain meets the robot: a primitive that names a skill or a skill parameter
that does not exist is caught when the file loads, not when the plan runs.
"""

from __future__ import annotations

import ast

from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from ..core import expr as bbexpr
from ..core.catalogue import LEAVES, SKILLS  # primitives bind to skill leaves (daemon leaves, wait, stop)
from ..core.suggest import did_you_mean
from .domain import PrimitiveDef, Target, check_skill_args
from .expressions import Scope, SkipIf, Value
from .misnamed import misnamed
from .read_expressions import ExpressionReader
from .read_yaml import Items

PRIMITIVE_KEYS = ("doc", "params", "skill", "args", "pre", "effects", "remove", "optional", "skip_if")


class PrimitiveReader(ExpressionReader):
    """Reads one primitive task's body; its parameters were read by the first pass."""

    def read_primitive(self, tname: str, key: ScalarNode, node: Node) -> PrimitiveDef | None:
        opened = self.open_task("primitives", tname, node, PRIMITIVE_KEYS)
        if opened is None:
            return None
        path, spec, scope = opened
        skill = self.read_skill(tname, key, spec, path)
        if skill is None:
            return None
        args = self.read_skill_args(skill, key, spec, scope, path)
        pre = self.read_conditions(spec["pre"][1], scope, f"{path}.pre") if "pre" in spec else []
        effects = self.read_effects(spec["effects"][1], scope, path) if "effects" in spec else []
        remove = self.read_remove(spec["remove"][1], scope, path) if "remove" in spec else []
        optional = self.read_flag(spec["optional"][1], "optional", path) if "optional" in spec else False
        skip_if = self.read_skip_if(spec["skip_if"][1], scope, path) if "skip_if" in spec else None
        return PrimitiveDef(tname, self.params.get(tname, []), skill, args, pre, effects, remove, optional, skip_if,
                            self.doc(spec, path), self.loc(key))

    def read_skill(self, tname: str, key: ScalarNode, spec: Items, path: str) -> str | None:
        if "skill" not in spec:
            self.err(key, f"primitive {tname!r} needs 'skill:' (one of {', '.join(SKILLS)})", path)
            return None
        skill = self.text(spec["skill"][1], path, "a skill name")
        if skill is not None and skill not in SKILLS:
            self.err(spec["skill"][1], misnamed("unknown skill", skill, SKILLS, "skills"), path)
            return None
        return skill

    def read_skill_args(self, skill: str, key: ScalarNode, spec: Items, scope: Scope,
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
                self.err(akey, misnamed(f"skill {skill!r} has no parameter", aname, LEAVES[skill].param_names,
                                        "parameters"), path)
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

    # effects -----------------------------------------------------------------------------------------
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

    def read_target(self, text: str | None, node: Node, scope: Scope, path: str) -> Target | None:
        """``at`` (a whole state variable) or ``objects[obj]`` (one key of a mapping variable)."""
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
        """A blackboard expression (checked when the leaf runs, not when planning), parsed now so
        a typo is a load error."""
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
