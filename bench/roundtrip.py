"""roundtrip: one command to a daemon and its answer, as a leaf sees it.

Measured: sequential ``ping`` requests to the dry ``tts`` daemon through
``Supervisor.client("tts").request`` + ``Supervisor.wait`` (:mod:`bench.daemon_peer`).
Anchors, measured in the same run:

1. the stdlib floor: a JSON-lines echo child on a pipe (:mod:`bench.pipe_echo`), and the same
   with orjson, the codec stuart_bt's protocol uses, at both ends (information: what is left
   above it is stuart_bt's own machinery);
2. rclpy: a std_msgs/String ping/pong between two nodes with SingleThreadedExecutors, once
   with both nodes in one process and once with the pong node in a second process
   (:mod:`bench.ros_pingpong`, in child processes with the ROS environment).

All four are kept up together and measured in interleaved batches, so each sees the same
machine: on this VM the same pipe round trip varies by 3x from one minute to the next.

Goals, on ratios: stuart_bt's median <= 1.5x the stdlib pipe's (it replaced "<= 100 us", which
a machine with slower Python failed while the ratio held), and <= half the rclpy median. The
rclpy goal is judged against both rclpy set-ups; the same-process one is the faster, hence the
harder, of the two, while the two-process one is the like-for-like comparison (a daemon is
another process).
"""

from __future__ import annotations

import statistics
from typing import Protocol

from .daemon_peer import FAMILY, DaemonPeer
from .pipe_echo import EchoPeer
from .result import Anchor, Goal, Result
from .ros_anchor import DOMAIN_ID, RosPeer, RosUnavailable
from .stats import paired_ratio, percentile

NAME = "roundtrip"
GOAL_STDLIB_RATIO = 1.5
GOAL_ROS_FRACTION = 0.5
WARMUP = 200
ROS_MODES = {"same": "rclpy topic ping/pong, two nodes in one process, one SingleThreadedExecutor",
             "two": "rclpy topic ping/pong, pong node in a second process, one SingleThreadedExecutor each"}


class Peer(Protocol):
    def batch(self, count: int) -> list[float]: ...

    def close(self) -> None: ...


def _us(samples: list[float]) -> tuple[float, float]:
    """(median, p99) in microseconds."""
    return statistics.median(samples) * 1e6, percentile(samples, 99) * 1e6


def start_peers() -> tuple[dict[str, Peer], dict[str, str]]:
    """Every peer that can start (the slow rclpy ones first), and why the others could not."""
    peers: dict[str, Peer] = {}
    missing: dict[str, str] = {}
    try:
        for mode in ROS_MODES:
            try:
                peers[mode] = RosPeer(mode)
            except RosUnavailable as e:
                missing[mode] = str(e)
        peers["stuart_bt"] = DaemonPeer()
        peers["stdlib"] = EchoPeer()
        peers["orjson"] = EchoPeer("orjson")
        for name in ("stuart_bt", "stdlib", "orjson"):
            peers[name].batch(WARMUP)  # the rclpy peers warm up before they report READY
    except BaseException:
        close_peers(peers)
        raise
    return peers, missing


def close_peers(peers: dict[str, Peer]) -> None:
    for peer in peers.values():
        peer.close()


def measure_interleaved(peers: dict[str, Peer], count: int, rounds: int,
                        missing: dict[str, str]) -> dict[str, list[list[float]]]:
    """``count`` samples per peer, in ``rounds`` batches (one list per round), the order rotating
    every round, so that a slow spell of the machine (they come and go here) is shared out
    rather than landing on one peer. An rclpy peer that fails is dropped into ``missing``."""
    batches: dict[str, list[list[float]]] = {name: [] for name in peers}
    names = list(peers)
    per_round = max(1, count // rounds)
    for r in range(rounds):
        for name in names[r % len(names):] + names[: r % len(names)]:
            if name in missing:
                continue
            try:
                batches[name].append(peers[name].batch(per_round))
            except RosUnavailable as e:
                missing[name] = str(e)
    return batches


def median_ratio(batches: dict[str, list[list[float]]], name: str, anchor: str) -> float:
    """stuart_bt's median over the anchor's, round by round (see :func:`bench.stats.paired_ratio`)."""
    return paired_ratio([statistics.median(b) for b in batches[name]], [statistics.median(b) for b in batches[anchor]])


def run(quick: bool = False) -> list[Result]:
    count, rounds = (300, 3) if quick else (6000, 24)
    peers, missing = start_peers()
    try:
        batches = measure_interleaved(peers, count, rounds, missing)
    finally:
        close_peers(peers)
    samples = {name: [x for b in runs for x in b] for name, runs in batches.items()}
    median, p99 = _us(samples["stuart_bt"])
    plain_median, plain_p99 = _us(samples["stdlib"])
    where = (f"{len(samples['stuart_bt'])} sequential pings to the dry {FAMILY} daemon (request + Supervisor.wait), "
             f"{rounds} rounds interleaved with the anchors")
    results = [
        Result(f"{NAME}.stuart_bt.median", median, "us", Anchor("stdlib JSON-lines pipe echo, median", plain_median),
               Goal(GOAL_STDLIB_RATIO, was="<= 100 us"),
               f"{where}; p99 {p99:.1f} us; ratio = median of per-round median ratios",
               paired_ratio=median_ratio(batches, "stuart_bt", "stdlib")),
        Result(f"{NAME}.stuart_bt.p99", p99, "us", Anchor("stdlib JSON-lines pipe echo, p99", plain_p99),
               note=f"{where}; no goal of its own; ratio of the pooled p99s"),
        Result(f"{NAME}.stuart_bt.median_vs_orjson_pipe", median, "us",
               Anchor("the same pipe echo with orjson at both ends, median", _us(samples["orjson"])[0]),
               note=f"{where}; information, no goal: the codec stuart_bt's protocol uses, so the ratio is "
                    "the price of its own machinery alone",
               paired_ratio=median_ratio(batches, "stuart_bt", "orjson")),
    ]
    goal = Goal(GOAL_ROS_FRACTION)
    for mode, label in ROS_MODES.items():
        name = f"{NAME}.stuart_bt.median_vs_rclpy_{mode}_process"
        if mode in missing:
            results.append(Result(name, median, "us", None, goal, f"no rclpy anchor: {missing[mode]}"))
            continue
        ros_median, ros_p99 = _us(samples[mode])
        ratio = median_ratio(batches, "stuart_bt", mode)
        results.append(Result(name, median, "us", Anchor(f"{label}, median", ros_median), goal,
                              f"rclpy: {len(samples[mode])} round trips, p99 {ros_p99:.1f} us; DDS on localhost, "
                              f"domain {DOMAIN_ID}; ratio = median of per-round median ratios",
                              paired_ratio=ratio))
    return results
