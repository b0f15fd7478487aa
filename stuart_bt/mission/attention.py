"""A bare "Hey Stuart" keeps the robot listening for what comes next.

People call a robot, wait to see it heard, then say what they want ("Hey Stuart." ... "go to
the kitchen"), and a speech segmenter may cut "Hey Stuart, ... stop" in two at a long pause.
An utterance that is only the wake phrase holds the robot's attention for ``hold_s`` wall
seconds (people speak in wall time, whatever the simulator's speed); the next utterance in that
time is taken as addressed to it, and uses up the hold. Anything else said ends it. The words
must still have the form of a command: the hold stands in for the wake phrase, nothing more.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

from .commands import Command

WAKE_HOLD_S = 5.0


class Attention:
    """Whether a bare wake phrase was heard in the last ``hold_s`` seconds (thread-safe)."""

    def __init__(self, hold_s: float = WAKE_HOLD_S, now: Callable[[], float] = time.monotonic) -> None:
        self.hold_s = hold_s
        self._now = now
        self._until = 0.0
        self._lock = threading.Lock()

    def held(self) -> bool:
        """Is the robot's attention held now? (Looking does not use the hold up.)"""
        with self._lock:
            return self._now() < self._until

    def take(self) -> bool:
        """Is the robot's attention held now? (Asking uses the hold up.)"""
        with self._lock:
            held = self._now() < self._until
            self._until = 0.0
            return held

    def after(self, command: Command) -> None:
        """What was just said: a bare wake phrase holds the attention for the next utterance."""
        parse = command.parse
        if parse.wake and not parse.command.strip(" ,.!?"):
            with self._lock:
                self._until = self._now() + self.hold_s
