"""How many warnings bad daemon lines may cost, and when a daemon's output is beyond saving.

A daemon (or a vendor library that got hold of its stdout) can write garbage as fast as a pipe
carries it: tens of thousands of lines a second. One warning event per line would flood the
event stream, the web view and the log, so bad lines are reported like this:

- the first :data:`FULL_WARNINGS` of a process are published in full, each one;
- after that, at most one summary a second (``... N more bad lines in the last 1.0 s; last: ...``);
- :data:`FAULTY_LINES` bad lines within :data:`FAULTY_WINDOW` seconds declare the daemon faulty:
  the supervisor then treats it like a hung one (its requests fail ``daemon_faulty``, it is killed
  and restarted with backoff). A daemon that is merely chatty now and then never gets there.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from typing import Any

FULL_WARNINGS = 5
SUMMARY_PERIOD = 1.0  # wall seconds between two summaries
FAULTY_LINES = 200
FAULTY_WINDOW = 2.0  # wall seconds

Publish = Callable[[str, dict[str, Any]], None]


class BadLineLimiter:
    """Counts one daemon process's bad lines and decides which become warning events."""

    def __init__(self, family: str, publish: Publish) -> None:
        self.family = family
        self.total = 0
        self.faulty: str | None = None
        self._publish = publish
        self._held = 0  # bad lines since the last warning or summary
        self._last: str = ""
        self._next_summary = 0.0
        self._recent: deque[float] = deque()

    def report(self, message: str, now: float) -> None:
        self.total += 1
        self._recent.append(now)
        while self._recent and now - self._recent[0] > FAULTY_WINDOW:
            self._recent.popleft()
        if self.faulty is None and len(self._recent) >= FAULTY_LINES:
            self.faulty = (f"{self.family} daemon sent {len(self._recent)} lines that are not protocol within "
                           f"{FAULTY_WINDOW:g} s (limit {FAULTY_LINES})")
        if self.total <= FULL_WARNINGS:
            self._publish(message, {})
            self._next_summary = now + SUMMARY_PERIOD
            return
        self._held += 1
        self._last = message
        self.tick(now)

    def tick(self, now: float) -> None:
        """Publish the summary of held-back lines once its period has passed."""
        if not self._held or now < self._next_summary:
            return
        self._publish(f"{self.family} daemon sent {self._held} more line(s) that are not protocol "
                      f"(warnings held back; {self.total} in all); last: {self._last}",
                      {"suppressed": self._held, "total": self.total})
        self._held = 0
        self._next_summary = now + SUMMARY_PERIOD
