"""ros: how long a ROS 2 client waits for its TaskIntent, across processes.

``stuart-bt ros --backend dry`` runs in one process; tests/ros_client.py (a plain rclpy program)
in another publishes "Hey Stuart, go to the kitchen" (then "... bathroom", alternately) on
``/audio_msg`` and times, on its own monotonic clock, the gap from just before ``publish`` to
the arrival of the intent on ``/llm/task_intent``. Inside: DDS delivery to the bridge, its
subscription callback, the wake filter and grammar in ``submit``, the ``utterance`` event queued
to the ROS thread, the guard condition waking it, translation and DDS delivery back. After each
sample "Hey Stuart, stop" (not timed) halts the walk it started, so the robot stays near home.

Anchor: the **plain rclpy round trip between two processes** (bench.ros_anchor, the roundtrip
benchmark's peer) measured in the same run: the DDS cost any bridge pays twice, so the ratio says
what the bridge adds on top of the transport.
"""

from __future__ import annotations

import importlib.util
import json
import statistics
import sys
import time
from pathlib import Path

from .result import Anchor, Goal, Result
from .ros_anchor import RosPeer, RosUnavailable, missing
from .stats import percentile

NAME = "ros"
GOAL_P99_MS = 20.0  # the absolute goal the ratio goal replaces (information)
# p99 over the plain rclpy round trip timed in the same run: 20 ms over that round trip on the
# machine that wrote bench/results.json (0.3177 ms), rounded down.
GOAL_P99 = Goal(62, was=f"<= {GOAL_P99_MS:g} ms")
PLACES = ("kitchen", "bathroom")
HARNESS = Path(__file__).resolve().parents[1] / "tests" / "ros_harness.py"


def _harness():
    """tests/ros_harness.py (the same bridge and client processes the tests drive)."""
    spec = importlib.util.spec_from_file_location("ros_harness", HARNESS)
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("ros_harness", module)
    spec.loader.exec_module(module)
    return module


def run(quick: bool) -> list[Result]:
    reason = missing()
    if reason:
        raise RosUnavailable(reason)
    reps = 8 if quick else 200
    h = _harness()
    latencies: list[float] = []
    with h.BridgeProcess("--backend", "dry", "--speed", "20") as bridge:
        peer = RosPeer("two")  # starts while the bridge's daemons come up
        try:
            bridge.up()
            with h.RosClient() as client:
                for i in range(reps):
                    latencies.append(_sample(client, PLACES[i % 2]))
            peer.batch(10 if quick else 20)  # warm-up
            anchor_ms = statistics.median(peer.batch(30 if quick else 300)) * 1000
        finally:
            peer.close()
    anchor = Anchor("rclpy String round trip, two processes, median", anchor_ms)
    note = f"{reps} utterances, dry backend; client-side clock; anchor measured right after in the same run"
    return [Result(f"{NAME}.audio_to_intent.p50", percentile(latencies, 50), "ms", anchor, note=note),
            Result(f"{NAME}.audio_to_intent.p99", percentile(latencies, 99), "ms", anchor,
                   goal=GOAL_P99, note=note)]


def _sample(client, place: str) -> float:
    """One utterance: milliseconds from publish to the intent, then "stop" (untimed) so the robot
    stays near home."""
    since = client.mark
    sent = client.publish("audio_msg", f"Hey Stuart, go to the {place}")
    got = client.wait_for(lambda m: m.get("topic") == "/llm/task_intent", 30, since)
    if got is None or json.loads(got["data"]).get("target") != place:
        raise RuntimeError(f"ros benchmark: no intent for the {place} within 30 s")
    since = client.mark
    client.publish("audio_msg", "Hey Stuart, stop")
    client.wait_for(lambda m: m.get("topic") == "/llm/task_intent", 30, since)
    time.sleep(0.05)  # let the halt settle: the next sample starts from a quiet bridge
    return (got["t"] - sent) * 1000
