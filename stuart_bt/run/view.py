"""Terminal views of a running tree, fed only by the event stream.

- :class:`LiveView` (a terminal): the tree redrawn with each node's status, a progress bar over the
  top-level steps and the latest events (speech, gestures, failures, warnings).
- :class:`LogView` (pipes, CI logs): one plain line per interesting event.
- :class:`NoView`: silence, except for the final summary.

Views keep their own copy of node statuses from ``status`` events; they never look inside the
executor, so the same code can replay a saved event log.
"""

from __future__ import annotations

import sys
import threading
from collections import deque
from typing import Any, TextIO

from rich.console import Console, Group
from rich.live import Live
from rich.progress_bar import ProgressBar
from rich.table import Table
from rich.text import Text
from rich.tree import Tree

from ..core.events import Event, EventStream
from ..tree.render import label
from ..tree.spec import NodeSpec, TreeSpec

STATUS_STYLE = {"SUCCESS": "green", "FAILURE": "bold red", "RUNNING": "bold yellow", "INVALID": "dim"}
STATUS_MARK = {"SUCCESS": "✔", "FAILURE": "✘", "RUNNING": "▶", "INVALID": "·"}
def _interesting(event: Event) -> str | None:
    d = event.data
    if event.kind == "leaf" and d.get("skill") != "condition":  # conditions answer every tick
        line = f"{d.get('outcome')}: {event.path}"
        return line + (f" ({d['reason']})" if d.get("reason") else "")
    if event.kind == "leaf":
        return None
    if event.kind == "command" and d.get("cmd") == "say":
        return f"says: {d.get('args', {}).get('text')}"
    if event.kind == "command" and d.get("cmd") == "play":
        args = d.get("args", {})
        return f"gesture: {args.get('name') or args.get('sequence') or 'recorded'}"
    if event.kind in ("warning", "daemon_state", "halt", "log"):
        return f"{event.kind}: {d.get('message') or d.get('reason') or d.get('state') or ''}".rstrip()
    return None


class _Base:
    def __init__(self, spec: TreeSpec, events: EventStream, out: TextIO | None = None) -> None:
        self.spec = spec
        self.out = out or sys.stdout
        self.statuses: dict[str, str] = {}
        self._lock = threading.Lock()
        self._unsubscribe = events.subscribe(self.on_event)

    def on_event(self, event: Event) -> None:
        if event.kind == "status" and event.path is not None:
            with self._lock:
                self.statuses[event.path] = event.data["new"]

    def start(self) -> None:
        pass

    def stop(self) -> None:
        self._unsubscribe()

    def summary(self, report: dict[str, Any]) -> None:
        line = f"{report['status']} in {report['duration']:.1f} s"
        if report.get("visited"):
            line += f"; visited {' -> '.join(report['visited'])}"
        if report.get("final_pose"):
            p = report["final_pose"]
            line += f"; final pose x={p['x']:.2f} y={p['y']:.2f} yaw={p['yaw']:.2f}"
        print(line, file=self.out)
        for failure in report.get("failures", [])[:10]:
            print(f"  failed: {failure['path']}: {failure['reason']}", file=self.out)


class NoView(_Base):
    pass


class LogView(_Base):
    def on_event(self, event: Event) -> None:
        super().on_event(event)
        line = _interesting(event)
        if line:
            print(f"[{event.t:8.2f}] {line}", file=self.out, flush=True)


class LiveView(_Base):
    def __init__(self, spec: TreeSpec, events: EventStream, out: TextIO | None = None) -> None:
        super().__init__(spec, events, out)
        self.recent: deque[str] = deque(maxlen=6)
        self.console = Console(file=self.out)
        self._live = Live(get_renderable=self.renderable, console=self.console, refresh_per_second=20,
                          transient=False, redirect_stdout=False, redirect_stderr=False)

    def on_event(self, event: Event) -> None:
        super().on_event(event)
        line = _interesting(event)
        if line:
            with self._lock:
                self.recent.append(f"[{event.t:7.1f}] {line}")

    def start(self) -> None:
        self._live.start()

    def stop(self) -> None:
        self._live.stop()
        super().stop()

    def renderable(self) -> Group:
        with self._lock:
            statuses = dict(self.statuses)
            recent = list(self.recent)
        tree = self._tree(self.spec.root, statuses)
        steps = self.spec.root.children or [self.spec.root]
        done = sum(1 for c in steps if statuses.get(c.path) in ("SUCCESS", "FAILURE"))
        bar = Table.grid(padding=(0, 1))
        bar.add_row(ProgressBar(total=len(steps), completed=done, width=40), Text(f"{done}/{len(steps)} steps"))
        return Group(tree, bar, Text("\n".join(recent), style="dim"))

    def _tree(self, node: NodeSpec, statuses: dict[str, str], parent: Tree | None = None) -> Tree:
        status = statuses.get(node.path, "INVALID")
        text = Text(f"{STATUS_MARK[status]} {label(node)}", style=STATUS_STYLE[status])
        branch = Tree(text) if parent is None else parent.add(text)
        collapse = status in ("SUCCESS", "INVALID") and node is not self.spec.root and node.children
        if collapse:
            hidden = sum(1 for _ in node.walk()) - 1
            branch.add(Text(f"… {hidden} node{'' if hidden == 1 else 's'}", style="dim"))
        else:
            for child in node.children:
                self._tree(child, statuses, branch)
        return branch


def make_view(mode: str, spec: TreeSpec, events: EventStream, out: TextIO | None = None) -> _Base:
    """``auto`` picks the live view on a terminal and the log view otherwise."""
    stream = out or sys.stdout
    if mode == "auto":
        mode = "live" if stream.isatty() else "log"
    return {"live": LiveView, "log": LogView, "none": NoView}[mode](spec, events, stream)
