"""The hub between the event stream and the browsers: a late client gets the snapshot and the
history, then every later event exactly once (events from other threads too), and bye when the
server stops; blackboard values are sent as they were when written; an utterance keeps its event
kind on the wire."""

from __future__ import annotations

import asyncio
import json
import threading

import pytest

pytest.importorskip("starlette", reason="the web view needs the web extra")

from stuart_bt.core.clock import ManualClock
from stuart_bt.core.events import EventStream
from stuart_bt.web.hub import EventHub

TREE = {"file": "t.yaml", "description": None,
        "root": {"path": "root", "name": "root", "kind": "sequence", "category": "composite", "params": {},
                 "children": [{"path": "root/a", "name": "a", "kind": "wait", "category": "leaf",
                               "params": {"seconds": 1}, "children": []}]}}


async def drain(queue: asyncio.Queue, until: float = 0.1) -> list[dict]:
    """Messages until the queue's end mark (None) or ``until`` seconds of quiet."""
    out = []
    try:
        while (text := await asyncio.wait_for(queue.get(), until)) is not None:
            out.append(json.loads(text))
    except TimeoutError:
        pass
    return out


def test_a_late_client_gets_history_then_each_later_event_once():
    events = EventStream(ManualClock())
    hub = EventHub(events, info={"mode": "tree"})
    events.publish("tree", **TREE)  # before the server runs: kept for the hello

    async def scenario() -> tuple[dict, list[dict]]:
        hub.attach(asyncio.get_running_loop())
        events.publish("status", "root", old="INVALID", new="RUNNING")
        publisher = threading.Thread(target=lambda: events.publish("status", "root/a", old="INVALID", new="RUNNING"))
        publisher.start()
        publisher.join()
        client, hello = hub.connect()  # the two status events are still pending here
        events.publish("status", "root/a", old="RUNNING", new="SUCCESS")
        batches = await drain(client.queue)
        hub.close()  # the server stops: the socket says bye and its sender ends
        return json.loads(hello), batches + await drain(client.queue)

    hello, batches = asyncio.run(scenario())
    assert [e["kind"] for e in hello["events"]] == ["tree", "status", "status"]
    assert hello["snapshot"]["format"] == "stuart_bt.snapshot/1"
    assert hello["snapshot"]["running"] == ["root", "root/a"]
    later = [e for b in batches if b["type"] == "events" for e in b["events"]]
    assert [(e["path"], e["new"]) for e in later] == [("root/a", "SUCCESS")]
    assert batches[-1]["type"] == "bye"


def test_a_blackboard_value_is_sent_as_it_was_when_written():
    events = EventStream(ManualClock())
    hub = EventHub(events)
    visits = {"kitchen": 1}
    events.publish("blackboard", key="visits", value=visits)
    visits["bathroom"] = 2  # changed in place after the write
    _, hello = asyncio.run(_hello(hub))
    assert json.loads(hello)["events"][0]["value"] == {"kitchen": 1}


def test_an_utterance_keeps_its_kind_and_its_command_kind_arrives_as_data_kind():
    events = EventStream(ManualClock())
    hub = EventHub(events)
    events.publish("utterance", text="Hey Stuart, stop", kind="stop", replace=False, intents=[])
    _, hello = asyncio.run(_hello(hub))
    event = json.loads(hello)["events"][0]
    assert (event["kind"], event["data_kind"], event["text"]) == ("utterance", "stop", "Hey Stuart, stop")


async def _hello(hub: EventHub) -> tuple[object, str]:
    hub.attach(asyncio.get_running_loop())
    client, hello = hub.connect()
    hub.close()
    return client, hello
