"""Timing helpers: garbage collection off inside timing windows, medians of several runs.

The machine is a shared 2-core VM whose speed changes from one second to the next, so a single
long run is at the mercy of whatever else happens. Many short runs, interleaved between the
candidates being compared, and ratios taken between runs that sat side by side in time, keep a
slow spell from landing on one candidate only.
"""

from __future__ import annotations

import gc
import math
import statistics
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager


@contextmanager
def gc_paused() -> Iterator[None]:
    """Keep the cyclic collector out of a timing window (it would charge its pause to whoever
    happened to allocate last)."""
    was_enabled = gc.isenabled()
    gc.collect()
    gc.disable()
    try:
        yield
    finally:
        if was_enabled:
            gc.enable()


def percentile(samples: Sequence[float], q: float) -> float:
    """The ``q``-th percentile (0..100) by the nearest-rank method: always an observed sample."""
    if not samples:
        raise ValueError("no samples")
    ordered = sorted(samples)
    rank = max(1, min(len(ordered), math.ceil(q / 100.0 * len(ordered))))
    return ordered[rank - 1]


def time_calls(fn: Callable[[], object], reps: int) -> float:
    """Seconds per call of ``fn`` over ``reps`` calls, collector paused."""
    with gc_paused():
        start = time.perf_counter()
        for _ in range(reps):
            fn()
        elapsed = time.perf_counter() - start
    return elapsed / reps


def calibrate(fn: Callable[[], object], window: float, min_reps: int = 3) -> int:
    """How many calls of ``fn`` fill about ``window`` seconds (after a few warm-up calls)."""
    for _ in range(min_reps):
        fn()
    reps, took = 1, 0.0
    while True:
        took = time_calls(fn, reps) * reps
        if took >= window / 10 or reps >= 1 << 22:
            break
        reps *= 4
    return max(min_reps, int(reps * window / max(took, 1e-9)))


def interleaved_runs(candidates: dict[str, Callable[[], object]], window: float, runs: int) -> dict[str, list[float]]:
    """Seconds per call of each candidate in each of ``runs`` rounds; within a round every
    candidate runs once, the order rotating from round to round (a b c, b c a, c a b, ...).

    The rounds matter more than the medians: this VM switches between speed modes (the same
    tick ~5 or ~8 us per node) that last seconds, so candidates are only comparable within a
    round. The rotation keeps any candidate from always running first or right after another.
    """
    reps = {name: calibrate(fn, window) for name, fn in candidates.items()}
    samples: dict[str, list[float]] = {name: [] for name in candidates}
    names = list(candidates)
    for r in range(runs):
        for name in names[r % len(names):] + names[: r % len(names)]:
            samples[name].append(time_calls(candidates[name], reps[name]))
    return samples


def paired_ratio(numerator: Sequence[float], denominator: Sequence[float]) -> float:
    """Median over rounds of numerator / denominator measured in the same round: a ratio that
    machine speed changes between rounds cannot move (the ratio of two medians can)."""
    return statistics.median(n / d for n, d in zip(numerator, denominator, strict=True))
