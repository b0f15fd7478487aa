"""The fault matrix's rows for the processes that host the missions themselves: the web server
(``stuart-bt serve --mission``) and the ROS bridge (``stuart-bt ros``), each frozen and killed
mid-walk (issue 12; docs/running.md lists every row).

Frozen for 5 s (SIGSTOP), the process sends its daemons no keep-alive, so the loco daemon's
watchdog stops the walk by itself; when the process wakes, the mission is held, the robot says
why, nothing moves until "continue", and "continue" carries on. Killed (SIGKILL), its daemons see
their stdin close, stop the robot and exit: nothing is left running. Times are printed (``-s``);
the assertions hold only generous bounds.
"""

from __future__ import annotations

import http.client
import json
import os
import signal
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from ros_harness import BridgeProcess, RosClient, alive, descendants
from stuart_bt.mission.executor import WATCHDOG_SENTENCE
from web_support import Served

pytestmark = pytest.mark.slow
FREEZE_S = 5.0  # wall seconds the host process is stopped: more than the daemons' 2 s watchdog
WALK = "go to the bathroom"  # ~18 s at real time from the entrance: long enough to freeze mid-way
Event = dict[str, Any]


def wait_until(found: Callable[[], Any], timeout: float, what: str) -> Any:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = found()
        if value:
            return value
        time.sleep(0.05)
    raise AssertionError(f"timed out after {timeout:g} s waiting for {what}")


def log_events(path: Path) -> list[Event]:
    """The events of a ``--log`` file so far (a line still being written is left for later)."""
    if not path.exists():
        return []
    out: list[Event] = []
    for line in path.read_text(encoding="utf-8").splitlines():
        try:
            out.append(json.loads(line))
        except ValueError:
            break
    return out


def watchdog_hold(events: list[Event]) -> Event | None:
    return next((e for e in events if e["kind"] == "mission" and e.get("phase") == "stopped"
                 and str(e.get("reason", "")).startswith("watchdog:")), None)


def said(events: list[Event], text: str) -> bool:
    return any(e["kind"] == "command" and e.get("cmd") == "say" and e["args"].get("text") == text for e in events)


def poses_after(events: list[Event], wall: float) -> list[tuple[float, float]]:
    return [(e["x"], e["y"]) for e in events if e["kind"] == "pose" and e["wall"] > wall]


def walked(events: list[Event], beyond: float = 0.3) -> bool:
    return any(e["kind"] == "pose" and abs(e["x"]) + abs(e["y"]) > beyond for e in events)


def freeze(pid: int) -> float:
    """Stop the process for FREEZE_S and wake it; the wall time it woke."""
    os.kill(pid, signal.SIGSTOP)
    time.sleep(FREEZE_S)
    os.kill(pid, signal.SIGCONT)
    return time.time()


def kill_and_time_the_orphans(pid: int) -> float:
    """SIGKILL ``pid`` alone; wall seconds until every process below it has exited."""
    children = descendants(pid)
    assert children, "the host process had no daemons"
    os.kill(pid, signal.SIGKILL)
    killed = time.monotonic()
    wait_until(lambda: not [c for c in children if alive(c)], 20, f"the daemons {children} to exit")
    return time.monotonic() - killed


def call(served: Served, path: str, body: dict[str, Any] | None = None) -> tuple[int, dict[str, Any]]:
    """POST ``body`` to ``path`` (GET without one); the status and the JSON answer."""
    conn = http.client.HTTPConnection("127.0.0.1", served.port, timeout=30)
    try:
        conn.request("POST" if body is not None else "GET", path, body=json.dumps(body) if body is not None else None,
                     headers={"Content-Type": "application/json"})
        response = conn.getresponse()
        return response.status, json.loads(response.read())
    finally:
        conn.close()


def test_a_web_server_frozen_mid_walk_leaves_a_stopped_robot_that_waits_for_continue_and_a_kill_leaves_nothing(
        tmp_path):
    log = tmp_path / "serve.jsonl"
    with Served("--mission", "--no-wake", "--log", str(log)) as served:
        assert call(served, "/api/say", {"text": WALK})[0] == 200
        wait_until(lambda: walked(log_events(log)), 60, "the walk to start")
        woke = freeze(served.proc.pid)
        hold = wait_until(lambda: watchdog_hold(log_events(log)), 30, "the mission to be held")
        wait_until(lambda: said(log_events(log), WATCHDOG_SENTENCE), 30, "the robot to say why it stopped")
        status, state = call(served, "/api/state")
        time.sleep(1.0)  # a second awake and held: nothing may move
        still = set(poses_after(log_events(log), hold["wall"]))
        assert call(served, "/api/continue", {})[0] == 200
        moved_on = wait_until(lambda: set(poses_after(log_events(log), hold["wall"])) - still, 30,
                              "the walk to carry on after continue")
        gone_in = kill_and_time_the_orphans(served.proc.pid)
        served.proc.wait(10)

    print(f"\nweb server frozen {FREEZE_S:g} s: held {hold['wall'] - woke:+.2f} s from waking; "
          f"killed: daemons gone in {gone_in:.2f} s")
    assert status == 200 and state["can_continue"] is True
    assert len(still) <= 1, f"the robot moved while held: {sorted(still)}"
    assert moved_on
    assert gone_in < 10


def test_a_ros_bridge_frozen_mid_walk_leaves_a_stopped_robot_that_waits_for_continue_and_a_kill_leaves_nothing():
    pytest.importorskip("rclpy", reason="the ros extra (real rclpy) is not installed: pip install -e '.[ros]'")
    with BridgeProcess("--backend", "dry") as bridge:  # real time: the walk takes seconds
        bridge.up()
        with RosClient() as client:
            client.publish("stuart/mission", WALK)

            def events() -> list[Event]:
                return [json.loads(m["data"]) for m in client.on("/bt/events")]

            wait_until(lambda: walked(events()), 60, "the walk to start")
            woke = freeze(bridge.proc.pid)
            hold = wait_until(lambda: watchdog_hold(events()), 30, "the mission to be held")
            wait_until(lambda: said(events(), WATCHDOG_SENTENCE), 30, "the robot to say why it stopped")
            time.sleep(1.0)
            still = set(poses_after(events(), hold["wall"]))
            client.publish("stuart/mission", "continue")
            moved_on = wait_until(lambda: set(poses_after(events(), hold["wall"])) - still, 30,
                                  "the walk to carry on after continue")
            gone_in = kill_and_time_the_orphans(bridge.proc.pid)
            bridge.proc.wait(10)

    print(f"\nROS bridge frozen {FREEZE_S:g} s: held {hold['wall'] - woke:+.2f} s from waking; "
          f"killed: daemons gone in {gone_in:.2f} s")
    assert len(still) <= 1, f"the robot moved while held: {sorted(still)}"
    assert moved_on
    assert gone_in < 10
