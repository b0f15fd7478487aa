"""Terminal views of a running tree, fed only by the event stream.

- :class:`LiveView` (a terminal): the tree redrawn with each node's status, a progress bar over the
  top-level steps and the latest events (speech, gestures, failures, warnings).
- :class:`LogView` (pipes, CI logs): one plain line per interesting event.
- :class:`NoView`: silence, except for the final summary.

Views keep their own copy of node statuses from ``status`` events; they never look inside the
executor, so the same code can replay a saved event log.

A view never slows a tick: events arrive on the tick thread, so a view only notes them there
and writes from a thread of its own (the log view) or a drawing process of its own (the live
view, :mod:`stuart_bt.run.drawing`). A slow terminal or a pipe read slowly then delays the
view, which drops frames (live) or lines it cannot hold (log, and says how many), never the run.
"""

from __future__ import annotations

import contextlib
import json
import queue
import subprocess
import sys
import threading
from collections import deque
from typing import IO, Any, TextIO

from ..core.events import Event, EventStream
from ..tree.render import label
from ..tree.spec import NodeSpec, TreeSpec
from .drawing import FRAME_RATE, RECENT

LOG_BACKLOG = 10_000  # lines the log view holds for a slow reader before it drops (and counts) them
DRAWER_EXIT_WAIT = 30.0  # wall s the drawing process may take to draw the final state on a slow terminal


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
        self._unsubscribe = events.subscribe(self.on_event)

    def on_event(self, event: Event) -> None:
        """Called on the publisher's thread (often the tick thread): note, never write or wait."""

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
    """One line per interesting event, written by a thread of its own: the tick thread only
    queues the line. A reader slower than the run gets the first :data:`LOG_BACKLOG` waiting
    lines and then one line saying how many were dropped."""

    def __init__(self, spec: TreeSpec, events: EventStream, out: TextIO | None = None) -> None:
        super().__init__(spec, events, out)
        self._lines: queue.Queue[str | None] = queue.Queue(maxsize=LOG_BACKLOG)
        self._dropped = 0  # written by the publisher's thread only, read by the writer
        self._writer = threading.Thread(target=self._write, name="log-view", daemon=True)

    def on_event(self, event: Event) -> None:
        line = _interesting(event)
        if line:
            try:
                self._lines.put_nowait(f"[{event.t:8.2f}] {line}")
            except queue.Full:
                self._dropped += 1

    def start(self) -> None:
        self._writer.start()

    def stop(self) -> None:
        super().stop()
        if self._writer.is_alive():
            self._lines.put(None)  # after every line queued; waits for room, the run is over
            self._writer.join()

    def _write(self) -> None:
        written_drops = 0
        for line in iter(self._lines.get, None):
            print(line, file=self.out, flush=self._lines.empty())
            if self._lines.empty() and self._dropped > written_drops:
                print(f"[view] {self._dropped - written_drops} lines dropped: the output is read more "
                      "slowly than the run writes it", file=self.out, flush=True)
                written_drops = self._dropped
        self.out.flush()


class LiveView(_Base):
    """The tree redrawn on a terminal by a drawing process (:mod:`stuart_bt.run.drawing`) whose
    stdout is ``out``. The tick thread only notes what changed; a sender thread ships it,
    merged, at most :data:`FRAME_RATE` times a second; the drawer draws the latest state. Its
    drawing takes no CPU time from this interpreter (the tick thread's lock), and a slow
    terminal holds up only the drawer and the sender, which then send the state as it is by
    the time they are free."""

    def __init__(self, spec: TreeSpec, events: EventStream, out: TextIO | None = None) -> None:
        super().__init__(spec, events, out)
        self._lock = threading.Lock()
        self._changed: dict[str, str] = {}
        self._recent: deque[str] = deque(maxlen=RECENT)
        self._closing = False
        self._wake = threading.Event()  # something to send, or closing
        self._closed = threading.Event()
        self._drawer: subprocess.Popen[bytes] | None = None
        self._sender = threading.Thread(target=self._send_changes, name="live-view", daemon=True)

    def on_event(self, event: Event) -> None:
        line = _interesting(event)
        if event.kind == "status" and event.path is not None:
            with self._lock:
                self._changed[event.path] = event.data["new"]
                self._wake.set()
        if line:
            with self._lock:
                self._recent.append(f"[{event.t:7.1f}] {line}")
                self._wake.set()

    def start(self) -> None:
        self.out.flush()
        self._drawer = subprocess.Popen([sys.executable, "-m", "stuart_bt.run.drawing"], stdin=subprocess.PIPE,
                                        stdout=self.out, start_new_session=True)
        self._send({"layout": _layout(self.spec.root)})
        self._sender.start()

    def stop(self) -> None:
        super().stop()
        with self._lock:
            self._closing = True
        self._closed.set()
        self._wake.set()
        if self._sender.is_alive():
            self._sender.join()  # the last changes are sent: the drawer ends on the final state
        if self._drawer is not None:
            if self._drawer.stdin is not None:
                with contextlib.suppress(OSError):  # the drawer is gone: its pipe is broken
                    self._drawer.stdin.close()
            try:
                self._drawer.wait(DRAWER_EXIT_WAIT)
            except subprocess.TimeoutExpired:  # a terminal that takes no more output
                self._drawer.kill()
                self._drawer.wait()

    def _send_changes(self) -> None:
        while True:
            self._wake.wait()
            with self._lock:
                self._wake.clear()
                changes = {"statuses": self._changed, "recent": list(self._recent)}
                self._changed = {}
                self._recent.clear()
                closing = self._closing
            if changes["statuses"] or changes["recent"]:
                self._send(changes)
            if closing:
                return
            self._closed.wait(1.0 / FRAME_RATE)  # what changes meanwhile goes in the next message

    def _send(self, message: dict[str, Any]) -> None:
        """One JSON line to the drawer (blocks while it is behind; never on the tick thread)."""
        pipe: IO[bytes] | None = self._drawer.stdin if self._drawer is not None else None
        if pipe is None or pipe.closed:
            return
        try:
            pipe.write(json.dumps(message, separators=(",", ":")).encode() + b"\n")
            pipe.flush()
        except OSError:  # the drawer died (its terminal went away): the run goes on undrawn
            pipe.close()


def _layout(node: NodeSpec) -> dict[str, Any]:
    """The tree as the drawer needs it: each node's path, label and children."""
    return {"path": node.path, "label": label(node), "children": [_layout(c) for c in node.children]}


def make_view(mode: str, spec: TreeSpec, events: EventStream, out: TextIO | None = None) -> _Base:
    """``auto`` picks the live view on a terminal and the log view otherwise."""
    stream = out or sys.stdout
    if mode == "auto":
        mode = "live" if stream.isatty() else "log"
    return {"live": LiveView, "log": LogView, "none": NoView}[mode](spec, events, stream)
