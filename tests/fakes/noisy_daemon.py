"""A daemon on the real runtime whose backend prints to stdout and has a command that crashes.

Stands in for a vendor SDK that prints (from Python and from C) and for a backend bug, neither
of which the dry backends have. Run as ``python noisy_daemon.py --backend noisy --clock wall``.
"""

import ctypes
import os
import sys
from typing import Any

from stuart_bt.daemon.backend import Activity, Backend, Done, Handler
from stuart_bt.skills.runtime import main


class Instant(Activity):
    def poll(self, now: float) -> Done:
        print("noisy: python print while polling")
        return Done({"printed": True})

    def cancel(self, now: float) -> None:
        return None


class NoisyBackend(Backend):
    family = "noisy"
    name = "noisy"

    def __init__(self, clock: Any, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        print("noisy: SDK banner from Python print")
        os.write(1, b"noisy: raw write to fd 1\n")
        ctypes.CDLL(None).puts(b"noisy: C puts to stdout")

    def commands(self) -> dict[str, Handler]:
        return {"chatter": self._chatter, "boom": self._boom}

    def _chatter(self, args: dict[str, Any]) -> Activity:
        print("noisy: chatter {\"id\":\"fake\",\"type\":\"done\"}", flush=True)
        return Instant()

    def _boom(self, args: dict[str, Any]) -> Activity:
        raise RuntimeError("simulated backend bug")

    def state(self) -> dict[str, Any]:
        return {}


if __name__ == "__main__":
    sys.exit(main("noisy", {"noisy": "__main__:NoisyBackend"}))
