"""Whole runs with a misbehaving loco daemon: the leaf fails promptly with the daemon's fault as
its reason, the run ends with a report (no traceback), and bad numbers never become the pose."""

from __future__ import annotations

import sys
import time
from pathlib import Path

import pytest

from stuart_bt.core.world import Pose, PoseError
from stuart_bt.daemon.supervisor import Supervisor
from stuart_bt.testing import run_tree

FAULTY = Path(__file__).parent / "fakes" / "faulty_daemon.py"


@pytest.fixture
def faulty_loco(monkeypatch):
    """Every supervisor of the test runs ``faulty_daemon.py FAULT`` as its loco daemon."""

    def use(fault: str) -> None:
        real_argv = Supervisor._argv

        def argv(self: Supervisor, family: str) -> list[str]:
            if family == "loco":
                self.programs["loco"] = [sys.executable, str(FAULTY), fault]
            return real_argv(self, family)

        monkeypatch.setattr(Supervisor, "_argv", argv)

    return use


def test_a_walk_to_a_daemon_that_never_answers_fails_within_the_heartbeat_not_the_leaf_timeout(faulty_loco):
    faulty_loco("mute")
    started = time.monotonic()
    result = run_tree(text="root: {navigate: {name: go, marker: kitchen}}")
    took = time.monotonic() - started
    assert result.status == "FAILURE"
    assert result.failure("go") == ("daemon_hung: loco daemon did not answer r1 (navigate) within 1.0 s "
                                    "though it still heartbeats")
    assert took < 30.0  # the navigate leaf's own timeout is 60 s; detection is the heartbeat timeout
    print(f"\nFAULT-MATRIX run with a mute loco daemon: leaf failed after {took:.2f} s (whole run incl. start-up)")


def test_bad_numbers_from_the_daemon_fail_the_leaf_and_never_become_the_pose(faulty_loco):
    faulty_loco("bad_numbers")
    result = run_tree(text="root: {navigate: {name: go, marker: kitchen}}")
    assert result.status == "FAILURE"
    assert result.failure("go").startswith("backend_error: loco daemon sent a malformed reply to r1: done:")
    result.assert_final_pose(0.0, 0.0)


@pytest.mark.parametrize("data, says", [
    ({"x": "abc", "y": 0}, "pose 'x' must be a finite number, got 'abc'"),
    ({"x": float("nan"), "y": 0}, "pose 'x' must be a finite number, got nan"),
    ({"x": 0, "y": float("inf")}, "pose 'y' must be a finite number, got inf"),
    ({"x": 0, "y": 0, "yaw": True}, "pose 'yaw' must be a finite number, got True"),
    ({"x": 10 ** 400, "y": 0}, "pose 'x' must be a finite number"),
    ([1, 2, 3], "a pose must be an object with x, y and yaw, got list"),
])
def test_pose_from_dict_refuses_what_is_not_three_finite_numbers(data, says):
    with pytest.raises(PoseError) as caught:
        Pose.from_dict(data)
    assert says in str(caught.value)


def test_pose_from_dict_takes_absent_or_null_axes_as_zero():
    assert Pose.from_dict({"x": 1, "y": 2.5}) == Pose(1.0, 2.5, 0.0)
    assert Pose.from_dict({"x": 1, "y": 2, "yaw": None}) == Pose(1.0, 2.0, 0.0)


class _DoneRequest:
    """A request the daemon already finished with ``result`` (a double for the client's handle)."""

    def __init__(self, result: dict) -> None:
        self.id, self.status, self.result, self.error_code, self.reason = "r1", "done", result, None, None
        self.finished = True


class _Daemons:
    """A daemon port whose one client answers every command with the same done result, as a
    daemon on an older framework (no schema check) could."""

    def __init__(self, result: dict) -> None:
        self.connected = True
        self._result = result

    def client(self, family: str) -> _Daemons:
        return self

    def request(self, cmd: str, args: dict, path: str | None = None) -> _DoneRequest:
        return _DoneRequest(self._result)

    def cancel(self, request: object) -> None:
        return None

    def stop_all(self) -> list:
        return []


def test_a_leaf_whose_result_the_world_cannot_take_fails_with_bad_result():
    from py_trees.common import Status

    from stuart_bt.core.blackboard import Blackboard
    from stuart_bt.core.clock import ScaledClock
    from stuart_bt.core.events import EventStream
    from stuart_bt.leaves.base import RunContext
    from stuart_bt.leaves.motion import Turn
    from stuart_bt.tree.spec import Location, NodeSpec

    clock = ScaledClock(1)
    events = EventStream(clock)
    blackboard = Blackboard(events)
    before = Pose(blackboard.world.pose.x, blackboard.world.pose.y, blackboard.world.pose.yaw)
    ctx = RunContext(clock, events, blackboard, _Daemons({"pose": {"x": "abc", "y": 0, "yaw": 0}}), Path("."))
    leaf = Turn(NodeSpec("turn", "spin", "root/spin", Location("t.yaml", 1, 1), {"angle": 0.5}), ctx)
    leaf.initialise()
    assert leaf.update() == Status.FAILURE
    assert leaf.failure_reason == ("bad_result: loco daemon's result for r1 is unusable: "
                                   "pose 'x' must be a finite number, got 'abc'")
    assert blackboard.world.pose == before
