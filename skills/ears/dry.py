"""Dry ears: no sound at all; ``listen`` hears the texts of the ``texts`` option, one every
``interval_s`` clock seconds, then ends (a tree or a test can be spoken to without a robot)."""

from __future__ import annotations

from typing import Any, ClassVar

from stuart_bt.core.clock import Clock
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, DaemonError, Done, Progress, StartupError

from .backend import EarsBackend, heard_line

SOURCE = "dry"


class DryListening(Activity):
    """The scripted texts, heard at their times."""

    resource: ClassVar[str | None] = "ears"

    def __init__(self, backend: DryEars) -> None:
        self.backend = backend
        self.texts = list(backend.texts)
        self.count = 0
        self.started = 0.0

    def start(self, now: float) -> dict[str, Any]:
        self.started = now
        return {"texts": len(self.texts)}

    def next_due(self) -> float:
        return self.started + (self.count + 1) * self.backend.interval

    def poll(self, now: float) -> Progress | Done | None:
        if now < self.next_due():
            return None
        if self.count >= len(self.texts):
            return Done({"heard": self.count})
        text = self.texts[self.count]
        self.count += 1
        self.backend.heard_total += 1
        start_s = round(self.started + (self.count - 1) * self.backend.interval, 3)
        return Progress({"heard": heard_line(text, SOURCE, 1.0, 0.0, start_s, 0.0)})

    def cancel(self, now: float) -> dict[str, Any]:
        return {"heard": self.count}


class DryEars(EarsBackend):
    name = "dry"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        where = "ears dry options"
        try:
            a.only_known(options, ("texts", "interval_s"), where)
            self.interval = a.number(options, "interval_s", where, default=1.0, minimum=0.01)
        except DaemonError as e:
            raise StartupError(e.reason) from None
        texts = options.get("texts", [])
        if not (isinstance(texts, list) and all(isinstance(t, str) for t in texts)):
            raise StartupError(f"{where}: 'texts' must be a list of strings, got {texts!r}")
        self.texts: list[str] = texts

    def listen(self) -> Activity:
        return DryListening(self)
