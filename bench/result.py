"""One reported figure and the anchor it is judged against.

Every figure carries its anchor (or ``None`` with a note saying why there is none) so that
bench/results.json can be read without the code: value, anchor, ratio, goal and verdict travel
together.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Anchor:
    """What a figure is compared with, measured in the same run."""

    name: str
    value: float


@dataclass(frozen=True)
class Result:
    """A figure. ``ratio`` is value / anchor value unless ``paired_ratio`` gives a better
    estimate (the median of per-round ratios, see :func:`bench.stats.paired_ratio`); ``met`` is
    ``None`` when there is no goal or nothing to judge it against (never a guess)."""

    name: str
    value: float
    unit: str
    anchor: Anchor | None
    goal: str | None = None
    met: bool | None = None
    note: str = ""
    paired_ratio: float | None = None

    @property
    def ratio(self) -> float | None:
        if self.anchor is None:
            return None
        if self.paired_ratio is not None:
            return self.paired_ratio
        if self.anchor.value == 0:
            return None
        return self.value / self.anchor.value

    @property
    def benchmark(self) -> str:
        return self.name.split(".", 1)[0]

    @property
    def figure(self) -> str:
        return self.name.split(".", 1)[-1]

    def to_dict(self) -> dict[str, Any]:
        ratio = self.ratio
        return {
            "name": self.name,
            "value": round(self.value, 4),
            "unit": self.unit,
            "anchor": None if self.anchor is None else {"name": self.anchor.name, "value": round(self.anchor.value, 4)},
            "ratio": None if ratio is None else round(ratio, 4),
            "goal": self.goal,
            "met": self.met,
            "note": self.note,
        }
