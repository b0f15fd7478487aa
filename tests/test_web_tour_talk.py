"""Talking to the tree ``stuart-bt serve TREE`` runs, through the console's API, as the page does:
a question is answered from facts and the tour goes on; "stop" holds it with nothing moving
until "continue", and it finishes. Events are read from the page's own socket (``/ws``)."""

from __future__ import annotations

import pytest

from web_support import EventFeed, Served, call

pytest.importorskip("starlette", reason="the web view needs the web extra (make test installs it)")
pytest.importorskip("websockets", reason="the event socket client needs websockets (the web extra)")

pytestmark = pytest.mark.slow
QUESTION = "Hey Stuart, what happens in the drone cage?"


def is_run(phase: str):
    return lambda e: e["kind"] == "run" and e.get("phase") == phase and e.get("label") == "run"


def test_a_question_typed_during_the_served_tour_is_answered_and_stop_holds_it_until_continue():
    with Served("trees/lab_tour.yaml", "--backend", "dry", "--speed", "20") as served, EventFeed(served) as feed:
        feed.wait_for(is_run("start"))
        asked = call(served, "POST", "/api/say", {"text": QUESTION})
        reply = feed.wait_for(lambda e: e["kind"] == "reply")
        answered = feed.wait_for(lambda e: e["kind"] == "resume")  # the tour goes on after the answer

        stopped = call(served, "POST", "/api/say", {"text": "Hey Stuart, stop"})
        hold = feed.wait_for(lambda e: e["kind"] == "hold" and e["reason"].startswith("stop said"))
        state = call(served, "GET", "/api/state")
        went_on = call(served, "POST", "/api/say", {"text": "Hey Stuart, continue"})
        end = feed.wait_for(is_run("end"))
        events = list(feed.events)

    assert asked == (200, {"ok": True, "kind": "conversation", "intents": []})
    assert reply["source"] == "facts" and "netted cage" in reply["text"]
    assert reply["to"] == "what happens in the drone cage?"
    spoken = [e["args"]["text"] for e in events if e["kind"] == "command" and e.get("path") == "reply"]
    assert spoken == [reply["text"]]
    assert stopped[0] == 200 and stopped[1]["kind"] == "stop"
    assert state == (200, {"mode": "tree", "busy": True, "running": "run", "held": hold["reason"],
                           "can_continue": True})
    assert went_on[0] == 200 and went_on[1]["kind"] == "continue"
    assert end["status"] == "SUCCESS"
    assert [e["reason"] for e in events if e["kind"] == "hold"] == ["answering a question", hold["reason"]]
    resumes = [e["t"] for e in events if e["kind"] == "resume"]
    assert len(resumes) == 2 and resumes[0] == answered["t"] < hold["t"] < resumes[1] < end["t"]
    sent_while_held = [e["cmd"] for e in events if e["kind"] == "command" and hold["t"] <= e["t"] < resumes[1]]
    assert set(sent_while_held) <= {"stop", "cancel"} and "stop" in sent_while_held  # nothing that moves
    finished = {e["path"] for e in events if e["kind"] == "status" and e["new"] == "SUCCESS"}
    assert {f"tour/station_{i}" for i in range(1, 7)} <= finished


def test_continue_pressed_on_the_page_lets_a_tree_held_by_a_spoken_stop_go_on():
    with Served("trees/lab_tour.yaml", "--backend", "dry", "--speed", "40", "--no-wake") as served, \
            EventFeed(served) as feed:
        feed.wait_for(is_run("start"))
        call(served, "POST", "/api/say", {"text": "stop"})  # --no-wake: no "Hey Stuart" needed
        feed.wait_for(lambda e: e["kind"] == "hold")
        pressed = call(served, "POST", "/api/continue")
        feed.wait_for(lambda e: e["kind"] == "resume")
        end = feed.wait_for(is_run("end"))
        heard = [(e["text"], e["data_kind"], e["source"]) for e in feed.of("utterance")]

    assert pressed == (200, {"ok": True})
    assert heard == [("stop", "stop", "web"), ("Hey Stuart, continue", "continue", "web")]
    assert end["status"] == "SUCCESS"


def test_a_stop_said_as_run_is_pressed_waits_for_the_tree_and_holds_it():
    """Run reserves the tree at once (the page says busy) and builds it on the worker; what is
    said in between is for that tree, not refused ("nothing is running to talk to")."""
    with Served("trees/lab_tour.yaml", "--backend", "dry", "--speed", "10", "--paused") as served, \
            EventFeed(served) as feed:
        ran = call(served, "POST", "/api/run", {})
        stopped = call(served, "POST", "/api/say", {"text": "Hey Stuart, stop"})  # no wait for the start
        hold = feed.wait_for(lambda e: e["kind"] == "hold")
    assert ran[0] == 200
    assert stopped[0] == 200 and stopped[1]["kind"] == "stop", stopped
    assert hold["reason"].startswith("stop said")
