"""The terminal views never slow a tick (docs/running.md, "Views").

Events reach a view on the tick thread. A view that wrote there, or drew there, would make the
tick wait for the terminal; one that drew on another thread of the run's process would still
take the interpreter lock from the tick thread while it draws. These runs give the views a
slow reader and a slow draw, and check the executor counted no overrun while the views still
end on the run's final state.
"""

from __future__ import annotations

import fcntl
import os
import pty
import re
import struct
import termios
import threading
import time
from pathlib import Path
from typing import Any, TextIO

import pytest
import rich.tree

from stuart_bt.run.session import RunOptions, Session
from stuart_bt.run.view import make_view
from stuart_bt.tree.loader import load_tree_text

STEPS = 12  # log + wait pairs: a run of about 40 ticks
PIPE_SIZE = 4096  # the smallest pipe Linux makes: a slow reader fills it within the run
SLOW_CHUNK, SLOW_PAUSE = 64, 0.05  # the slow reader takes 64 bytes every 50 ms (about 1.3 kB/s)
DRAW_COST = 3_000_000  # items summed in C per tree drawn: tens of ms holding the interpreter lock
ROWS, COLUMNS = 60, 120
ROOT = "[->] steps"  # how the views label the root sequence

SLOW_DRAW = f'''
import rich.tree

_draw = rich.tree.Tree.__rich_console__


def _slow_draw(self, console, options):
    sum(range({DRAW_COST}))  # like drawing done in C: the interpreter lock is held throughout
    yield from _draw(self, console, options)


rich.tree.Tree.__rich_console__ = _slow_draw
'''


def steps_tree(message_size: int = 0) -> Any:
    pad = "x" * message_size
    steps = "\n".join(f"      - log: step {i} {pad}\n      - wait: 0.05" for i in range(STEPS))
    return load_tree_text(f"root:\n  sequence:\n    name: steps\n    children:\n{steps}\n")


class SlowReader:
    """Reads ``fd`` a little at a time until told to hurry, then drains it to the end."""

    def __init__(self, fd: int) -> None:
        self.fd = fd
        self.data = bytearray()
        self.read_while_slow = 0  # bytes taken before the hurry: what a slow terminal let through
        self.hurry = threading.Event()
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._thread.start()

    def _read(self) -> None:
        while True:
            try:
                chunk = os.read(self.fd, SLOW_CHUNK if not self.hurry.is_set() else 1 << 16)
            except OSError:  # a pty whose other side closed
                return
            if not chunk:
                return
            self.data.extend(chunk)
            if not self.hurry.is_set():
                self.read_while_slow = len(self.data)
                time.sleep(SLOW_PAUSE)

    def text(self) -> str:
        self.hurry.set()
        self._thread.join(30)
        assert not self._thread.is_alive(), "the view's output never ended"
        return self.data.decode("utf-8", errors="replace")

    def was_behind(self) -> bool:
        """More was still to come when the run ended than the pipe or terminal could hold: the
        view had to wait for this reader (or drop what it could not write)."""
        return len(self.data) - self.read_while_slow > PIPE_SIZE


def run_viewed(mode: str, spec: Any, out: TextIO, reader: SlowReader) -> tuple[dict[str, Any], int]:
    """Run ``spec`` at real time with a ``mode`` view on ``out``; (report, overruns counted)."""
    session = Session(spec, RunOptions(speed=1.0))
    view = make_view(mode, spec, session.events, out)
    with session:
        view.start()
        try:
            outcome = session.run()
        finally:
            reader.hurry.set()  # the run is over: now the view may catch up
            view.stop()
    report = session.report()
    view.summary(report)
    out.close()
    assert outcome.status == "SUCCESS"
    assert session.executor is not None
    return report, session.executor.overruns


def overrun_warnings(report: dict[str, Any]) -> list[str]:
    return [w for w in report["warnings"] if "tick overrun" in w]


def test_a_log_view_on_a_pipe_read_slowly_never_delays_a_tick() -> None:
    read_end, write_end = os.pipe()
    fcntl.fcntl(write_end, fcntl.F_SETPIPE_SZ, PIPE_SIZE)
    reader = SlowReader(read_end)
    try:
        report, overruns = run_viewed("log", steps_tree(message_size=1000), os.fdopen(write_end, "w"), reader)
        text = reader.text()
    finally:
        os.close(read_end)

    assert overruns == 0 and not overrun_warnings(report), report["warnings"]
    lines = text.splitlines()
    assert reader.was_behind(), (reader.read_while_slow, len(reader.data))
    assert f"SUCCESS: steps/wait_{STEPS}" in lines[-2] and lines[-1].startswith("SUCCESS in"), lines[-3:]


@pytest.fixture
def slow_drawing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Drawing a tree takes long wherever it happens: in this process and in any Python process
    started from it (a ``sitecustomize`` on its path patches rich the same way)."""
    (tmp_path / "sitecustomize.py").write_text(SLOW_DRAW, encoding="utf-8")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(filter(None, (str(tmp_path), os.environ.get("PYTHONPATH")))))
    draw = rich.tree.Tree.__rich_console__

    def slow_draw(self: rich.tree.Tree, console: Any, options: Any) -> Any:
        sum(range(DRAW_COST))
        yield from draw(self, console, options)

    monkeypatch.setattr(rich.tree.Tree, "__rich_console__", slow_draw)


def test_a_live_view_drawing_slowly_on_a_slow_terminal_never_delays_a_tick_and_ends_on_the_final_state(
        slow_drawing: None) -> None:
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", ROWS, COLUMNS, 0, 0))
    reader = SlowReader(master)
    try:
        report, overruns = run_viewed("live", steps_tree(), os.fdopen(slave, "w", encoding="utf-8"), reader)
        text = reader.text()
    finally:
        os.close(master)

    assert overruns == 0 and not overrun_warnings(report), report["warnings"]
    assert reader.was_behind(), (reader.read_while_slow, len(reader.data))
    progress = re.findall(r"(\d+)/(\d+) steps", text)
    assert progress, text[-500:]
    assert progress[-1] == (str(2 * STEPS), str(2 * STEPS))  # the last frame drawn is the finished tree
    last_frame = text[text.rindex(ROOT):]
    assert text.rindex(f"✔ {ROOT}") == text.rindex(ROOT) - len("✔ "), last_frame  # the root drawn last is done
    assert f"✔ wait seconds=0.05 (wait_{STEPS})" in last_frame, last_frame
    assert "SUCCESS in" in text.rstrip().splitlines()[-1]  # the summary comes after the last frame
