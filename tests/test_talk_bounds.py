"""A flood of talk cannot keep a command waiting: the robot answers a couple of questions at a
time, lets the rest go with a warning, and drops replies nobody is waiting for any more."""

from __future__ import annotations

import time

from stuart_bt.core.events import Event
from stuart_bt.mission.executor import SESSION_HISTORY, MissionExecutor, MissionOptions
from stuart_bt.mission.queue import MAX_QUEUED_REPLIES, STALE_REPLY_S, Say
from stuart_bt.mission.replies import MAX_PENDING_REPLIES


def test_fifty_questions_at_once_leave_at_most_a_few_replies_before_the_next_command_walks():
    events: list[Event] = []
    with MissionExecutor(MissionOptions(backend="dry", speed=20.0)) as robot:
        robot.events.subscribe(events.append)
        for k in range(50):
            robot.submit(f"Hey Stuart, how are you doing today, number {k}?")
        robot.submit("Hey Stuart, go to the kitchen")
        assert robot.wait_idle(60.0)
        walk = next(i for i, e in enumerate(events) if e.kind == "command" and e.data.get("family") == "loco"
                    and e.data.get("cmd") == "navigate")
        spoken_before = [e for e in events[:walk] if e.kind == "command" and e.data.get("family") == "tts"
                         and e.data.get("cmd") == "say"]
        assert len(spoken_before) <= MAX_PENDING_REPLIES + MAX_QUEUED_REPLIES + 1  # + the mission's ack
        warnings = [e for e in events if e.kind == "warning" and "too much talk" in e.data.get("message", "")]
        assert warnings, "the talk that went unanswered is counted in a warning"
        assert len(warnings) <= 3, "at most one such warning a second"
        assert robot.missions[-1].status == "succeeded"


def test_a_reply_that_waited_too_long_is_dropped_unsaid():
    events: list[Event] = []
    with MissionExecutor(MissionOptions(backend="dry", speed=20.0)) as robot:
        robot.events.subscribe(events.append)
        stale = Say("an answer to a question asked long ago", "reply")
        stale.made = time.monotonic() - STALE_REPLY_S - 1.0
        with robot.jobs.cond:
            robot.jobs.queue.append(stale)
            robot.jobs.cond.notify_all()
        assert robot.wait_idle(30.0)
        said = [e.data["args"]["text"] for e in events if e.kind == "command" and e.data.get("cmd") == "say"]
        assert stale.text not in said
        assert any(e.kind == "log" and "dropped unsaid" in e.data.get("message", "") for e in events)


def test_a_long_mission_session_keeps_a_bounded_event_history():
    from stuart_bt.core.clock import ManualClock
    from stuart_bt.core.events import EventRecorder, EventStream

    stream = EventStream(ManualClock())
    recorder = EventRecorder(stream, limit=100)
    for k in range(1000):
        stream.publish("log", message=f"line {k}")
    assert len(recorder.events) == 100 and recorder.events[-1].data["message"] == "line 999"
    with MissionExecutor(MissionOptions(backend="dry", speed=20.0)) as robot:
        assert robot.session.recorder.events.maxlen == SESSION_HISTORY
