"""Events in their flat JSON form (the JSON-lines log, the web socket, the report) keep their own
kind, time and path, whatever keys their data has, and read back the same."""

import json

from stuart_bt.core.events import Event


def test_an_utterance_keeps_its_kind_and_its_data_kind_survives_the_round_trip():
    event = Event(1.5, "utterance", None, {"text": "Hey Stuart, stop", "kind": "stop", "path": "x"}, wall=10.0)
    flat = json.loads(event.to_json())
    assert (flat["kind"], flat["data_kind"], flat["data_path"], flat["t"]) == ("utterance", "stop", "x", 1.5)
    assert "path" not in flat  # the event has none; the data's path did not take its place
    assert Event.from_dict(flat) == event


def test_plain_events_are_flat_and_read_back_unchanged():
    event = Event(0.25, "status", "tour/welcome", {"old": "INVALID", "new": "RUNNING"}, wall=3.0)
    flat = event.to_dict()
    assert flat == {"t": 0.25, "wall": 3.0, "kind": "status", "path": "tour/welcome", "old": "INVALID",
                    "new": "RUNNING"}
    assert Event.from_dict(flat) == event
