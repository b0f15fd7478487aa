"""Anchor 2 of roundtrip: a ROS 2 topic round trip with rclpy, run in its own process.

Started by :mod:`bench.ros_anchor` with the environment rclpy needs (library path, DDS kept on
this machine); never imported by the benchmark process itself, so DDS threads cannot disturb
the other measurements.

``python bench/ros_pingpong.py same TAG``: two nodes in this process, one
SingleThreadedExecutor spinning both; the ping node publishes a std_msgs/String on
``bench_ping_TAG``, the pong node's callback republishes it on ``bench_pong_TAG``, the ping node
spins until it is back.

``python bench/ros_pingpong.py two TAG``: the same, but the pong node runs in a child process
(``pong TAG``) with its own SingleThreadedExecutor, like a daemon in another process.

Both print ``READY`` once connected, then answer each stdin line holding a count N with one line
``{"samples": [seconds, ...]}`` of N round trips, so the parent can interleave these batches
with its other measurements. End of input ends the process.

The topic names carry a per-run tag so that two benchmark runs at once never answer each other.
"""

from __future__ import annotations

import gc
import json
import os
import subprocess
import sys
import threading
import time
from typing import Any

os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")  # before rclpy loads DDS
os.environ.setdefault("ROS_DOMAIN_ID", "87")

import rclpy
from rclpy.executors import SingleThreadedExecutor
from std_msgs.msg import String

WARMUP = 200  # answered pings before READY
MATCH_TIMEOUT = 20.0  # seconds for discovery on loopback (normally well under one)


def make_pong(tag: str) -> Any:
    """A node that republishes every ping as a pong."""
    node = rclpy.create_node(f"bench_pong_{tag}")
    publisher = node.create_publisher(String, f"bench_pong_{tag}", 10)
    node.create_subscription(String, f"bench_ping_{tag}", publisher.publish, 10)
    return node


class Pinger:
    """The measuring side: publish, then spin until the matching pong has arrived."""

    def __init__(self, tag: str, executor: SingleThreadedExecutor) -> None:
        self.node = rclpy.create_node(f"bench_ping_{tag}")
        self.publisher = self.node.create_publisher(String, f"bench_ping_{tag}", 10)
        self.node.create_subscription(String, f"bench_pong_{tag}", self._on_pong, 10)
        self.executor = executor
        self.executor.add_node(self.node)
        self.last = ""
        self.pong_topic = f"bench_pong_{tag}"

    def _on_pong(self, msg: String) -> None:
        self.last = msg.data

    def wait_for_match(self) -> None:
        deadline = time.monotonic() + MATCH_TIMEOUT
        while self.publisher.get_subscription_count() < 1 or self.node.count_publishers(self.pong_topic) < 1:
            if time.monotonic() > deadline:
                raise TimeoutError("the ping and pong nodes did not discover each other")
            self.executor.spin_once(timeout_sec=0.05)

    def round_trip(self, text: str, timeout: float) -> float | None:
        """Seconds for one ping -> pong, or None if the pong did not come back in ``timeout``."""
        msg = String()
        msg.data = text
        start = time.perf_counter()
        self.publisher.publish(msg)
        while self.last != text:
            self.executor.spin_once(timeout_sec=timeout)
            if self.last != text and time.perf_counter() - start > timeout:
                return None
        return time.perf_counter() - start


def connect(pinger: Pinger) -> None:
    """Wait for discovery, then for answered pings (the first may leave before the link is up)."""
    pinger.wait_for_match()
    answered = attempt = 0
    while answered < WARMUP:
        attempt += 1
        if attempt > WARMUP + 200:
            raise TimeoutError("pings go unanswered after discovery")
        if pinger.round_trip(f"hello{attempt}", 0.5) is not None:
            answered += 1


def batch(pinger: Pinger, count: int, first: int) -> list[float]:
    """Round-trip seconds of ``count`` sequential pings, collector paused."""
    samples: list[float] = []
    gc.collect()
    gc.disable()
    try:
        for i in range(first, first + count):
            took = pinger.round_trip(str(i), 5.0)
            if took is None:
                raise TimeoutError(f"ping {i} got no pong within 5 s")
            samples.append(took)
    finally:
        gc.enable()
    return samples


def serve_batches(pinger: Pinger) -> None:
    """READY, then one JSON line of samples per request line (a count) until end of input."""
    connect(pinger)
    print("READY", flush=True)
    done = 0
    for line in sys.stdin:
        count = int(line)
        print(json.dumps({"samples": batch(pinger, count, done)}), flush=True)
        done += count


def serve_pong(tag: str) -> None:
    """The second process of ``two`` mode: answer pings until end of input."""
    executor = SingleThreadedExecutor()
    executor.add_node(make_pong(tag))
    finished = threading.Event()
    threading.Thread(target=lambda: (sys.stdin.read(), finished.set()), daemon=True).start()
    while not finished.is_set():
        executor.spin_once(timeout_sec=0.1)


def main(argv: list[str]) -> int:
    mode, tag = argv
    rclpy.init()
    try:
        if mode == "pong":
            serve_pong(tag)
        elif mode == "same":
            executor = SingleThreadedExecutor()
            executor.add_node(make_pong(tag))
            serve_batches(Pinger(tag, executor))
        else:
            run_two(tag)
        return 0
    finally:
        rclpy.try_shutdown()


def run_two(tag: str) -> None:
    child = subprocess.Popen([sys.executable, __file__, "pong", tag], stdin=subprocess.PIPE)
    try:
        serve_batches(Pinger(tag, SingleThreadedExecutor()))
    finally:
        assert child.stdin is not None
        child.stdin.close()  # the pong process exits at end of input
        try:
            child.wait(timeout=10)
        except subprocess.TimeoutExpired:
            child.kill()
            child.wait()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
