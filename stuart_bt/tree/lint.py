"""Warnings about a tree that loads: things the language allows but that are probably mistakes.

``stuart-bt validate`` prints them after a clean load (and still exits 0). Today there is one:
walking while a gesture holds the arms. Some gestures end in a pose the arm service keeps
("high five", "hug", "hands up": ``holds`` in :mod:`stuart_bt.core.gestures`) until
``gesture: release arm``; walking meanwhile swings a raised arm through a room and shifts the
robot's balance. So for every walking leaf (a leaf of the loco daemon: navigate, approach,
turn) the tree is read in running order, following sequences, selectors (a later branch runs
after an earlier one failed part way), parallels and loops, and a walk that some run of the
tree can reach with a holding gesture played and not released since is reported, with the
node paths of both.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..core import gestures
from ..core.catalogue import LEAVES
from .spec import Location, NodeSpec, TreeSpec

WALKS = frozenset(name for name, leaf in LEAVES.items() if leaf.family == "loco")

# What the arm may be holding at some point of a run: the path of the holding gesture node that
# left it so, or None for free arms.
Arms = frozenset[str | None]
FREE: Arms = frozenset({None})


@dataclass(frozen=True)
class TreeWarning:
    """A probable mistake at a node; shown as ``file:line:col: path: warning: message``."""

    location: Location
    path: str
    message: str

    def __str__(self) -> str:
        return f"{self.location}: {self.path}: warning: {self.message}"


@dataclass(frozen=True)
class _Exit:
    """The arms when a node succeeds, and when it fails (a leaf that fails, or is cut short,
    is taken to have changed nothing)."""

    success: Arms
    failure: Arms


def tree_warnings(spec: TreeSpec) -> list[TreeWarning]:
    """Every warning for ``spec``, in reading order."""
    reader = _ArmsReader(spec)
    reader.visit(spec.root, FREE)
    return sorted(reader.warnings, key=lambda w: (w.location.file, w.location.line, w.location.column))


@dataclass
class _ArmsReader:
    spec: TreeSpec
    warnings: list[TreeWarning] = field(default_factory=list)
    _seen: set[tuple[str, str]] = field(default_factory=set)

    def visit(self, node: NodeSpec, arms: Arms) -> _Exit:
        if node.kind == "sequence":
            return self._sequence(node, arms)
        if node.kind == "selector":
            return self._selector(node, arms)
        if node.kind == "parallel":
            return self._parallel(node, arms)
        if node.kind in ("retry", "repeat"):
            return self._loop(node, arms)
        if node.children:
            return self._decorator(node, arms)
        return self._leaf(node, arms)

    def _sequence(self, node: NodeSpec, arms: Arms) -> _Exit:
        failed: Arms = frozenset()
        for child in node.children:
            exit_ = self.visit(child, arms)
            failed |= exit_.failure
            arms = exit_.success
        return _Exit(arms, failed)

    def _selector(self, node: NodeSpec, arms: Arms) -> _Exit:
        done: Arms = frozenset()
        for child in node.children:
            exit_ = self.visit(child, arms)
            done |= exit_.success
            arms = exit_.failure  # the next branch runs after this one failed, wherever that was
        return _Exit(done, arms)

    def _parallel(self, node: NodeSpec, arms: Arms) -> _Exit:
        """Children start together, so none follows another; when the parallel ends, any of
        them may have been the last to move the arms (or have been stopped part way)."""
        exits = [self.visit(child, arms) for child in node.children]
        succeeded = frozenset().union(*(e.success for e in exits))
        failed = frozenset().union(*(e.failure for e in exits))
        return _Exit(succeeded if node.params.get("policy", "all") == "all" else succeeded | failed,
                     succeeded | failed)

    def _loop(self, node: NodeSpec, arms: Arms) -> _Exit:
        """A retry runs its child again after a failure, a repeat after a success: until the
        arms a new round can start with stop growing."""
        start, done, failed = arms, frozenset[str | None](), frozenset[str | None]()
        while True:
            exit_ = self.visit(node.children[0], start)
            done, failed = done | exit_.success, failed | exit_.failure
            again = start | (exit_.failure if node.kind == "retry" else exit_.success)
            if again == start:
                return _Exit(done, failed)
            start = again

    def _decorator(self, node: NodeSpec, arms: Arms) -> _Exit:
        exit_ = self.visit(node.children[0], arms)
        either = exit_.success | exit_.failure
        if node.kind == "inverter":
            return _Exit(exit_.failure, exit_.success)
        if node.kind == "force_success":
            return _Exit(either, frozenset())
        if node.kind == "force_failure":
            return _Exit(frozenset(), either)
        return exit_

    def _leaf(self, node: NodeSpec, arms: Arms) -> _Exit:
        if node.kind in WALKS:
            for holder in sorted(h for h in arms if h is not None):
                self._warn(node, holder)
        if node.kind != "gesture":
            return _Exit(arms, arms)
        return _Exit(frozenset({node.path}) if _ends_holding(node) else FREE, arms)

    def _warn(self, walk: NodeSpec, holder: str) -> None:
        if (holder, walk.path) in self._seen:
            return
        self._seen.add((holder, walk.path))
        gesture = self.spec.find(holder)
        assert gesture is not None
        name = _last_gesture(gesture)
        self.warnings.append(TreeWarning(
            walk.location, walk.path,
            f"{walk.kind} while the arms may still hold the '{name}' pose of {holder} (line {gesture.location.line}); "
            f"put 'gesture: release arm' between them"))


def _last_gesture(node: NodeSpec) -> str | None:
    """The name of the gesture a gesture node ends with; None when only known at run time."""
    played = node.params.get("play")
    if played is None and isinstance(node.params.get("sequence"), list) and node.params["sequence"]:
        played = node.params["sequence"][-1]
    gesture = gestures.lookup(played) if isinstance(played, str) else None
    return gesture.name if gesture is not None else None


def _ends_holding(node: NodeSpec) -> bool:
    """Whether the arms hold a pose after this gesture node; a recorded file, or a name known
    only at run time, is taken not to (a warning should be sure)."""
    name = _last_gesture(node)
    return name is not None and gestures.LIBRARY[name].holds
