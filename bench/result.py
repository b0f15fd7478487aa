"""One reported figure, the anchor it is compared with, and the goal it is judged by.

Every figure carries its anchor (or ``None`` with a note saying why there is none) so that
bench/results.json can be read without the code: value, anchor, ratio, goal and verdict travel
together.

Two kinds of goal. A :class:`Goal` is judged on the **ratio** to the anchor: every goal on a time
or a speed is one, since a machine that runs Python 3.5x slower moves the figure and an anchor
timed in the same run alike, and leaves their ratio where it was. The absolute goal a ratio goal
replaced is kept (``was``) as information, like the absolute figure itself. A :class:`Bound` is
judged on the **value**, for what a machine's speed cannot move: an accuracy, an error in metres,
a count of processes left behind.
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

_OPS: dict[str, Callable[[float, float], bool]] = {"<=": operator.le, "<": operator.lt, ">=": operator.ge,
                                                   "==": operator.eq}


@dataclass(frozen=True)
class Anchor:
    """What a figure is compared with. ``timed``: measured in the same run (a baseline on this
    machine now); otherwise a constant (a tolerance, a protocol period, a figure from elsewhere)."""

    name: str
    value: float
    timed: bool = True


@dataclass(frozen=True)
class Goal:
    """``ratio <op> limit``. ``was``: the absolute goal it replaced (information), set so that the
    two agreed on the machine that wrote bench/results.json."""

    limit: float
    op: str = "<="
    was: str | None = None

    def __post_init__(self) -> None:
        if self.op not in _OPS:
            raise ValueError(f"goal operator {self.op!r} is not one of {', '.join(_OPS)}")

    judged_on = "ratio"

    @property
    def text(self) -> str:
        return f"ratio {self.op} {self.limit:g}"

    def met(self, value: float, ratio: float | None) -> bool | None:
        return None if ratio is None else _OPS[self.op](ratio, self.limit)


@dataclass(frozen=True)
class Bound:
    """``value <op> limit`` in the figure's unit, for a quantity the machine's speed cannot move."""

    limit: float
    op: str = "<="
    unit: str = ""

    def __post_init__(self) -> None:
        if self.op not in _OPS:
            raise ValueError(f"bound operator {self.op!r} is not one of {', '.join(_OPS)}")

    judged_on = "value"
    was = None

    @property
    def text(self) -> str:
        return f"{self.op} {self.limit:g}{' ' + self.unit if self.unit else ''}"

    def met(self, value: float, ratio: float | None) -> bool | None:
        return _OPS[self.op](value, self.limit)


@dataclass(frozen=True)
class Result:
    """A figure. ``ratio`` is value / anchor value unless ``paired_ratio`` gives a better
    estimate (the median of per-round ratios, see :func:`bench.stats.paired_ratio`); ``met`` is
    ``None`` when there is no goal or nothing to judge it by (never a guess)."""

    name: str
    value: float
    unit: str
    anchor: Anchor | None
    goal: Goal | Bound | None = None
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
    def met(self) -> bool | None:
        """The goal judged on the figures as written (rounded to 4 decimals), so that a report
        never says a ratio of 1.05 missed a goal of <= 1.05 (the unrounded 1.050004 did)."""
        if self.goal is None:
            return None
        ratio = self.ratio
        return self.goal.met(round(self.value, 4), None if ratio is None else round(ratio, 4))

    @property
    def benchmark(self) -> str:
        return self.name.split(".", 1)[0]

    @property
    def figure(self) -> str:
        return self.name.split(".", 1)[-1]

    def to_dict(self) -> dict[str, Any]:
        ratio = self.ratio
        goal = self.goal
        return {
            "name": self.name,
            "value": round(self.value, 4),
            "unit": self.unit,
            "anchor": None if self.anchor is None else {"name": self.anchor.name, "value": round(self.anchor.value, 4),
                                                        "timed": self.anchor.timed},
            "ratio": None if ratio is None else round(ratio, 4),
            "goal": None if goal is None else goal.text,
            "judged_on": None if goal is None else goal.judged_on,
            "was": None if goal is None else goal.was,
            "met": self.met,
            "note": self.note,
        }
