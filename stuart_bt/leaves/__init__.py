"""Leaves: skill leaves that drive daemons, and built-ins that run inside the executor.

:func:`make_leaf` is the factory the tree builder calls for every leaf node.
"""

from __future__ import annotations

from ..tree.spec import NodeSpec
from .base import Leaf, LeafFailure, RunContext, SkillLeaf, failure_code
from .builtin import Condition, Log, Set, Stop, Wait
from .expression import Gesture, Speak
from .manipulation import Pick, Release
from .motion import Approach, Navigate, Turn, View
from .vision import Find, Observe

LEAF_CLASSES: dict[str, type[Leaf]] = {
    cls.kind: cls
    for cls in (Navigate, Approach, View, Turn, Pick, Release, Find, Observe, Speak, Gesture, Wait, Stop, Condition,
                Set, Log)
}


def make_leaf(spec: NodeSpec, ctx: RunContext) -> Leaf:
    """Build the leaf behaviour for a leaf node of a loaded tree."""
    return LEAF_CLASSES[spec.kind](spec, ctx)


__all__ = ["Leaf", "LeafFailure", "RunContext", "SkillLeaf", "LEAF_CLASSES", "failure_code", "make_leaf"]
