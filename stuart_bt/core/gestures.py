"""The G1 gesture library: names people use, mapped to the arm service's action ids.

Ids are the vendor's ``G1ArmActionClient.ExecuteAction`` ids (see ../shared/FIELD_NOTES.md).
Canonical names are lower-case words separated by spaces ("high five"); lookups also accept
underscores and hyphens, and a few aliases people say ("wave" plays the high wave).
Durations are typical playing times in seconds; the dry backend uses them and the sim replays
keyframes of about that length.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Gesture:
    name: str
    action_id: int
    duration: float
    holds: bool = False  # the pose is held until "release arm" (id 99)


LIBRARY: dict[str, Gesture] = {
    g.name: g
    for g in (
        Gesture("release arm", 99, 1.5),
        Gesture("two hand kiss", 11, 4.0),
        Gesture("left kiss", 12, 3.5),
        Gesture("right kiss", 13, 3.5),
        Gesture("hands up", 15, 3.0, holds=True),
        Gesture("clap", 17, 3.0),
        Gesture("high five", 18, 3.0, holds=True),
        Gesture("hug", 19, 4.0, holds=True),
        Gesture("heart", 20, 3.5, holds=True),
        Gesture("right heart", 21, 3.5, holds=True),
        Gesture("reject", 22, 3.0),
        Gesture("right hand up", 23, 3.0, holds=True),
        Gesture("x-ray", 24, 3.5),
        Gesture("face wave", 25, 3.0),
        Gesture("high wave", 26, 3.5),
        Gesture("shake hand", 27, 4.0, holds=True),
    )
}

ALIASES: dict[str, str] = {
    "wave": "high wave",
    "hello": "high wave",
    "kiss": "two hand kiss",
    "handshake": "shake hand",
    "shake hands": "shake hand",
    "xray": "x-ray",
    "release": "release arm",
}


def normalise(name: str) -> str:
    return " ".join(name.strip().lower().replace("_", " ").split())


def lookup(name: str) -> Gesture | None:
    """The gesture called ``name`` (any spelling the library accepts, or its vendor action id
    such as ``"26"``), or ``None``."""
    key = normalise(name)
    if key.isdigit():
        return next((g for g in LIBRARY.values() if g.action_id == int(key)), None)
    if key in LIBRARY:
        return LIBRARY[key]
    if key in ALIASES:
        return LIBRARY[ALIASES[key]]
    key = key.replace("-", " ")
    for g in LIBRARY.values():
        if g.name.replace("-", " ") == key:
            return g
    return None


def names() -> list[str]:
    """Every accepted name, canonical ones first (for suggestions and the schema)."""
    return [*LIBRARY, *ALIASES]
