"""Ctrl-C and SIGTERM handled on a thread of their own, never inside the signal handler.

Python runs a signal handler on the main thread, between two of its bytecodes, wherever that
thread happens to be: also inside ``threading.Event.wait``, holding the lock the event's
``set`` needs. A handler that sets that event (asking a run to stop, waking a loop) then waits
for a lock its own thread holds, and the program hangs: seen in the Ctrl-C test of a fresh
clone, the executor asleep until its next tick on the very event the handler set.

So the handler here only puts the signal's number in a :class:`queue.SimpleQueue`, whose
``put`` is reentrant (documented as safe where any other code may be interrupted), and a
watcher thread takes it from there and calls ``on_signal`` like any other thread would: the
executor's stop, an event, anything that takes a lock. What ``on_signal`` does is then as
thread-safe as its own code, and the stop it asks for still comes within one tick.
"""

from __future__ import annotations

import queue
import signal
import threading
from collections.abc import Callable, Iterable
from types import TracebackType
from typing import Any

INTERRUPTS = (signal.SIGINT, signal.SIGTERM)


class Interrupts:
    """``with Interrupts(on_signal):``: SIGINT and SIGTERM call ``on_signal(signum)`` on the
    watcher thread while the block runs. On leaving, the handlers that were in place come back,
    or what ``then`` makes of each (a command line keeps one that exits quietly while it prints
    its summary). Only the main thread may set handlers: from any other, nothing is installed."""

    def __init__(self, on_signal: Callable[[int], None], signals: Iterable[signal.Signals] = INTERRUPTS,
                 then: Callable[[Any], Any] | None = None) -> None:
        self._on_signal = on_signal
        self._signals = tuple(signals)
        self._then = then
        self._queue: queue.SimpleQueue[int | None] = queue.SimpleQueue()
        self._watcher = threading.Thread(target=self._watch, name="interrupts", daemon=True)
        self.previous: dict[int, Any] = {}

    def __enter__(self) -> Interrupts:
        if threading.current_thread() is threading.main_thread():
            self._watcher.start()
            self.previous = {s: signal.signal(s, self._handle) for s in self._signals}
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        for signum, handler in self.previous.items():
            signal.signal(signum, self._then(handler) if self._then is not None else handler)
        if self._watcher.is_alive():
            self._queue.put(None)
            self._watcher.join(5.0)

    def _handle(self, signum: int, _frame: Any) -> None:
        self._queue.put(signum)  # reentrant: the only thing done inside the handler

    def _watch(self) -> None:
        while (signum := self._queue.get()) is not None:
            self._on_signal(signum)
