"""The live terminal view's drawing process (``python -m stuart_bt.run.drawing``).

:class:`~stuart_bt.run.view.LiveView` starts it with the terminal as its stdout and feeds it
JSON lines on stdin: first ``{"layout": NODE}`` (NODE: ``{"path", "label", "children"}``), then
``{"statuses": {path: status}, "recent": [line, ...]}`` with what changed since the last line.
It draws the latest state at most :data:`FRAME_RATE` times a second and drops the frames in
between; at the end of its input it draws the final state and exits.

Drawing lives in a process of its own because drawing a tree with rich costs milliseconds of
CPU a frame: in the run's process that time holds the interpreter lock the tick thread needs,
and a slow terminal would hold whatever thread writes to it. Here a slow terminal or a slow
draw delays only the next frame.
"""

from __future__ import annotations

import contextlib
import json
import os
import select
import signal
import sys
import time
from collections import deque
from typing import Any

from rich.console import Console, Group
from rich.live import Live
from rich.progress_bar import ProgressBar
from rich.table import Table
from rich.text import Text
from rich.tree import Tree

FRAME_RATE = 10.0  # frames a second at most; the state between two frames is merged, not queued
NICENESS = 10  # the drawer yields the processor to the run when both want it
RECENT = 6  # latest interesting events shown under the tree
STATUS_STYLE = {"SUCCESS": "green", "FAILURE": "bold red", "RUNNING": "bold yellow", "INVALID": "dim"}
STATUS_MARK = {"SUCCESS": "✔", "FAILURE": "✘", "RUNNING": "▶", "INVALID": "·"}


class Picture:
    """The state a frame draws: the tree's layout, each node's latest status, recent events."""

    def __init__(self) -> None:
        self.layout: dict[str, Any] = {"path": "", "label": "", "children": []}
        self.statuses: dict[str, str] = {}
        self.recent: deque[str] = deque(maxlen=RECENT)

    def take(self, message: dict[str, Any]) -> None:
        """Fold one input line into the state."""
        if "layout" in message:
            self.layout = message["layout"]
        self.statuses.update(message.get("statuses") or {})
        self.recent.extend(message.get("recent") or [])

    def renderable(self) -> Group:
        tree = self._tree(self.layout)
        steps = self.layout["children"] or [self.layout]
        done = sum(1 for c in steps if self.statuses.get(c["path"]) in ("SUCCESS", "FAILURE"))
        bar = Table.grid(padding=(0, 1))
        bar.add_row(ProgressBar(total=len(steps), completed=done, width=40), Text(f"{done}/{len(steps)} steps"))
        return Group(tree, bar, Text("\n".join(self.recent), style="dim"))

    def _tree(self, node: dict[str, Any], parent: Tree | None = None) -> Tree:
        """Finished and untouched branches fold into one line, so what runs stays on screen."""
        status = self.statuses.get(node["path"], "INVALID")
        text = Text(f"{STATUS_MARK.get(status, '?')} {node['label']}", style=STATUS_STYLE.get(status, ""))
        branch = Tree(text) if parent is None else parent.add(text)
        if status in ("SUCCESS", "INVALID") and parent is not None and node["children"]:
            hidden = _count(node) - 1
            branch.add(Text(f"… {hidden} node{'' if hidden == 1 else 's'}", style="dim"))
        else:
            for child in node["children"]:
                self._tree(child, branch)
        return branch


def _count(node: dict[str, Any]) -> int:
    return 1 + sum(_count(c) for c in node["children"])


class Lines:
    """Complete JSON lines from a file descriptor, read without blocking past what is there."""

    def __init__(self, fd: int) -> None:
        self.fd = fd
        self.ended = False
        self._partial = b""

    def read(self, timeout: float | None) -> list[dict[str, Any]]:
        """What arrived within ``timeout`` seconds (None: until something does), all of it."""
        messages: list[dict[str, Any]] = []
        while not self.ended and select.select([self.fd], [], [], timeout)[0]:
            chunk = os.read(self.fd, 1 << 16)
            if not chunk:
                self.ended = True
                break
            *complete, self._partial = (self._partial + chunk).split(b"\n")
            messages.extend(json.loads(line) for line in complete if line.strip())
            timeout = 0.0  # then only what is already there
        return messages


def draw(fd: int, console: Console, frame_rate: float = FRAME_RATE) -> None:
    """Draw the state read from ``fd`` until its end: at most ``frame_rate`` frames a second,
    each the latest state; then the final state once more, which stays on the screen."""
    picture, lines = Picture(), Lines(fd)
    live = Live(console=console, auto_refresh=False, transient=False, redirect_stdout=False, redirect_stderr=False)
    live.start()
    try:
        period, drawn, dirty = 1.0 / frame_rate, float("-inf"), False
        while not lines.ended:
            wait = None if not dirty else max(0.0, drawn + period - time.monotonic())
            for message in lines.read(wait):
                picture.take(message)
                dirty = True
            if dirty and time.monotonic() >= drawn + period:
                live.update(picture.renderable(), refresh=True)
                drawn, dirty = time.monotonic(), False
        live.update(picture.renderable(), refresh=True)
    finally:
        live.stop()


def main() -> int:
    # Ctrl-C is the run's to handle; this process ends when the run closes its input.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    with contextlib.suppress(OSError):
        os.nice(NICENESS)  # on a busy machine the run gets the processor first
    try:
        draw(sys.stdin.fileno(), Console())
    except BrokenPipeError:  # the terminal went away: nothing left to draw on
        return 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
