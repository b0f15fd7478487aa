"""What the conversation is told the robot sees: the objects perception placed in the world state.

The mission executor answers "what do you see" from the world state's known objects that came
from the camera (``source == "vision"``) and were seen within ``recent`` seconds of clock time,
each with its distance from the robot and the nearest marker, in the shape
:func:`stuart_bt.conversation.prompt.vision_text` reads. Objects only known from the catalogue
(skills/objects.json) are not *seen*, so they are never claimed.
"""

from __future__ import annotations

import math
from typing import Any

from ..core.world import WorldState

RECENT = 60.0  # s: older sightings are memories, not what the robot sees now
NEAR_MARKER = 1.5  # m


def seen_objects(world: WorldState, now: float, recent: float = RECENT) -> list[dict[str, Any]]:
    """``[{"label", "distance", "where"}]`` nearest first."""
    out = []
    for o in world.objects.values():
        if o.source != "vision" or now - o.seen_at > recent:
            continue
        distance = math.hypot(o.x - world.pose.x, o.y - world.pose.y)
        entry: dict[str, Any] = {"label": o.label, "distance": round(distance, 2)}
        near = [(math.hypot(o.x - m.x, o.y - m.y), m) for m in world.markers.values()]
        if near:
            gap, marker = min(near, key=lambda pair: pair[0])
            if gap <= NEAR_MARKER:
                entry["where"] = f"near the {marker.name.replace('_', ' ')}"
        out.append(entry)
    return sorted(out, key=lambda e: e["distance"])
