"""web: what the live web view costs the executor, and how late a status change reaches a browser.

Set-up: the web app (``stuart_bt.web.app``) on uvicorn on 127.0.0.1 in a thread of this process,
its hub subscribed to an executor's event stream, and 5 WebSocket clients, each a process of its
own (as browsers are) that reads every batch and notes, for each status event, its receive time
minus the event's publish time (``time.time()`` on both sides: one machine, one clock).

- **tick overhead** (goal <= 5 %): two identical trees, both streams with the subscriber every
  run has (bench/sink.py), one also with the web view and its 5 clients; each ticked by
  ``Executor.tick_once`` at the run's pace (20 Hz of wall time; the quick run 50 Hz), in
  alternating rounds. Each tick is timed on the executor's thread, so what is measured is what
  the executor feels: the hub's subscriber on its thread and the server's work competing for the
  interpreter between ticks (collector paused in each round, as in the other benchmarks). A third,
  identical tree without the web view gives the noise floor of the ratio (an A/A pair). Figure:
  the median tick with the web view; ratio: median over rounds of (median tick web / median tick
  none), goal <= 1.05. Trees: ``flip-10`` (10 status changes every tick: more than a real tree, the tour averages
  well under one per tick) and ``flip-100`` (100 per tick, the worst case, no goal).
- **latency**: every status event of those runs, publish to receive in a client process;
  anchor: the executor's tick period (a constant: the pace the view has to keep up with), goal
  p99 <= 2 ticks (it was p99 <= 100 ms, the same at 20 Hz).
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import threading
import time
from typing import Any

from stuart_bt.core.clock import ManualClock
from stuart_bt.core.events import EventStream
from stuart_bt.run.executor import Executor

from .result import Anchor, Goal, Result
from .sink import EventCounter
from .stats import gc_paused, percentile
from .trees import Shape, build_py_trees

NAME = "web"
CLIENTS = 5
GOAL_OVERHEAD = 5.0  # percent
GOAL_LATENCY_P99_MS = 100.0  # the absolute goal the ratio goal replaces (information)
GOAL_LATENCY_P99 = Goal(2.0, was=f"<= {GOAL_LATENCY_P99_MS:g} ms")  # two tick periods at 20 Hz

CLIENT = r"""
import json, sys, threading, time
from websockets.sync.client import connect
delays, count = [], 0
with connect(sys.argv[1], open_timeout=20, max_size=None) as socket:
    json.loads(socket.recv(timeout=20))  # hello
    print("ready", flush=True)
    threading.Thread(target=lambda: (sys.stdin.read(), socket.close()), daemon=True).start()
    try:
        for text in socket:
            now = time.time()
            for e in json.loads(text).get("events", []):
                if e.get("kind") == "status":
                    count += 1
                    delays.append(now - e["wall"])
    except Exception:
        pass
