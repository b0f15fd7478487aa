"""Running one tree on the mission session's daemons, and reading what its leaves recorded.

Every tree the mission executor runs goes through :class:`TreeRunner`: a compiled mission, and
the one-leaf trees that speak or look. Each gets its own :class:`~stuart_bt.run.executor.Executor`
on the session's clock; the job queue knows it while it runs, so "stop" reaches it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from py_trees.common import Status

from ..tree.spec import Location, NodeSpec, TreeSpec
from .failures import Failure

if TYPE_CHECKING:
    from ..run.executor import RunOutcome
    from ..run.session import Session
    from .queue import JobQueue, Mission


class TreeRunner:
    """Builds and ticks one tree at a time; ``aside`` runs before each tick of a mission tree
    (a reply waiting for a pause in the mission's speech)."""

    def __init__(self, session: Session, jobs: JobQueue, aside: Callable[[], None]) -> None:
        self.session = session
        self.jobs = jobs
        self.aside = aside

    def run(self, spec: TreeSpec, mission: Mission | None,
            max_duration: float | None) -> tuple[RunOutcome, set[str], str | None]:
        """Build and tick one tree on the session's daemons, for at most ``max_duration`` clock
        seconds; the paths that succeeded and the leaf whose failure failed the tree."""
        executor = self.session.executor_for(spec)
        root = executor.root
        succeeded: set[str] = set()

        def track(event: Any) -> None:
            if event.kind == "status" and event.data.get("new") == "SUCCESS" and event.path:
                succeeded.add(event.path)

        unsubscribe = self.session.events.subscribe(track)
        if mission is not None:
            executor.pre_tick.append(self.aside)
        self.jobs.attach(executor, mission)
        try:
            outcome = executor.run(max_duration)
        finally:
            unsubscribe()
            self.jobs.detach()
        failed = failed_leaf(root) if outcome.status == "FAILURE" else None
        return outcome, succeeded, failed


def leaf_outcome(session: Session, path: str | None) -> dict[str, Any]:
    """What the leaf at ``path`` recorded last: status, reason, the daemon's error code, result."""
    outcomes = session.blackboard.get("outcomes", None) or {}
    return (outcomes.get(path) if path else None) or {}


def failure_reason(session: Session, path: str | None, outcome: RunOutcome) -> str:
    return leaf_outcome(session, path).get("reason") or outcome.reason or "something went wrong"


def failure_facts(session: Session, spec: TreeSpec, path: str | None, outcome: RunOutcome) -> Failure:
    """The failed leaf's facts, for saying what went wrong in words: its reason and code, its
    kind and parameters (which object, which place) and the data its daemon's error carried."""
    entry = leaf_outcome(session, path)
    node = spec.find(path) if path else None
    return Failure(failure_reason(session, path, outcome), entry.get("code"), node.kind if node else None,
                   dict(node.params) if node else {}, dict(entry.get("detail") or {}))


def failed_leaf(root: Any) -> str | None:
    """Follow the failure down: the last failed child of every failed node ends at the leaf."""
    node = root
    while node.children:
        failed = [c for c in node.children if c.status == Status.FAILURE]
        if not failed:
            break
        node = failed[-1]
    return getattr(node, "spec_path", None) if not node.children else None


# -- the trees the executor builds itself -------------------------------------------------------------
def where() -> Location:
    return Location("<mission>", 1, 1)


def say_tree(text: str) -> TreeSpec:
    return TreeSpec(NodeSpec("speak", "say", "say", where(), {"text": text, "timeout": 120.0}), "<say>")


def look_tree() -> TreeSpec:
    return TreeSpec(NodeSpec("observe", "look", "look", where(), {}), "<look>")


def all_families_tree(markers_file: str) -> TreeSpec:
    """A stand-in tree naming one leaf of every skill family, so the Session starts every daemon."""
    here = where()
    leaves = [NodeSpec("speak", "speak", "daemons/speak", here, {"text": ""}),
              NodeSpec("navigate", "navigate", "daemons/navigate", here, {"dx": 0}),
              NodeSpec("gesture", "gesture", "daemons/gesture", here, {"play": "clap"}),
              NodeSpec("pick", "pick", "daemons/pick", here, {"object": "cup"}),
              NodeSpec("find", "find", "daemons/find", here, {"object": "cup"})]
    return TreeSpec(NodeSpec("sequence", "daemons", "daemons", here, {}, leaves), "<missions>",
                    markers_file=markers_file)
