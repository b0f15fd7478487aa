"""What the ROS bridge publishes for each event (stuart_bt.ros.topics, no ROS needed), and the two
mission-executor hooks it uses: input that was woken already, and a daemon command sent from the
tick thread (the pick confirmation)."""

from __future__ import annotations

import json

from stuart_bt.core.events import Event
from stuart_bt.mission.commands import MAX_UTTERANCE, clean_utterance
from stuart_bt.mission.executor import MissionExecutor, MissionOptions
from stuart_bt.ros import topics as t


def translated(*events: Event) -> list[t.Outgoing]:
    translator = t.EventTranslator()
    return [out for e in events for out in translator.translate(e) if out.topic != t.EVENTS]


def test_an_utterance_gives_one_task_intent_message_per_intent_in_the_order_said():
    parsed = [{"action": "stop", "target": "", "x": 0.0, "y": 0.0, "yaw": 0.0, "raw_text": "stop"},
              {"action": "navigate_to_marker", "target": "bathroom", "x": 0.0, "y": 0.0, "yaw": 0.0,
               "raw_text": "go to the bathroom"}]
    out = translated(Event(1.0, "utterance", data={"text": "Hey Stuart, stop, go to the bathroom", "kind": "stop",
                                                     "intents": parsed[1:], "parsed": parsed}))
    assert [o.topic for o in out] == [t.TASK_INTENT, t.TASK_INTENT]
    assert [json.loads(o.payload) for o in out] == parsed  # the stop is published too


def test_what_the_robot_says_is_the_response_and_a_social_reply_keeps_its_gesture_tags():
    say = lambda text: Event(2.0, "command", data={"family": "tts", "cmd": "say", "args": {"text": text}})  # noqa: E731
    out = translated(say("Navigating to the kitchen"),
                     Event(3.0, "reply", data={"text": "Hello there!", "gestures": ["high wave"], "to": "hi"}),
                     say("Hello there!"), say("Hello there!"),
                     Event(4.0, "command", data={"family": "gesture", "cmd": "play", "args": {"name": "clap"}}))
    assert [(o.topic, o.payload) for o in out] == [
        (t.RESPONSE, "Navigating to the kitchen"), (t.RESPONSE, "Hello there! [high wave]"),
        (t.RESPONSE, "Hello there!")]  # the tags belong to the reply once, not to a later same sentence


def test_pose_events_become_map_poses_and_every_event_is_a_log_line():
    event = Event(5.0, "pose", data={"x": 3.5, "y": 1.5, "yaw": 0.25}, wall=100.0)
    out = t.EventTranslator().translate(event)
    assert out[0] == t.Outgoing(t.POSE, {"x": 3.5, "y": 1.5, "yaw": 0.25})
    assert out[-1] == t.Outgoing(t.EVENTS, event.to_json())
    assert json.loads(out[-1].payload)["kind"] == "pose"


def test_a_memory_event_from_perception_gives_its_summary_and_markers_of_the_well_formed_objects():
    summary = {"format": "stuart_bt.memory/1", "t": 6.0, "frame": "map", "objects": [
        {"id": "bottle_1", "label": "bottle", "x": 3.9, "y": 1.6, "z": 0.8, "confidence": 0.91, "sightings": 3},
        {"id": "cup_1", "label": "cup", "x": "far"},  # no position: no marker
        {"x": 1.0, "y": 2.0}]}  # no label: no marker
    text, markers = translated(Event(6.0, "memory", "mission/find", summary))
    assert text.topic == t.MEMORY_SUMMARY and json.loads(text.payload) == summary  # the summary as perception made it
    assert markers.topic == t.MEMORY_MARKERS
    placed = [(o["id"], o["label"], o["x"], o["y"], o["z"]) for o in markers.payload]
    assert placed == [("bottle_1", "bottle", 3.9, 1.6, 0.8)]
    assert translated(Event(7.0, "leaf", "mission/go", {"outcome": "SUCCESS"})) == []  # no memory, no summary


def test_input_text_that_is_not_speech_is_refused_and_control_characters_are_blanked():
    assert clean_utterance("  Hey Stuart,\tgo to the kitchen \n") == "Hey Stuart, go to the kitchen"
    assert [clean_utterance(x) for x in ("", "   ", "\x00\x01", "a" * (MAX_UTTERANCE + 1), 7)] == [None] * 5


def test_woken_input_needs_no_wake_phrase_and_a_daemon_request_goes_to_the_running_tree():
    events: list[Event] = []
    asked: list[bool] = []

    def on_event(event: Event) -> None:
        events.append(event)
        if event.kind == "command" and event.data.get("family") == "loco" and not asked:
            asked.append(robot.daemon_request("pick", "ping"))  # while the turn runs

    with MissionExecutor(MissionOptions(backend="dry", speed=20)) as robot:
        robot.events.subscribe(on_event)
        ignored = robot.submit("go to the kitchen")
        woken = robot.submit("turn around", woken=True)
        assert robot.wait_idle(60)
        when_idle = robot.daemon_request("pick", "ping")
    assert (ignored.kind, woken.kind) == ("ignore", "tasks")
    heard = [(e.data["text"], [i["action"] for i in e.data["parsed"]]) for e in events if "parsed" in e.data]
    assert heard == [("go to the kitchen", []), ("turn around", ["turn_around"])]  # not woken: not parsed
    assert asked == [True] and when_idle is False  # nothing is kept for a later tree
    turn = next(i for i, e in enumerate(events) if e.kind == "command" and e.data["family"] == "loco")
    pings = [i for i, e in enumerate(events) if e.kind == "command" and e.data.get("cmd") == "ping"]
    assert len(pings) == 1 and pings[0] > turn  # sent once, before a later tick
    assert any(e.kind == "daemon" and e.data.get("family") == "pick" and e.data.get("type") == "done"
               for e in events[pings[0]:])  # and the pick daemon answered it
