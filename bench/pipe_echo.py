"""Anchor 1 of roundtrip: request/reply over a pipe to :mod:`bench.echo_child`.

The parent side mirrors the child: encode a request line, write, flush, block on the reply
line, decode it. Both ends are plain stdlib, so this is the cost of two processes, two pipes and
two JSON round trips on this machine at this moment. ``codec="orjson"`` makes both ends use the
codec stuart_bt's protocol uses: the same floor for a design with that codec (information).
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from .stats import gc_paused

CHILD = Path(__file__).with_name("echo_child.py")  # run by path: no package import in the child


class EchoPeer:
    """One echo child process, kept alive across batches so batches can interleave with others."""

    def __init__(self, codec: str = "json") -> None:
        flags = ["--orjson"] if codec == "orjson" else []
        self._child = subprocess.Popen([sys.executable, str(CHILD), *flags], stdin=subprocess.PIPE,
                                       stdout=subprocess.PIPE)
        assert self._child.stdin is not None and self._child.stdout is not None
        self._send, self._receive = self._child.stdin, self._child.stdout
        self._next = 0
        if codec == "orjson":
            import orjson

            self._dumps: Callable[[Any], bytes] = lambda m: orjson.dumps(m, option=orjson.OPT_APPEND_NEWLINE)
            self._loads: Callable[[bytes], Any] = orjson.loads
        else:
            self._dumps = lambda m: json.dumps(m, separators=(",", ":")).encode() + b"\n"
            self._loads = json.loads

    def batch(self, count: int) -> list[float]:
        """Round-trip seconds of ``count`` sequential requests, collector paused."""
        samples: list[float] = []
        send, receive, dumps, loads = self._send, self._receive, self._dumps, self._loads
        with gc_paused():
            for _ in range(count):
                self._next += 1
                request_id = str(self._next)
                start = time.perf_counter()
                send.write(dumps({"id": request_id, "cmd": "ping", "args": {}}))
                send.flush()
                reply = loads(receive.readline())
                samples.append(time.perf_counter() - start)
                if reply.get("id") != request_id:
                    raise RuntimeError(f"echo child answered {reply!r} to request {request_id}")
        return samples

    def close(self) -> None:
        self._send.close()  # the child exits at end of input
        try:
            self._child.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self._child.kill()
            self._child.wait()
        self._receive.close()
