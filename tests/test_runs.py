"""Whole runs on the dry backend: the tour, preemption, stop requests, crashed daemons."""

from __future__ import annotations

import math
import os
import signal
import time

from stuart_bt.run.session import Session
from stuart_bt.testing import run_tree


def test_lab_tour_visits_six_stations_in_order_speaking_while_gesturing():
    result = run_tree("trees/lab_tour.yaml", speed=60)
    result.assert_success()
    result.assert_no_failures()
    assert result.report["visited"] == [f"station_{i}" for i in range(1, 7)]
    result.assert_final_pose(2.0, 2.5, math.pi)
    for i in range(1, 7):
        present = f"tour/station_{i}/present/"
        (speech,) = [s for s in result.report["spoken"] if s["path"].startswith(present)]
        (gesture,) = [g for g in result.report["gestures"] if g["path"].startswith(present)]
        assert speech["start"] < gesture["end"] and gesture["start"] < speech["end"], f"station_{i} did not overlap"
    result.assert_said("Thank you for visiting")


def test_timeout_decorator_preempts_the_walk_and_cancels_it_in_the_daemon():
    result = run_tree(text="root: {timeout: {name: hurry, seconds: 2, "
                           "child: {navigate: {name: go, marker: bathroom}}}}")
    assert result.status == "FAILURE"
    (cancel,) = [e for e in result.events("command") if e["cmd"] == "cancel"]
    assert cancel["path"] == "hurry/go"
    (cancelled,) = [e for e in result.events("daemon") if e.get("code") == "cancelled"]
    assert cancelled["path"] == "hurry/go"
    pose = result.report["final_pose"]
    assert 0.2 < math.hypot(pose["x"], pose["y"]) < 2.0  # stopped where it was after ~2 s


def test_guard_that_stops_holding_preempts_its_child():
    result = run_tree(text="""
blackboard: {abort: false}
root:
  parallel:
    children:
      - guard: {name: unless_aborted, condition: "not abort", child: {navigate: {name: go, marker: bathroom}}}
      - sequence: [{wait: 1}, {set: {key: abort, value: true}}]
""")
    assert result.status == "FAILURE"
    assert [e["path"] for e in result.events("command") if e["cmd"] == "cancel"] == ["root/unless_aborted/go"]


def test_higher_priority_branch_preempts_a_running_lower_one_in_a_reactive_selector():
    result = run_tree(text="""
blackboard: {visitor: false}
root:
  parallel:
    policy: one
    children:
      - selector:
          name: behaviour
          children:
            - sequence:
                name: greet
                children: [{condition: visitor}, {speak: "Hello visitor!"}]
            - navigate: {name: patrol, marker: bathroom}
      - sequence: [{wait: 1.5}, {set: {key: visitor, value: true}}, {wait: 5}]
""")
    cancels = [e["path"] for e in result.events("command") if e["cmd"] == "cancel"]
    assert cancels == ["root/behaviour/patrol"]
    result.assert_said("Hello visitor!")


def test_stop_request_halts_the_run_and_every_daemon_receives_stop():
    def stop_after_two_seconds(session: Session) -> None:
        if session.clock.now() > 2.0:
            session.request_stop("operator pressed stop")

    result = run_tree("trees/lab_tour.yaml", speed=20, on_tick=stop_after_two_seconds)
    assert result.status == "STOPPED"
    assert result.report["reason"] == "operator pressed stop"
    stopped = {e["family"] for e in result.events("command") if e["cmd"] == "stop"}
    assert stopped == {"loco", "tts", "gesture"}
    acks = {e["family"] for e in result.events("daemon") if e["type"] == "done" and e["id"] in
            {c["id"] for c in result.events("command") if c["cmd"] == "stop"}}
    assert acks == stopped  # every daemon acknowledged before the run ended


def test_killed_daemon_fails_the_running_leaf_at_once_and_comes_back():
    killed: dict[str, float] = {}

    def kill_loco_mid_walk(session: Session) -> None:
        assert session.supervisor is not None
        client = session.supervisor.client("loco")
        walking = any(r.cmd == "navigate" for r in client.in_flight)
        if walking and not killed and session.clock.now() > 1.0:
            killed["wall"] = time.time()
            os.kill(session.supervisor.pid("loco"), signal.SIGKILL)

    result = run_tree(text="""
root:
  selector:
    memory: true    # do not re-try the failed walk every tick
    children:
      - navigate: {name: far, marker: bathroom}
      - sequence:
          name: recover
          children:
            - speak: "My legs stopped for a moment. Going to the kitchen instead."
            - navigate: {name: near, marker: kitchen}
""", speed=5, on_tick=kill_loco_mid_walk)

    assert killed, "the walk never started"
    reason = result.failure("root/far")
    assert reason is not None and reason.startswith("daemon_died:") and "SIGKILL" in reason
    died = next(e for e in result.events("daemon") if e.get("code") == "daemon_died")
    assert died["wall"] - killed["wall"] < 0.1  # noticed within 100 ms
    states = [e["state"] for e in result.events("daemon_state") if e["family"] == "loco"]
    assert states[:3] == ["starting", "ready", "died"] and states.count("ready") == 2
    result.assert_success()  # the restarted daemon took the second walk
    result.assert_visited("kitchen")