print(json.dumps({"count": count, "delays": delays}), flush=True)
"""


class Clients:
    """``CLIENTS`` processes reading the socket; on ``close`` each reports its delays."""

    def __init__(self, url: str, n: int = CLIENTS) -> None:
        self.procs = [subprocess.Popen([sys.executable, "-c", CLIENT, url], stdin=subprocess.PIPE,
                                       stdout=subprocess.PIPE, text=True) for _ in range(n)]
        for proc in self.procs:
            if proc.stdout is None or proc.stdout.readline().strip() != "ready":
                raise RuntimeError("a WebSocket client did not connect")

    def close(self) -> tuple[list[int], list[float]]:
        """(status events each client received, every delay in seconds)."""
        counts, delays = [], []
        for proc in self.procs:
            out, _ = proc.communicate("", timeout=30)
            report = json.loads(out.strip().splitlines()[-1])
            counts.append(report["count"])
            delays += report["delays"]
        return counts, delays


class Server:
    """The web app for one event stream, on a free loopback port, in a thread."""

    def __init__(self, events: EventStream) -> None:
        import socket

        import uvicorn

        from stuart_bt.web.app import WebParts, create_app
        from stuart_bt.web.hub import EventHub
        from stuart_bt.web.security import Guard

        self.hub = EventHub(events, info={"mode": "bench"})
        self.listener = socket.socket()
        self.listener.bind(("127.0.0.1", 0))
        self.listener.listen(16)
        self.port = self.listener.getsockname()[1]
        config = uvicorn.Config(create_app(WebParts(self.hub, Guard(None))), log_level="warning",
                                lifespan="on", ws="websockets-sansio", timeout_graceful_shutdown=2)
        self.server = uvicorn.Server(config)
        self.thread = threading.Thread(target=self.server.run, kwargs={"sockets": [self.listener]}, daemon=True)
        self.thread.start()
        deadline = time.monotonic() + 20
        while not self.server.started and time.monotonic() < deadline:
            time.sleep(0.01)

    @property
    def url(self) -> str:
        return f"ws://127.0.0.1:{self.port}/ws"

    def close(self) -> None:
        self.server.should_exit = True
        self.thread.join(timeout=10)
        self.hub.close()
        self.listener.close()


def stream() -> EventStream:
    """An event stream with the one subscriber every run has (the report builder's part)."""
    events = EventStream(ManualClock())
    events.subscribe(EventCounter())
    return events


def executor(shape: Shape, rate: float, events: EventStream | None = None) -> Executor:
    events = events or stream()
    return Executor(build_py_trees(shape), events.clock, events, rate=rate)


def paced_ticks(ex: Executor, n: int, rate: float) -> list[float]:
    """Tick ``n`` times at ``rate`` Hz of wall time; the duration of each tick_once."""
    period = 1.0 / rate
    took = []
    next_tick = time.perf_counter()
    for _ in range(n):
        start = time.perf_counter()
        ex.tick_once()
        took.append(time.perf_counter() - start)
        next_tick += period
        time.sleep(max(0.0, next_tick - time.perf_counter()))
    return took


def overhead(shape: Shape, watched: Executor, ticks: int, rounds: int, rate: float) -> Result:
    """``watched`` (on the web view's stream) against two identical trees without it."""
    plain = executor(shape, rate)
    twin = executor(shape, rate)  # a second tree without the web view: the noise floor (A/A)
    candidates = {"none": plain, "twin": twin, "web": watched}
    ticks_of: dict[str, list[float]] = {name: [] for name in candidates}
    ratios, floor = [], []
    for r in range(rounds):
        names = list(candidates)
        medians = {}
        for name in names[r % 3:] + names[:r % 3]:  # rotating order
            with gc_paused():  # the collector's pauses land on whoever allocates last (bench/stats.py)
                took = paced_ticks(candidates[name], ticks, rate)
            ticks_of[name].extend(took)
            medians[name] = statistics.median(took)
        ratios.append(medians["web"] / medians["none"])
        floor.append(medians["twin"] / medians["none"])
    ratio = statistics.median(ratios)
    none_us, web_us = statistics.median(ticks_of["none"]) * 1e6, statistics.median(ticks_of["web"]) * 1e6
    noise = (statistics.median(floor) - 1) * 100
    limit = 1.0 + GOAL_OVERHEAD / 100.0
    goal = Goal(limit) if shape.size <= 10 else None
    note = (f"{shape.label}: {shape.size} status changes per tick at {rate:g} Hz, with the web view and {CLIENTS} "
            f"WebSocket client processes; overhead {(ratio - 1) * 100:+.1f} %, noise floor (a second tree without "
            f"the web view against the first) {noise:+.1f} % ({rounds} rounds of {ticks} ticks each, order rotating, "
            "ratio = median of per-round ratios; every client received every status event)")
    if goal is None:
        note += "; worst case (every node changes every tick), no goal"
    return Result(f"{NAME}.tick_overhead.{shape.label}", web_us, "us/tick",
                  Anchor("the same executor and tree without the web view", none_us),
                  goal, note, paired_ratio=ratio)


def latency(delays: list[float], rate: float) -> list[Result]:
    delays_ms = [d * 1000.0 for d in delays]
    p50, p99 = percentile(delays_ms, 50), percentile(delays_ms, 99)
    anchor = Anchor(f"executor tick period at {rate:g} Hz (ms)", 1000.0 / rate, timed=False)
    note = (f"{len(delays_ms)} status events received by {CLIENTS} WebSocket client processes during the tick "
            f"overhead runs ({rate:g} Hz); publish (executor thread) to receive (client process)")
    return [Result(f"{NAME}.latency.p50", p50, "ms", anchor, note=note),
            Result(f"{NAME}.latency.p99", p99, "ms", anchor, GOAL_LATENCY_P99, note)]


def run(quick: bool = False) -> list[Result]:
    ticks, rounds, rate = (6, 3, 50.0) if quick else (40, 12, 20.0)
    shapes = (Shape("flip", 10), Shape("flip", 100))
    events = stream()  # one web view for both trees
    watched = [executor(shape, rate, events) for shape in shapes]
    server = Server(events)
    clients = Clients(server.url)
    try:
        results = [overhead(shape, ex, ticks, rounds, rate) for shape, ex in zip(shapes, watched, strict=True)]
        time.sleep(0.2)  # the last batch on its way
    finally:
        counts, delays = clients.close()
        server.close()
    sent = sum(ex.ticks * shape.size for shape, ex in zip(shapes, watched, strict=True))
    if min(counts) < sent:
        raise RuntimeError(f"a client received {min(counts)} of {sent} status events")
    return [*results, *latency(delays, rate)]


def main() -> Any:  # pragma: no cover - python -m bench.web for a look
    for result in run(quick="--full" not in sys.argv):
        print(result.name, f"{result.value:.3f}", result.unit, result.note)


if __name__ == "__main__":  # pragma: no cover
    main()
