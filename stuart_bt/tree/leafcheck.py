"""Which parameters a leaf needs: required ones and its ``one_of`` alternative groups.

Only names matter here (values are checked by :mod:`stuart_bt.tree.values`), which keeps the
rules for "navigate takes a marker, or x/y(/yaw), or dx/dy/dyaw" in one small place.
"""

from __future__ import annotations

from collections.abc import Collection

from ..core.catalogue import LeafSpec


def alternatives(leaf: LeafSpec) -> str:
    """``marker | x, y, yaw | dx, dy, dyaw``: the groups as a user reads them."""
    return " | ".join(", ".join(group) for group in leaf.one_of)


def missing_or_conflicting(leaf: LeafSpec, given: Collection[str]) -> list[str]:
    """Messages for absent required parameters and for zero or several ``one_of`` groups used."""
    grouped = {p for group in leaf.one_of for p in group}
    problems = [
        f"missing parameter {p.name!r} for {leaf.name}"
        for p in leaf.params
        if p.required and p.name not in grouped and p.name not in given
    ]
    if not leaf.one_of:
        return problems
    used = [group for group in leaf.one_of if any(p in given for p in group)]
    if not used:
        return [*problems, f"{leaf.name} needs one of: {alternatives(leaf)}"]
    if len(used) > 1:
        picked = ", ".join(repr(next(p for p in group if p in given)) for group in used)
        return [*problems, f"{leaf.name} takes only one of: {alternatives(leaf)} (got {picked})"]
    group = used[0]
    present = next(p for p in group if p in given)
    for name in group:
        param = leaf.param(name)
        if param is not None and param.required and name not in given:
            problems.append(f"missing parameter {name!r} for {leaf.name} (needed with {present!r})")
    return problems
