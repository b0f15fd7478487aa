"""The measured side of roundtrip: ``ping`` through stuart_bt's Supervisor to a dry daemon.

Everything a leaf's command pays is inside the timed window: building the Request, the
``command`` event, encoding, the pipe, the daemon's selector loop and dispatch, the reply
parse, the ``daemon`` event, and the supervisor's wait. Only the daemon family the benchmark
needs is started, on the dry backend, with a wall clock (a daemon cannot share a manual one).
"""

from __future__ import annotations

import tempfile
import time

from stuart_bt.core.clock import WallClock
from stuart_bt.core.events import EventStream
from stuart_bt.daemon.supervisor import Supervisor

from .sink import EventCounter
from .stats import gc_paused

FAMILY = "tts"
WAIT_TIMEOUT = 5.0  # seconds; a ping that takes this long is a failure, not a sample


class DaemonPeer:
    """One Supervisor with one dry daemon, kept up across batches."""

    def __init__(self, family: str = FAMILY) -> None:
        self.family = family
        self.clock = WallClock()
        self.events = EventStream(self.clock)
        self.counter = EventCounter()  # one subscriber, as in a run (the report builder)
        self.events.subscribe(self.counter)
        self._run_dir = tempfile.TemporaryDirectory(prefix="stuart_bt-bench-")  # daemon stderr logs
        self.supervisor = Supervisor("dry", self.clock, self.events, families=[family], run_dir=self._run_dir.name)
        try:
            self.supervisor.start()
        except BaseException:
            self._run_dir.cleanup()
            raise
        self.client = self.supervisor.client(family)

    def batch(self, count: int) -> list[float]:
        """Round-trip seconds of ``count`` sequential pings, collector paused."""
        samples: list[float] = []
        client, supervisor = self.client, self.supervisor
        with gc_paused():
            for _ in range(count):
                start = time.perf_counter()
                request = client.request("ping", {})
                supervisor.wait(request, WAIT_TIMEOUT)
                samples.append(time.perf_counter() - start)
                if not request.ok:
                    raise RuntimeError(f"ping failed: {request!r}")
        return samples

    def close(self) -> None:
        self.supervisor.shutdown()
        self._run_dir.cleanup()
