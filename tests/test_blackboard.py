"""Blackboard: dotted keys, the world state, references and templates, write events."""

from __future__ import annotations

import pytest

from stuart_bt.core.blackboard import Blackboard, render_template
from stuart_bt.core.clock import ManualClock
from stuart_bt.core.events import EventRecorder, EventStream


def test_dotted_set_creates_nested_dicts_and_get_reads_them():
    bb = Blackboard()
    bb.set("visits.kitchen", 1)
    assert bb.get("visits") == {"kitchen": 1}
    assert bb.get("visits.kitchen") == 1
    assert "visits.bathroom" not in bb
    with pytest.raises(KeyError):
        bb.get("visits.bathroom")


def test_world_state_is_on_the_blackboard_and_writable_by_dotted_key():
    bb = Blackboard()
    bb.set("world.held", "cup")
    assert bb.world.held == "cup"
    assert bb.get("world.holding") is True
    assert bb.snapshot()["world"]["held"] == "cup"


def test_references_and_templates_resolve_at_use():
    bb = Blackboard(initial={"target": "kitchen", "n": 2.5, "names": ["a", "b"]})
    assert bb.resolve("$target") == "kitchen"
    assert bb.resolve("$names") == ["a", "b"]  # whole-value references keep their type
    assert bb.resolve("go to ${target} in ${n} s") == "go to kitchen in 2.5 s"
    assert bb.resolve("costs $$5 at ${target}") == "costs $5 at kitchen"
    assert bb.resolve({"a": ["$n"]}) == {"a": [2.5]}
    assert bb.resolve("no refs here") == "no refs here"
    with pytest.raises(KeyError):
        bb.resolve("$missing")


def test_template_uses_the_lookup_given():
    assert render_template("${a}-${b.c}", {"a": 1, "b.c": 2}.__getitem__) == "1-2"


def test_writes_are_published_on_the_event_stream():
    events = EventStream(ManualClock())
    rec = EventRecorder(events)
    bb = Blackboard(events)
    bb.set("mode", "tour")
    assert [(e.kind, e.data) for e in rec.events] == [("blackboard", {"key": "mode", "value": "tour"})]
