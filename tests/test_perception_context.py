"""'What do you see' gets what the camera placed in the world state, recent sightings only,
never objects merely listed in the catalogue."""

from __future__ import annotations

from stuart_bt.conversation import build_messages
from stuart_bt.core.world import KnownObject, Marker, Pose, WorldState
from stuart_bt.perception.context import seen_objects


def lab() -> WorldState:
    world = WorldState(pose=Pose(3.5, 1.5, 0.0), markers={"kitchen": Marker("kitchen", 3.5, 1.5)})
    world.objects = {
        "bottle": KnownObject("bottle", 4.01, 1.38, 0.855, 0.9, seen_at=100.0, source="vision"),
        "apple": KnownObject("apple", 4.35, 1.85, 0.79, 0.95, seen_at=10.0, source="vision"),  # long ago
        "cup": KnownObject("cup", 0.85, -3.0, 0.9),  # from skills/objects.json: never seen
    }
    return world


def test_only_recent_camera_sightings_are_seen_with_distance_and_place():
    assert seen_objects(lab(), now=105.0) == [{"label": "bottle", "distance": 0.52, "where": "near the kitchen"}]
    assert [o["label"] for o in seen_objects(lab(), now=65.0, recent=60.0)] == ["bottle", "apple"]
    assert seen_objects(lab(), now=500.0) == []


def test_the_vision_question_carries_them_into_the_prompt():
    messages = build_messages("Stuart, what do you see?", {"detections": seen_objects(lab(), now=105.0)})
    assert "You currently see: bottle (0.5 m away, near the kitchen)." in messages[-1]["content"]
    nothing = build_messages("what do you see", {"detections": seen_objects(lab(), now=900.0)})
    assert "nothing in particular" in nothing[-1]["content"]
