"""Path segments for sibling nodes, shared by the loader and the exporter so both agree.

A child's segment is its explicit ``name``; otherwise its base (the kind, or an included file's
stem) when no sibling shares that base, else ``base_N`` with N counting same-base siblings
from 1. Counting includes named siblings, so naming one node never renames the others.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence


def child_segments(names: Sequence[str | None], bases: Sequence[str]) -> list[str]:
    """Segments for siblings given their explicit names (or ``None``) and bases, in order."""
    totals = Counter(bases)
    seen: Counter[str] = Counter()
    segments = []
    for name, base in zip(names, bases, strict=True):
        seen[base] += 1
        if name:
            segments.append(name)
        elif totals[base] == 1:
            segments.append(base)
        else:
            segments.append(f"{base}_{seen[base]}")
    return segments
