"""Spatial memory: association, smoothing, decay on the clock, removal, two objects of a class,
queries and the JSON summary."""

from __future__ import annotations

import json

import pytest

from stuart_bt.core.clock import ManualClock
from stuart_bt.perception.memory import MemoryConfig, Observation, SpatialMemory


def bottle(x: float, y: float, confidence: float = 0.9, label: str = "bottle") -> Observation:
    return Observation(label, x, y, 0.85, confidence)


@pytest.fixture
def memory() -> SpatialMemory:
    return SpatialMemory(ManualClock())


def test_first_sighting_is_remembered(memory):
    touched = memory.update([bottle(4.0, 1.4)])
    assert [e.id for e in touched] == ["bottle_1"]
    entry = memory.entries["bottle_1"]
    assert (entry.x, entry.y, entry.confidence, entry.sightings) == (4.0, 1.4, 0.9, 1)


def test_same_label_within_half_a_metre_updates_with_smoothing(memory):
    memory.update([bottle(4.0, 1.4)])
    memory.clock.advance(0.1)
    memory.update([bottle(4.1, 1.4, confidence=0.8)])
    assert list(memory.entries) == ["bottle_1"]
    entry = memory.entries["bottle_1"]
    assert entry.x == pytest.approx(4.0 + 0.3 * 0.1)  # smoothing 0.3 toward the new sighting
    assert entry.confidence == pytest.approx(0.9 + 0.3 * (0.8 - 0.9))
    assert entry.sightings == 2 and entry.last_seen == pytest.approx(0.1)


def test_farther_than_the_radius_or_another_label_is_a_new_entry(memory):
    memory.update([bottle(4.0, 1.4)])
    memory.update([bottle(4.6, 1.4)])  # 0.6 m away
    memory.update([bottle(4.0, 1.45, label="cup")])
    assert sorted(memory.entries) == ["bottle_1", "bottle_2", "cup_1"]


def test_two_bottles_in_one_frame_stay_two_even_within_the_radius(memory):
    memory.update([bottle(4.0, 1.4), bottle(4.0, 1.7)])  # 0.3 m apart
    assert sorted(memory.entries) == ["bottle_1", "bottle_2"]
    memory.update([bottle(4.0, 1.72), bottle(4.02, 1.4)])  # next frame, listed the other way round
    assert len(memory.entries) == 2
    assert memory.entries["bottle_1"].y == pytest.approx(1.4)
    assert memory.entries["bottle_2"].y == pytest.approx(1.7 + 0.3 * 0.02)
    assert all(e.sightings == 2 for e in memory.entries.values())


def test_decay_starts_after_thirty_seconds_and_drops_below_the_floor(memory):
    memory.update([bottle(4.0, 1.4, confidence=0.9)])
    entry = memory.entries["bottle_1"]
    memory.clock.set(30.0)
    assert memory.confidence(entry) == pytest.approx(0.9)
    memory.clock.set(40.0)
    assert memory.confidence(entry) == pytest.approx(0.9 - 0.02 * 10)
    memory.clock.set(30.0 + 0.85 / 0.02 - 0.1)  # just above 0.05
    assert memory.forget() == [] and "bottle_1" in memory.entries
    memory.clock.set(30.0 + 0.85 / 0.02 + 0.1)  # just below
    assert memory.forget() == ["bottle_1"] and memory.entries == {}


def test_seeing_it_again_restarts_the_decay(memory):
    memory.update([bottle(4.0, 1.4, confidence=0.9)])
    memory.clock.set(50.0)
    memory.update([bottle(4.0, 1.4, confidence=0.9)])
    entry = memory.entries["bottle_1"]
    decayed = 0.9 - 0.02 * 20
    assert entry.confidence == pytest.approx(decayed + 0.3 * (0.9 - decayed))
    memory.clock.set(79.0)
    assert memory.confidence(entry) == pytest.approx(entry.confidence)


def test_everything_is_configurable():
    memory = SpatialMemory(ManualClock(), MemoryConfig(match_radius=0.1, smoothing=1.0, decay_after=1.0,
                                                       decay_rate=0.5, drop_below=0.5))
    memory.update([bottle(4.0, 1.4, 0.9)])
    memory.update([bottle(4.05, 1.4, 0.8)])
    assert memory.entries["bottle_1"].x == pytest.approx(4.05)  # smoothing 1: replaced
    memory.update([bottle(4.2, 1.4)])
    assert "bottle_2" in memory.entries  # 0.15 m is beyond a 0.1 m radius
    memory.clock.set(1.9)
    assert memory.forget() == ["bottle_1", "bottle_2"]  # 0.9 - 0.5 * 0.9 < 0.5
    with pytest.raises(ValueError, match="smoothing"):
        MemoryConfig(smoothing=0.0)


def test_removal_and_queries(memory):
    memory.update([bottle(4.0, 1.4), bottle(1.0, -3.0), bottle(4.3, 1.9, label="apple")])
    assert memory.nearest("bottle", 0.9, -2.5).id == "bottle_2"
    assert memory.nearest("bottle", 3.5, 1.5).id == "bottle_1"
    assert memory.nearest("cup", 0.0, 0.0) is None
    near_kitchen = memory.near(3.5, 1.5, radius=1.0)
    assert [e.id for e in near_kitchen] == ["bottle_1", "apple_1"]
    memory.remove("bottle_1")
    assert memory.nearest("bottle", 3.5, 1.5).id == "bottle_2"


def test_summary_is_json(memory):
    memory.update([bottle(4.0, 1.4)])
    memory.clock.set(45.0)
    summary = json.loads(json.dumps(memory.summary()))
    assert summary["format"] == "stuart_bt.memory/1" and summary["frame"] == "map" and summary["t"] == 45.0
    [entry] = summary["objects"]
    assert entry == {"id": "bottle_1", "label": "bottle", "x": 4.0, "y": 1.4, "z": 0.85, "confidence": 0.6,
                     "first_seen": 0.0, "last_seen": 0.0, "sightings": 1}
