"""The event stream: one place where everything that happens is published.

Status changes, commands sent to daemons, daemon events, log lines, utterances and replies are
all :class:`Event` objects on one :class:`EventStream`. The run report, the JSON-lines log, the
terminal view the web view and the ROS bridge subscribe to it; none of them reach
into the executor. Publishing is synchronous and cheap: subscribers must not block.

Event kinds used by the framework (``data`` keys in brackets):

- ``run``: start / end of a run [phase, tree, status, backend]
- ``tree``: an executor was built for a tree [file, description, root (nested nodes)]
- ``status``: a node's status changed [old, new]  (``path`` is the node path)
- ``command``: a request sent to a daemon [family, id, cmd, args]
- ``daemon``: a line from a daemon [family, type, id, ...] (accepted, progress, done, error)
- ``daemon_state``: a daemon came up / died / restarts [family, state, reason]
- ``leaf``: a leaf finished [outcome, reason, result]
- ``log``: a ``log`` leaf or a framework message [level, message]
- ``blackboard``: a key was written [key, value]
- ``warning``: something a user should see (tick overrun, garbage line) [message]
- ``utterance`` / ``reply``: conversation in and out [text]
- ``pose``: the robot's map pose changed [x, y, yaw]
- ``memory``: perception's spatial memory after a ``find`` [format, t, frame, objects] (docs/perception.md;
  the ROS bridge publishes it on ``/spatial_memory/*``, docs/ros.md)
"""

from __future__ import annotations

import json
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import IO, Any

from .clock import Clock
from .jsonfile import to_json

ENVELOPE = ("t", "wall", "kind", "path")  # an event's own fields in its flat dict form


@dataclass(frozen=True)
class Event:
    """One thing that happened. ``t`` is clock time, ``wall`` is Unix time."""

    t: float
    kind: str
    path: str | None = None
    data: dict[str, Any] = field(default_factory=dict)
    wall: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        """Flat: the envelope (t, wall, kind, path) and the data keys side by side. A data key
        that would hide an envelope field (the ``utterance`` event's ``kind``: tasks, stop, ...)
        is written as ``data_<key>``; :meth:`from_dict` reads it back."""
        out: dict[str, Any] = {f"data_{k}" if k in ENVELOPE else k: v for k, v in self.data.items()}
        out.update({"t": round(self.t, 6), "wall": round(self.wall, 6), "kind": self.kind})
        if self.path is not None:
            out["path"] = self.path
        return out

    def to_json(self) -> str:
        return to_json(self.to_dict(), default=_json_default, separators=(",", ":"))

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Event:
        data = {k: v for k, v in d.items() if k not in ENVELOPE}
        for key in ENVELOPE:
            if f"data_{key}" in data:
                data[key] = data.pop(f"data_{key}")
        return cls(t=d.get("t", 0.0), kind=d["kind"], path=d.get("path"), data=data, wall=d.get("wall", 0.0))


def _json_default(value: Any) -> Any:
    if hasattr(value, "to_dict"):
        return value.to_dict()
    if isinstance(value, (set, frozenset, tuple)):
        return list(value)
    return str(value)


Subscriber = Callable[[Event], object]  # what it returns is ignored


class EventStream:
    """Synchronous publish / subscribe; safe to publish from several threads."""

    def __init__(self, clock: Clock) -> None:
        self.clock = clock
        self._subscribers: list[Subscriber] = []
        self._lock = threading.RLock()

    def subscribe(self, fn: Subscriber) -> Callable[[], None]:
        """Call ``fn`` with every later event; returns a function that unsubscribes."""
        with self._lock:
            self._subscribers = [*self._subscribers, fn]

        def unsubscribe() -> None:
            with self._lock:
                self._subscribers = [s for s in self._subscribers if s is not fn]

        return unsubscribe

    def publish(self, kind: str, path: str | None = None, /, **data: Any) -> Event:
        event = Event(self.clock.now(), kind, path, data, time.time())  # positional: a third cheaper
        for fn in self._subscribers:  # copy-on-write list: no lock needed to iterate
            fn(event)
        return event


class EventRecorder:
    """Keeps the events in memory (for reports and tests): every one, or with ``limit`` the last
    ``limit`` of them, so a session that runs all day (a mission console, a ROS bridge) holds a
    bounded history instead of growing with every word it hears."""

    def __init__(self, stream: EventStream | None = None, limit: int | None = None) -> None:
        self.events: list[Event] | deque[Event] = [] if limit is None else deque(maxlen=limit)
        self._unsubscribe = stream.subscribe(self.events.append) if stream else None

    def close(self) -> None:
        if self._unsubscribe:
            self._unsubscribe()
            self._unsubscribe = None

    def of_kind(self, kind: str) -> list[Event]:
        return [e for e in self.events if e.kind == kind]


class JsonlWriter:
    """Writes each event as one JSON line (the ``--log`` file)."""

    def __init__(self, stream: EventStream, out: IO[str]) -> None:
        self._out = out
        self._lock = threading.Lock()
        self._unsubscribe = stream.subscribe(self._write)

    def _write(self, event: Event) -> None:
        with self._lock:
            self._out.write(event.to_json() + "\n")
            self._out.flush()

    def close(self) -> None:
        self._unsubscribe()


def read_jsonl(path: str) -> list[Event]:
    """Read events back from a JSON-lines log."""
    with open(path, encoding="utf-8") as f:
        return [Event.from_dict(json.loads(line)) for line in f if line.strip()]
