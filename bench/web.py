"""web: what the live web view costs the executor, and how late a status change reaches a browser.

Set-up: the web app (``stuart_bt.web.app``) on uvicorn on 127.0.0.1 in a thread of this process,
its hub subscribed to an executor's event stream, and 5 WebSocket clients, each a process of its
own (as browsers are) that reads every batch and notes, for each status event, its receive time
minus the event's publish time (``time.time()`` on both sides: one machine, one clock).

- **tick overhead** (goal <= 5 %): two identical trees, one with nothing listening, one with the
  web view and its 5 clients, each ticked by ``Executor.tick_once`` at the run's pace (20 Hz of
  wall time; the quick run 50 Hz), in alternating rounds. Each tick is timed on the executor's
  thread, so what is measured is what the executor feels: the hub's subscriber on its thread and
  the server's work competing for the interpreter between ticks. Figure: median over rounds of
  (median tick web / median tick none) - 1. Trees: ``flip-10`` (10 status changes every tick:
  more than a real tree, the tour averages well under one per tick) and ``flip-100`` (100 per
  tick, the worst case, no goal).
- **latency** (goal p99 <= 100 ms): every status event of the ``flip-10`` ticks, publish to
  receive in a client process.
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import threading
import time
from typing import Any

from stuart_bt.clock import ManualClock
from stuart_bt.events import EventStream
from stuart_bt.executor import Executor

from .result import Anchor, Result
from .stats import percentile
from .trees import Shape, build_py_trees

NAME = "web"
CLIENTS = 5
GOAL_OVERHEAD = 5.0  # percent
GOAL_LATENCY_P99_MS = 100.0

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
                                lifespan="on", ws="websockets-sansio")
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


def executor(shape: Shape, rate: float) -> tuple[Executor, EventStream]:
    clock = ManualClock()
    events = EventStream(clock)
    return Executor(build_py_trees(shape), clock, events, rate=rate), events


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


def measure(shape: Shape, ticks: int, rounds: int, rate: float) -> tuple[Result, list[float], int]:
    """The overhead figure for ``shape``; the delays seen by the clients; status events sent."""
    plain, _ = executor(shape, rate)
    watched, events = executor(shape, rate)
    server = Server(events)
    clients = Clients(server.url)
    ratios, none_ticks, web_ticks = [], [], []
    try:
        for r in range(rounds):
            order = ("none", "web") if r % 2 == 0 else ("web", "none")
            medians = {}
            for who in order:
                took = paced_ticks(plain if who == "none" else watched, ticks, rate)
                (none_ticks if who == "none" else web_ticks).extend(took)
                medians[who] = statistics.median(took)
            ratios.append(medians["web"] / medians["none"])
        time.sleep(0.2)  # the last batch on its way
    finally:
        counts, delays = clients.close()
        server.close()
    sent = watched.ticks * shape.size
    if min(counts) < sent:
        raise RuntimeError(f"a client received {min(counts)} of {sent} status events")
    percent = (statistics.median(ratios) - 1.0) * 100.0
    none_us, web_us = statistics.median(none_ticks) * 1e6, statistics.median(web_ticks) * 1e6
    goal = f"<= {GOAL_OVERHEAD:g} %" if shape.size <= 10 else None
    note = (f"{shape.label}: {shape.size} status changes per tick at {rate:g} Hz; median tick {web_us:.0f} us with "
            f"the web view and {CLIENTS} WebSocket client processes vs {none_us:.0f} us without ({rounds} "
            f"alternating rounds of {ticks} ticks; every client received all {sent} status events)")
    if goal is None:
        note += "; worst case (every node changes every tick), no goal"
    result = Result(f"{NAME}.tick_overhead.{shape.label}", percent, "%",
                    Anchor("median tick of the same executor and tree with nothing listening (us)", none_us),
                    goal, percent <= GOAL_OVERHEAD if goal else None, note)
    return result, delays, sent


def latency(delays: list[float], rate: float, shape: Shape) -> list[Result]:
    delays_ms = [d * 1000.0 for d in delays]
    p50, p99 = percentile(delays_ms, 50), percentile(delays_ms, 99)
    anchor = Anchor(f"executor tick period at {rate:g} Hz (ms)", 1000.0 / rate)
    note = (f"{len(delays_ms)} status events received by {CLIENTS} WebSocket client processes while {shape.label} "
            f"ticked at {rate:g} Hz; publish (executor thread) to receive (client process)")
    return [Result(f"{NAME}.latency.p50", p50, "ms", anchor, note=note),
            Result(f"{NAME}.latency.p99", p99, "ms", anchor, f"<= {GOAL_LATENCY_P99_MS:g} ms",
                   p99 <= GOAL_LATENCY_P99_MS, note)]


def run(quick: bool = False) -> list[Result]:
    ticks, rounds, rate = (10, 2, 50.0) if quick else (40, 12, 20.0)
    small, large = Shape("flip", 10), Shape("flip", 100)
    overhead_small, delays, _ = measure(small, ticks, rounds, rate)
    overhead_large, _, _ = measure(large, ticks, rounds, rate)
    return [overhead_small, overhead_large, *latency(delays, rate, small)]


def main() -> Any:  # pragma: no cover - python -m bench.web for a look
    for result in run(quick="--full" not in sys.argv):
        print(result.name, f"{result.value:.3f}", result.unit, result.note)


if __name__ == "__main__":  # pragma: no cover
    main()
