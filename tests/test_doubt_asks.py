"""A command in doubt is asked about, never done: "Did you mean: ...?", and only a yes (or "no,
the bathroom") moves the robot. A clear command is never asked about; a stop never waits."""

from __future__ import annotations

from typing import Any

from stuart_bt.mission.executor import MissionExecutor, MissionOptions


def run(*said: str) -> tuple[MissionExecutor, list[Any]]:
    events: list[Any] = []
    with MissionExecutor(MissionOptions(speed=50.0)) as mx:
        mx.events.subscribe(events.append)
        for text in said:
            mx.submit(text)
            assert mx.wait_idle(30)
    return mx, events


def spoken(events: list[Any]) -> list[str]:
    return [e.data["args"]["text"] for e in events if e.kind == "command" and e.data.get("cmd") == "say"]


def moved(events: list[Any]) -> list[Any]:
    return [e for e in events if e.kind == "command" and e.data.get("family") == "loco"
            and e.data.get("cmd") not in ("stop", "shutdown")]


def test_a_command_with_words_it_did_not_understand_is_asked_about_and_waits():
    mx, events = run("Hey Stuart, go to the kitchen in twenty minutes")

    assert spoken(events) == ["Did you mean: go to the kitchen? Say yes or no."]
    [offer] = [e for e in events if e.kind == "proposal"]
    assert offer.data["phase"] == "offered" and "twenty minutes" in " ".join(offer.data["doubt"])
    assert not mx.missions and not moved(events)


def test_yes_does_what_was_asked_about():
    mx, events = run("Hey Stuart, go to the kitchen in twenty minutes", "yes")

    assert [e.data["phase"] for e in events if e.kind == "proposal"] == ["offered", "confirmed"]
    assert mx.missions[0].status == "succeeded" and mx.world.last_marker == "kitchen"


def test_no_leaves_the_robot_where_it_is():
    mx, events = run("Hey Stuart, walk forward minus two metres", "no")

    assert spoken(events)[-1] == "OK, I won't." and not mx.missions and not moved(events)


def test_no_with_another_target_does_that_instead():
    mx, events = run("Hey Stuart, go to the kitchen at half past three", "no, the bathroom")

    assert [e.data["phase"] for e in events if e.kind == "proposal"] == ["offered", "corrected"]
    assert [str(c) for c in mx.missions[0].calls] == ["navigate_to_marker(place=bathroom)"]


def test_a_clear_command_is_never_asked_about():
    mx, events = run("Hey Stuart, please go to the kitchen, mate")

    assert not [e for e in events if e.kind == "proposal"]
    assert mx.missions[0].status == "succeeded"


def test_a_stop_in_a_doubtful_utterance_stops_at_once():
    _, events = run("Hey Stuart, stop, and then go to the kitchen at half past three")

    assert any(e.kind == "utterance" and e.data["kind"] == "stop" for e in events)
    assert [e.data["phase"] for e in events if e.kind == "proposal"] == ["offered"]
    assert not moved(events)


def submit_heard(text: str, heard: dict[str, Any]) -> list[Any]:
    events: list[Any] = []
    with MissionExecutor(MissionOptions(speed=50.0)) as mx:
        mx.events.subscribe(events.append)
        mx.submit(text, source="mic", heard=heard)
        assert mx.wait_idle(30)
    return events


def test_a_command_heard_with_low_confidence_is_asked_about():
    events = submit_heard("Hey Stuart, go to the kitchen", {"confidence": 0.2})

    [offer] = [e for e in events if e.kind == "proposal"]
    assert "not sure I heard you right" in offer.data["doubt"][0] and not moved(events)


def test_a_command_heard_clearly_is_done():
    events = submit_heard("Hey Stuart, go to the kitchen", {"confidence": 0.8})

    assert not [e for e in events if e.kind == "proposal"] and moved(events)


def test_two_readings_asking_for_different_things_are_asked_about():
    events = submit_heard("Hey Stuart, go to the kitchen", {"confidence": 0.8,
                                                           "rival_reading": "Hey Stuart, go to the bathroom"})

    [offer] = [e for e in events if e.kind == "proposal"]
    assert "go to the bathroom" in offer.data["doubt"][0] and not moved(events)


def test_a_stop_heard_with_low_confidence_still_stops():
    events = submit_heard("Hey Stuart, stop", {"confidence": 0.1})

    assert not [e for e in events if e.kind == "proposal"]
    assert any(e.kind == "utterance" and e.data["kind"] == "stop" for e in events)
