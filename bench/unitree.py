"""unitree: how fast a lost tree stops the robot, and how steadily a walk is commanded.

The loco daemon runs with the unitree backend against the fake G1 (tests/fakes/unitree_services.py,
DDS on loopback, a private domain), started directly as a subprocess with pipes, as the
supervisor does. Each round starts a body-relative walk, waits for its first velocity command,
then closes the daemon's stdin: exactly what the kernel does when the tree process dies. The fake
stamps every request it receives on the machine's monotonic clock, which the benchmark shares.

- ``stop_after_tree_loss``: from the stdin close to the fake receiving the zero-velocity
  command. Goal: within one heartbeat period (0.1 s), the issue's acceptance bound.
- ``command_gap``: the gaps between consecutive velocity commands while walking. Goal: below
  the command duration (0.3 s), so the robot never coasts to a halt between two commands.

No timed anchor: there is no other implementation of the same stop path to run. These are
deadlines, so each figure's anchor is the protocol constant its deadline is (the heartbeat
period, the command duration) and the goal is on the ratio to it, the same bound as before.
"""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
import time
from itertools import pairwise
from pathlib import Path

from .result import Anchor, Goal, Result
from .stats import percentile

NAME = "unitree"
HEARTBEAT_MS = 100.0
COMMAND_DURATION_MS = 300.0
HARNESS = Path(__file__).resolve().parents[1] / "tests" / "unitree_fake.py"


def _fake_module():
    spec = importlib.util.spec_from_file_location("unitree_fake", HARNESS)
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("unitree_fake", module)
    spec.loader.exec_module(module)
    return module


def _one_round(robot, gaps: list[float]) -> float:
    """Start a walk, cut the daemon's stdin; milliseconds until the fake heard the stop."""
    options = json.dumps(robot.options())
    daemon = subprocess.Popen([sys.executable, "-m", "stuart_bt.skills.loco", "--backend", "unitree", "--options",
                               options], stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    try:
        assert daemon.stdin is not None and daemon.stdout is not None
        ready = json.loads(daemon.stdout.readline() or "{}")
        if ready.get("type") != "ready":
            raise RuntimeError("unitree benchmark: the loco daemon did not start against the fake robot")
        before, mark = len(robot.rpc("sport", 7105)), len(robot.records)
        daemon.stdin.write(b'{"id":"w","cmd":"navigate","args":{"relative":{"dx":20.0}}}\n')
        daemon.stdin.flush()
        robot.wait_for(lambda r: r.get("api") == 7105 and any(r["parameter"]["velocity"]), 10, "a velocity command",
                       since=mark)
        time.sleep(0.5)  # a steady stream of commands first
        mark = len(robot.records)
        closed = time.monotonic()
        daemon.stdin.close()
        stop = robot.wait_for(lambda r: r.get("api") == 7105 and not any(r["parameter"]["velocity"]), 10, "the stop",
                              since=mark)
        moving = [r["t"] for r in robot.rpc("sport", 7105)[before:] if any(r["parameter"]["velocity"])]
        gaps += [(b - a) * 1000 for a, b in pairwise(moving)]
        daemon.wait(timeout=10)
        return (stop["t"] - closed) * 1000
    finally:
        if daemon.poll() is None:
            daemon.kill()
            daemon.wait()


def run(quick: bool) -> list[Result]:
    fake = _fake_module()
    rounds = 1 if quick else 15
    stops: list[float] = []
    gaps: list[float] = []
    with fake.FakeRobot() as robot:
        for _ in range(rounds):
            stops.append(_one_round(robot, gaps))
    stop_p99, gap_p99 = percentile(stops, 99), percentile(gaps, 99)
    note = (f"{rounds} walks against the fake G1 on loopback; stdin closed as by a dead tree process; "
            "the anchor is the protocol's bound (a constant): no other stop path to time")
    heartbeat = Anchor("heartbeat period (the protocol's bound)", HEARTBEAT_MS, timed=False)
    return [
        Result(f"{NAME}.stop_after_tree_loss.p50", percentile(stops, 50), "ms", heartbeat, note=note),
        Result(f"{NAME}.stop_after_tree_loss.p99", stop_p99, "ms", heartbeat,
               goal=Goal(1.0, was=f"<= {HEARTBEAT_MS:g} ms"), note=note),
        Result(f"{NAME}.command_gap.p99", gap_p99, "ms",
               Anchor("command duration (the robot coasts to a halt after it)", COMMAND_DURATION_MS, timed=False),
               goal=Goal(1.0, "<", was=f"< {COMMAND_DURATION_MS:g} ms"), note=note),
    ]
