"""What every ears backend offers: ``listen``, an activity whose progress lines each carry one
utterance heard (``{"heard": {...}}``) until it is cancelled or its sound ends.

Hearing runs on its own thread (a socket, a recogniser, a DDS callback) and hands utterances to
the daemon loop through a queue, so the loop's heartbeats never wait for a recogniser.
"""

from __future__ import annotations

import queue
import threading
from abc import abstractmethod
from collections.abc import Callable
from typing import Any, ClassVar

from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, Backend, DaemonError, Done, Handler, Progress

POLL_S = 0.05  # clock seconds between looks at the queue of utterances


def heard_line(text: str, source: str, confidence: float | None = None, audio_s: float | None = None,
               start_s: float | None = None, no_speech: float | None = None, **extra: Any) -> dict[str, Any]:
    """One utterance as the ``heard`` object of a progress line (None where the source cannot say)."""
    return {"text": text, "source": source, "confidence": confidence, "audio_s": audio_s, "start_s": start_s,
            "no_speech": no_speech, **extra}


class Ended:
    """Put on the queue when the sound ends (``error``: why it ended early, if it failed)."""

    def __init__(self, error: str | None = None) -> None:
        self.error = error


Deliver = Callable[[dict[str, Any] | Ended], None]


class Listening(Activity):
    """Utterances from ``run`` (called on its own thread with a deliver function; it returns when
    the sound ends or ``stop`` was called) become progress lines, one per utterance."""

    resource: ClassVar[str | None] = "ears"

    def __init__(self, backend: EarsBackend, run: Callable[[Deliver], None], stop: Callable[[], None]) -> None:
        self.backend = backend
        self._run, self._stop = run, stop
        self._queue: queue.Queue[dict[str, Any] | Ended] = queue.Queue()
        self.count = 0
        self._due = 0.0

    def start(self, now: float) -> dict[str, Any]:
        threading.Thread(target=self._hear, name="ears-listen", daemon=True).start()
        return {}

    def _hear(self) -> None:
        try:
            self._run(self._queue.put)
            self._queue.put(Ended())
        except Exception as e:  # noqa: BLE001 - whatever stopped the sound ends the activity with its reason
            self._queue.put(Ended(str(e) or type(e).__name__))

    def poll(self, now: float) -> Progress | Done | None:
        self._due = now + POLL_S
        try:
            item = self._queue.get_nowait()
        except queue.Empty:
            return None
        if isinstance(item, Ended):
            if item.error:
                raise DaemonError("backend_error", f"ears listen: {item.error}")
            return Done({"heard": self.count})
        self.count += 1
        self.backend.heard_total += 1
        return Progress({"heard": item})

    def next_due(self) -> float | None:
        return None if not self._queue.empty() else self._due

    def cancel(self, now: float) -> dict[str, Any]:
        self._stop()
        return {"heard": self.count}


class EarsBackend(Backend):
    family = "ears"

    def __init__(self, clock: Any, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        self.heard_total = 0
        self._logs: list[tuple[str, str]] = []
        self._logs_lock = threading.Lock()

    @abstractmethod
    def listen(self) -> Activity:
        """Start hearing; progress data is ``{"heard": heard_line(...)}``, the result ``{"heard": N}``."""

    def commands(self) -> dict[str, Handler]:
        return {"listen": self._listen_command}

    def _listen_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, (), "listen")
        return self.listen()

    def warn(self, message: str) -> None:
        """A ``log`` warning line, from any thread (sent by the daemon loop)."""
        with self._logs_lock:
            self._logs.append(("warning", message))

    def take_logs(self) -> list[tuple[str, str]]:
        """The warnings since the last call (the daemon loop sends them as ``log`` lines)."""
        with self._logs_lock:
            logs, self._logs = self._logs, []
        return logs

    def state(self) -> dict[str, Any]:
        return {"heard_total": self.heard_total}
