"""The one event subscriber the benchmarks attach.

A run always has at least one subscriber (the report builder), so publishing is measured with
one; counting what arrives also lets a benchmark say how many events it caused.
"""

from __future__ import annotations

from stuart_bt.core.events import Event


class EventCounter:
    """Counts events; as cheap as a subscriber can be."""

    def __init__(self) -> None:
        self.count = 0

    def __call__(self, event: Event) -> None:
        self.count += 1
