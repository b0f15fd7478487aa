"""The tree snapshot: one JSON document that says what the tree is and where it stands now.

The web view draws it and the ROS bridge publishes it on ``/bt/status``, so both agree on one
format (documented in docs/web.md). It is built only from the event stream, never by looking into
the executor: a ``tree`` event (published whenever an executor is built for a tree, so also for each
mission plan) gives the structure; ``status`` events move node statuses; ``leaf`` events give each
leaf's last outcome and reason; ``blackboard`` events fill the blackboard table. The same code
therefore rebuilds the snapshot from a saved JSON-lines log.

Format ``stuart_bt.snapshot/1``::

    {"format": "stuart_bt.snapshot/1", "seq": 12, "t": 3.25,
     "tree": {"file": "trees/lab_tour.yaml", "description": "...", "root": "lab_tour"},
     "nodes": [{"path": "lab_tour", "parent": null, "depth": 0, "name": "lab_tour",
                "kind": "sequence", "category": "composite", "params": {}, "children": ["lab_tour/..."],
                "status": "RUNNING", "last": null}, ...],
     "running": ["lab_tour", "lab_tour/station_1", ...],
     "blackboard": {"pose": {...}, ...},
     "mission": {"id": 3, "phase": "started", ...} | null}

``nodes`` is depth first, parents before children. ``status`` is one of INVALID, RUNNING, SUCCESS,
FAILURE. ``last`` is a leaf's last finish: ``{"outcome", "reason", "t"}``. ``running`` is the
running path, root first. ``seq`` grows by one with every change to nodes or tree.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterable
from typing import Any

from ..core.events import Event, EventStream, _json_default
from ..core.jsonfile import to_json
from ..tree.render import category
from ..tree.spec import NodeSpec, TreeSpec

FORMAT = "stuart_bt.snapshot/1"


def node_structure(node: NodeSpec) -> dict[str, Any]:
    """A node and its descendants as plain data (the payload of a ``tree`` event)."""
    return {"path": node.path, "name": node.name, "kind": node.kind, "category": category(node),
            "params": dict(node.params), "children": [node_structure(c) for c in node.children]}


def tree_event_data(spec: TreeSpec) -> dict[str, Any]:
    """What the ``tree`` event carries: the file, the description and the nested structure."""
    return {"file": spec.file, "description": spec.description, "root": node_structure(spec.root)}


class TreeSnapshot:
    """The latest snapshot, kept up to date from events.

    ``on_change`` (optional) is called with no arguments after each event that changed the tree or a
    node (not for blackboard writes, which can be many per tick); it runs on the publishing thread,
    so it must be quick (set a flag, put on a queue).
    """

    def __init__(self, events: EventStream | None = None, on_change: Callable[[], None] | None = None) -> None:
        self._lock = threading.Lock()
        self._nodes: dict[str, dict[str, Any]] = {}  # path -> node dict, in depth-first order
        self._tree: dict[str, Any] | None = None
        self._blackboard: dict[str, Any] = {}
        self._mission: dict[str, Any] | None = None
        self.seq = 0
        self.t = 0.0
        self.on_change = on_change
        self._unsubscribe = events.subscribe(self.apply) if events is not None else None

    @classmethod
    def from_events(cls, events: Iterable[Event]) -> TreeSnapshot:
        """The snapshot after replaying ``events`` (a saved log)."""
        snap = cls()
        for event in events:
            snap.apply(event)
        return snap

    def close(self) -> None:
        if self._unsubscribe is not None:
            self._unsubscribe()
            self._unsubscribe = None

    # -- events -----------------------------------------------------------------------------------
    def apply(self, event: Event) -> bool:
        """Fold one event in; True when the tree or a node changed."""
        changed = False
        with self._lock:
            self.t = event.t
            kind, d = event.kind, event.data
            if kind == "tree" and isinstance(d.get("root"), dict):
                self._set_tree(d)
                changed = True
            elif kind == "status" and event.path in self._nodes:
                self._nodes[event.path]["status"] = d.get("new", "INVALID")
                changed = True
            elif kind == "leaf" and event.path in self._nodes:
                self._nodes[event.path]["last"] = {"outcome": d.get("outcome"), "reason": d.get("reason"),
                                                   "t": round(event.t, 6)}
                changed = True
            elif kind == "blackboard" and "key" in d:
                self._blackboard[str(d["key"])] = d.get("value")
            elif kind == "mission":
                self._mission = dict(d)
                changed = True
            if changed:
                self.seq += 1
        if changed and self.on_change is not None:
            self.on_change()
        return changed

    def _set_tree(self, d: dict[str, Any]) -> None:
        root = d["root"]
        self._tree = {"file": d.get("file"), "description": d.get("description"), "root": root.get("path")}
        self._nodes = {}

        def add(node: dict[str, Any], parent: str | None, depth: int) -> None:
            self._nodes[node["path"]] = {
                "path": node["path"], "parent": parent, "depth": depth, "name": node.get("name"),
                "kind": node.get("kind"), "category": node.get("category"), "params": node.get("params", {}),
                "children": [c["path"] for c in node.get("children", [])], "status": "INVALID", "last": None,
            }
            for child in node.get("children", []):
                add(child, node["path"], depth + 1)

        add(root, None, 0)

    # -- reading ----------------------------------------------------------------------------------
    def status(self, path: str) -> str | None:
        with self._lock:
            node = self._nodes.get(path)
            return node["status"] if node else None

    def running_path(self) -> list[str]:
        """Root first, following the RUNNING child at each level."""
        with self._lock:
            return self._running()

    def _running(self) -> list[str]:
        if self._tree is None:
            return []
        out: list[str] = []
        path: str | None = self._tree["root"]
        while path is not None and self._nodes.get(path, {}).get("status") == "RUNNING":
            out.append(path)
            path = next((c for c in self._nodes[path]["children"] if self._nodes[c]["status"] == "RUNNING"), None)
        return out

    def to_dict(self) -> dict[str, Any]:
        with self._lock:
            return {
                "format": FORMAT, "seq": self.seq, "t": round(self.t, 6),
                "tree": dict(self._tree) if self._tree else None,
                "nodes": [dict(n, last=dict(n["last"]) if n["last"] else None) for n in self._nodes.values()],
                "running": self._running(), "blackboard": dict(self._blackboard),
                "mission": dict(self._mission) if self._mission else None,
            }

    def to_json(self) -> str:
        """The snapshot as one JSON line (values the blackboard holds as objects use their to_dict)."""
        return to_json(self.to_dict(), default=_json_default, separators=(",", ":"))
