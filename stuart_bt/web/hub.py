"""From the event stream to the browsers: one subscriber, batched pushes, history for late joiners.

The executor publishes on its own thread and must never wait for a browser, so the subscriber
only appends the event to a pending list: no encoding, no wake-up of another thread (a wake-up
per batch made the tick measurably slower; see bench/web.py). The server's event loop flushes
the list every FLUSH_EVERY seconds: it folds the batch into the snapshot and the history, encodes
it once and hands the same text to every client's bounded queue; a client that falls far behind
is told to reload instead of growing memory without end. A status change therefore reaches the
browsers at most FLUSH_EVERY (plus sending) after it happened.

A browser that connects later gets a ``hello``: the snapshot (stuart_bt.snapshot/1) and the
recent history of events, from which it folds the same state and draws the scrubbable timeline.
The same hub serves a saved log (``--replay``): the whole log is the history and nothing is live.
"""

from __future__ import annotations

import asyncio
import json
from collections import deque
from collections.abc import Iterable
from typing import Any

from ..core.events import Event, EventStream, _json_default
from ..core.jsonfile import to_json
from ..run.snapshot import TreeSnapshot

FLUSH_EVERY = 0.015  # seconds between two pushes to the browsers
HISTORY = 50_000  # events a late browser receives (the tour has ~3000 status changes)
CLIENT_QUEUE = 2_000  # batches a client may fall behind before it is told to resync


class Client:
    """One connected browser: a queue of encoded messages the socket task sends in order."""

    def __init__(self) -> None:
        self.queue: asyncio.Queue[str | None] = asyncio.Queue(maxsize=CLIENT_QUEUE)
        self.dropped = False

    def offer(self, text: str) -> None:
        try:
            self.queue.put_nowait(text)
        except asyncio.QueueFull:
            self.dropped = True
            self._drain()
            self.queue.put_nowait(to_json({"type": "resync"}))

    def _drain(self) -> None:
        while not self.queue.empty():
            self.queue.get_nowait()

    def end(self, last: str | None = None) -> None:
        """Make the socket's sender stop (after ``last``, if given), however full the queue is."""
        self._drain()
        if last is not None:
            self.queue.put_nowait(last)
        self.queue.put_nowait(None)


class EventHub:
    """Keeps the snapshot and history; pushes batches of events to the connected clients."""

    def __init__(self, events: EventStream | None = None, replay: Iterable[Event] = (),
                 info: dict[str, Any] | None = None) -> None:
        self.info = dict(info or {})
        self.snapshot = TreeSnapshot()
        self.history: deque[dict[str, Any]] = deque(maxlen=HISTORY)
        self.replay = False
        for event in replay:
            self.replay = True
            self._fold(event)
        self.clients: set[Client] = set()
        self._pending: deque[Event] = deque()
        self._pump: asyncio.Task[None] | None = None
        self._unsubscribe = events.subscribe(self._on_event) if events is not None else None

    def attach(self, loop: asyncio.AbstractEventLoop) -> None:
        """Start pushing from the server's event loop (call it on that loop)."""
        self._pump = loop.create_task(self._push_forever())

    async def _push_forever(self) -> None:
        while True:
            self._flush()
            await asyncio.sleep(FLUSH_EVERY)

    def close(self) -> None:
        if self._unsubscribe is not None:
            self._unsubscribe()
            self._unsubscribe = None
        if self._pump is not None:
            self._pump.cancel()
            self._pump = None
        for client in list(self.clients):
            client.end(to_json({"type": "bye"}))

    # -- publishing thread: as little as possible (the executor is waiting) -------------------------
    def _on_event(self, event: Event) -> None:
        if event.kind == "blackboard":  # its value may be changed in place later: keep it as it is now
            event = Event(event.t, event.kind, event.path, _frozen(event.data), event.wall)
        self._pending.append(event)  # deque.append is atomic: no lock on the executor's thread

    # -- event loop ---------------------------------------------------------------------------------
    def _fold(self, event: Event) -> dict[str, Any]:
        self.snapshot.apply(event)
        item = event.to_dict()  # a data key that clashes with the event's own arrives as data_<key>
        self.history.append(item)
        return item

    def _flush(self) -> None:
        pending = self._pending
        events = [pending.popleft() for _ in range(len(pending))]  # what arrives meanwhile waits
        batch = [self._fold(e) for e in events]
        if not batch or not self.clients:
            return
        text = to_json({"type": "events", "events": batch}, default=_json_default, separators=(",", ":"))
        for client in list(self.clients):
            client.offer(text)

    def connect(self) -> tuple[Client, str]:
        """Register a new client and its first message: who we are, the snapshot and the history.

        Runs on the event loop, like the flush, after flushing what is pending: the history then
        ends exactly where the next batch will begin (no gap, no duplicate)."""
        self._flush()
        client = Client()
        self.clients.add(client)
        hello = to_json({"type": "hello", "info": self.info, "replay": self.replay,
                            "snapshot": self.snapshot.to_dict(), "events": list(self.history)},
                           default=_json_default, separators=(",", ":"))
        return client, hello

    def disconnect(self, client: Client) -> None:
        self.clients.discard(client)


def _frozen(data: dict[str, Any]) -> dict[str, Any]:
    """A deep copy as plain JSON data (what the page would receive anyway)."""
    return json.loads(to_json(data, default=_json_default))
