"""Executor: ticking, status events, overruns, stop requests and halting (tick traces)."""

from __future__ import annotations

import threading
import time

import py_trees
from py_trees.common import Status

from stuart_bt.core.clock import ManualClock, ScaledClock
from stuart_bt.core.events import EventRecorder, EventStream
from stuart_bt.run.executor import Executor


class Counter(py_trees.behaviour.Behaviour):
    """RUNNING for ``n`` ticks, then SUCCESS; records terminate calls."""

    def __init__(self, name: str, n: int) -> None:
        super().__init__(name)
        self.n = n
        self.count = 0
        self.terminated: list[Status] = []

    def initialise(self) -> None:
        self.count = 0

    def update(self) -> Status:
        self.count += 1
        return Status.SUCCESS if self.count >= self.n else Status.RUNNING

    def terminate(self, new_status: Status) -> None:
        self.terminated.append(new_status)


class Slow(py_trees.behaviour.Behaviour):
    """Burns clock time on every tick (to provoke overruns)."""

    def __init__(self, clock: ManualClock, cost: float) -> None:
        super().__init__("slow")
        self.clock, self.cost = clock, cost

    def update(self) -> Status:
        self.clock.advance(self.cost)
        return Status.RUNNING


def make(root: py_trees.behaviour.Behaviour, clock=None, rate: float = 20.0):
    clock = clock or ManualClock()
    events = EventStream(clock)
    return Executor(root, clock, events, rate=rate), EventRecorder(events), clock


def test_sequence_runs_to_success_and_publishes_each_status_change_once():
    a, b = Counter("a", 2), Counter("b", 1)
    root = py_trees.composites.Sequence("root", memory=True, children=[a, b])
    executor, rec, clock = make(root)

    outcome = executor.run()

    assert outcome.status == "SUCCESS"
    assert outcome.ticks == 2
    changes = [(e.path, e.data["old"], e.data["new"]) for e in rec.of_kind("status")]
    assert changes == [
        ("root", "INVALID", "RUNNING"), ("a", "INVALID", "RUNNING"),
        ("root", "RUNNING", "SUCCESS"), ("a", "RUNNING", "SUCCESS"), ("b", "INVALID", "SUCCESS"),
    ]
    # tick 1 at t=0, tick 2 one period later: time is on the clock, not the wall
    assert clock.now() == 0.05


def test_spec_path_names_nodes_in_status_events():
    leaf = Counter("walk", 1)
    leaf.spec_path = "tour/station_1/walk"
    executor, rec, _ = make(leaf)
    executor.run()
    assert {e.path for e in rec.of_kind("status")} == {"tour/station_1/walk"}


def test_pre_tick_hooks_run_before_every_tick():
    calls: list[int] = []
    root = Counter("a", 3)
    executor, _, _ = make(root)
    executor.pre_tick.append(lambda: calls.append(root.count))
    executor.run()
    assert calls == [0, 1, 2]  # each hook call sees the state before that tick


def test_stop_request_halts_running_leaves_and_runs_halt_hooks():
    leaf = Counter("forever", 10**9)
    executor, rec, _ = make(leaf)
    halted: list[str] = []
    executor.on_halt.append(lambda: halted.append("daemons stopped"))
    executor.pre_tick.append(lambda: executor.ticks == 3 and executor.request_stop("operator said stop"))

    outcome = executor.run()

    assert outcome.status == "STOPPED"
    assert outcome.reason == "operator said stop"
    assert outcome.ticks == 4  # the request made before tick 4 stops the run before tick 5
    assert leaf.terminated == [Status.INVALID]
    assert halted == ["daemons stopped"]
    assert rec.of_kind("halt")[0].data["reason"] == "operator said stop"
    assert rec.of_kind("status")[-1].data == {"old": "RUNNING", "new": "INVALID"}


def test_max_duration_halts_with_timeout_status():
    leaf = Counter("forever", 10**9)
    executor, _, clock = make(leaf, rate=10.0)
    outcome = executor.run(max_duration=1.0)
    assert outcome.status == "TIMEOUT"
    assert leaf.terminated == [Status.INVALID]
    assert 1.0 <= clock.now() < 1.2


def test_overrun_publishes_rate_limited_warning_and_resynchronises():
    clock = ManualClock()
    slow = Slow(clock, cost=0.12)  # each tick costs 120 ms of a 50 ms period
    executor, rec, _ = make(slow, clock=clock)
    executor.run(max_duration=3.0)
    warnings = rec.of_kind("warning")
    assert executor.overruns >= 20
    assert 2 <= len(warnings) <= 4  # about one per clock second, not one per tick
    assert "tick overrun" in warnings[0].data["message"]


def test_deadlines_do_not_drift_at_real_time():
    root = Counter("a", 11)  # 10 periods of 20 ms
    executor, _, _ = make(root, clock=ScaledClock(1.0), rate=50.0)
    outcome = executor.run()
    # fixed-period deadlines: 10 periods, whatever each tick cost (sleep granularity aside)
    assert 0.19 <= outcome.duration < 0.26


def test_stop_from_another_thread_wakes_the_sleeping_loop():
    leaf = Counter("forever", 10**9)
    executor, _, _ = make(leaf, clock=ScaledClock(1.0), rate=1.0)  # one tick per second
    threading.Timer(0.1, executor.request_stop, args=("from web",)).start()
    t0 = time.monotonic()
    outcome = executor.run()
    assert outcome.status == "STOPPED"
    assert time.monotonic() - t0 < 0.9  # did not sleep out the 1 s period


def test_rate_must_be_positive():
    try:
        make(Counter("a", 1), rate=0)
    except ValueError as e:
        assert "positive" in str(e)
    else:
        raise AssertionError("rate 0 was accepted")
