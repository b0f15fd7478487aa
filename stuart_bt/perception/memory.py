"""Spatial memory: where things were seen, in the map frame, fading when not seen again.

The original system's rules, all configurable and all on the shared clock (so a sim running at
50x real time decays at 50x too): an observation of a label within ``match_radius`` (0.5 m) of a
remembered object of that label updates it with exponential smoothing; after ``decay_after``
(30 s) unseen its confidence falls by ``decay_rate`` (0.02) per second; under ``drop_below``
(0.05) it is forgotten. Unlike the original, association happens per frame and each remembered
object takes at most one observation from a frame, so two bottles seen side by side stay two.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from ..core.clock import Clock

FORMAT = "stuart_bt.memory/1"


@dataclass(frozen=True)
class MemoryConfig:
    match_radius: float = 0.5  # m
    smoothing: float = 0.3  # weight of a new observation (0: ignore it, 1: replace)
    decay_after: float = 30.0  # s unseen before confidence starts falling
    decay_rate: float = 0.02  # confidence per second
    drop_below: float = 0.05

    def __post_init__(self) -> None:
        if not 0.0 < self.smoothing <= 1.0:
            raise ValueError(f"memory smoothing must be in (0, 1], got {self.smoothing}")
        if self.match_radius <= 0 or self.decay_after < 0 or self.decay_rate < 0 or self.drop_below < 0:
            raise ValueError("memory radius must be positive; decay times and rates not negative")


@dataclass
class Observation:
    """One detection placed in the map frame."""

    label: str
    x: float
    y: float
    z: float
    confidence: float


@dataclass
class Remembered:
    id: str
    label: str
    x: float
    y: float
    z: float
    confidence: float  # at last_seen; see SpatialMemory.confidence for now
    first_seen: float
    last_seen: float
    sightings: int = 1

    def distance_to(self, x: float, y: float, z: float | None = None) -> float:
        dz = 0.0 if z is None else z - self.z
        return math.sqrt((self.x - x) ** 2 + (self.y - y) ** 2 + dz * dz)


@dataclass
class SpatialMemory:
    clock: Clock
    config: MemoryConfig = field(default_factory=MemoryConfig)
    entries: dict[str, Remembered] = field(default_factory=dict)
    _counts: dict[str, int] = field(default_factory=dict)

    def confidence(self, entry: Remembered, now: float | None = None) -> float:
        now = self.clock.now() if now is None else now
        unseen = now - entry.last_seen - self.config.decay_after
        return entry.confidence - self.config.decay_rate * max(0.0, unseen)

    def update(self, observations: Iterable[Observation], now: float | None = None) -> list[Remembered]:
        """Take one frame's observations; returns the entries they touched (new or updated)."""
        now = self.clock.now() if now is None else now
        self.forget(now)
        pending = list(observations)
        pairs = sorted(
            ((e.distance_to(o.x, o.y, o.z), i, e.id) for i, o in enumerate(pending) for e in self.entries.values()
             if e.label == o.label and e.distance_to(o.x, o.y, o.z) <= self.config.match_radius),
        )
        taken_obs: set[int] = set()
        taken_entries: set[str] = set()
        touched: list[Remembered] = []
        for _, i, entry_id in pairs:  # closest pairs first, each side used once
            if i in taken_obs or entry_id in taken_entries:
                continue
            taken_obs.add(i)
            taken_entries.add(entry_id)
            touched.append(self._merge(self.entries[entry_id], pending[i], now))
        for i, obs in enumerate(pending):
            if i not in taken_obs:
                touched.append(self._add(obs, now))
        return touched

    def _merge(self, entry: Remembered, obs: Observation, now: float) -> Remembered:
        a = self.config.smoothing
        entry.x += a * (obs.x - entry.x)
        entry.y += a * (obs.y - entry.y)
        entry.z += a * (obs.z - entry.z)
        entry.confidence = self.confidence(entry, now) + a * (obs.confidence - self.confidence(entry, now))
        entry.last_seen = now
        entry.sightings += 1
        return entry

    def _add(self, obs: Observation, now: float) -> Remembered:
        n = self._counts.get(obs.label, 0) + 1
        self._counts[obs.label] = n
        entry = Remembered(f"{obs.label}_{n}", obs.label, obs.x, obs.y, obs.z, obs.confidence, now, now)
        self.entries[entry.id] = entry
        return entry

    def forget(self, now: float | None = None) -> list[str]:
        """Drop entries whose confidence fell under the floor; returns their ids."""
        now = self.clock.now() if now is None else now
        gone = [k for k, e in self.entries.items() if self.confidence(e, now) < self.config.drop_below]
        for k in gone:
            del self.entries[k]
        return gone

    def remove(self, entry_id: str) -> None:
        """Forget one entry now (it was picked up, or looked for where it should be and not seen)."""
        self.entries.pop(entry_id, None)

    # -- queries -----------------------------------------------------------------------------
    def nearest(self, label: str, x: float, y: float) -> Remembered | None:
        """The remembered ``label`` closest (horizontally) to (x, y), or None."""
        self.forget()
        found = [e for e in self.entries.values() if e.label == label]
        return min(found, key=lambda e: e.distance_to(x, y)) if found else None

    def near(self, x: float, y: float, radius: float = 1.5) -> list[Remembered]:
        """Everything remembered within ``radius`` (horizontally) of (x, y), nearest first."""
        self.forget()
        found = [e for e in self.entries.values() if e.distance_to(x, y) <= radius]
        return sorted(found, key=lambda e: e.distance_to(x, y))

    def summary(self, now: float | None = None) -> dict[str, Any]:
        """The JSON summary the ``memory`` event carries (docs/perception.md)."""
        now = self.clock.now() if now is None else now
        self.forget(now)
        return {
            "format": FORMAT,
            "t": round(now, 3),
            "frame": "map",
            "objects": [
                {"id": e.id, "label": e.label, "x": round(e.x, 4), "y": round(e.y, 4), "z": round(e.z, 4),
                 "confidence": round(self.confidence(e, now), 3), "first_seen": round(e.first_seen, 3),
                 "last_seen": round(e.last_seen, 3), "sightings": e.sightings}
                for e in sorted(self.entries.values(), key=lambda e: e.id)
            ],
        }
