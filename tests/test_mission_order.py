"""Commands take effect in the order they were heard, whatever the worker threads are doing.

One dry mission executor (real daemons, fast clock) hears utterances back to back, with no wait
between them, so a "stop" may still be halting the tree when the next words arrive. The property
is checked over sequences hypothesis draws; the worker's timing varies from run to run, the
outcome must not.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from stuart_bt.mission.executor import MissionExecutor, MissionOptions

PLACES = ("kitchen", "bathroom", "entrance")
IDLE = 60.0  # wall seconds for the robot to settle on a loaded machine


@pytest.fixture(scope="module")
def robot() -> Iterator[MissionExecutor]:
    with MissionExecutor(MissionOptions(backend="dry", speed=20.0, max_repairs=0)) as made:
        yield made


def _settle(robot: MissionExecutor) -> None:
    assert robot.wait_idle(IDLE), "the robot did not settle"


def test_stop_then_continue_said_at_once_resumes_the_walk(robot: MissionExecutor):
    _settle(robot)
    robot.submit("Hey Stuart, go to the kitchen")
    robot.submit("Hey Stuart, stop")
    robot.submit("Hey Stuart, continue")
    _settle(robot)
    assert robot.missions[-1].status == "succeeded"
    assert robot.world.last_marker == "kitchen"


def test_stop_then_continue_then_stop_said_at_once_leaves_the_robot_stopped(robot: MissionExecutor):
    _settle(robot)
    robot.submit("Hey Stuart, go to the bathroom")
    robot.submit("Hey Stuart, stop")
    robot.submit("Hey Stuart, continue")
    robot.submit("Hey Stuart, stop")
    _settle(robot)
    assert robot.missions[-1].status in ("stopped", "succeeded")  # it may have arrived before the last stop
    if robot.missions[-1].status == "stopped":
        assert robot.halted is robot.missions[-1]


def _utterance(step: tuple[str, str]) -> str:
    verb, place = step
    return {"go": f"Hey Stuart, go to the {place}", "stop": "Hey Stuart, stop",
            "continue": "Hey Stuart, continue", "wave": "Hey Stuart, wave"}[verb]


STEPS = st.tuples(st.sampled_from(("go", "stop", "continue", "wave")), st.sampled_from(PLACES))


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(prefix=st.lists(STEPS, max_size=5), place=st.sampled_from(PLACES))
def test_whatever_came_before_go_stop_continue_said_at_once_ends_at_the_place(robot, prefix, place):
    """Model: "stop" halts the running mission and drops the queued ones; a "continue" right
    after it resumes the halted one, even while the halt is still under way. So nothing is left
    halted, and the last mission either ends where it was sent, or (queued behind another when
    the stop came) was dropped while the mission the stop halted was resumed and finished."""
    _settle(robot)
    for step in prefix:
        robot.submit(_utterance(step))
    robot.submit(f"Hey Stuart, go to the {place}")
    robot.submit("Hey Stuart, stop")
    robot.submit("Hey Stuart, continue")
    _settle(robot)
    last = robot.missions[-1]
    trace = (prefix, place, [m.to_dict() for m in robot.missions[-3:]])
    assert robot.halted is None, trace
    if last.reason == "stop requested":  # dropped from the queue: the running one was resumed
        resumed = [m for m in robot.missions if m.resumed]
        assert resumed and resumed[-1].status == "succeeded", trace
    else:
        assert last.utterance.endswith(place) and last.status == "succeeded", trace
        assert robot.world.last_marker == place


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(prefix=st.lists(STEPS, max_size=5))
def test_a_stop_said_last_always_wins(robot, prefix):
    _settle(robot)
    for step in prefix:
        robot.submit(_utterance(step))
    robot.submit("Hey Stuart, stop")
    _settle(robot)
    assert all(m.status in ("stopped", "succeeded", "failed") for m in robot.missions), \
        [m.to_dict() for m in robot.missions]
    assert not robot.busy
