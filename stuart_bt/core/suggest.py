"""Closest valid name for "did you mean ...?" hints in error messages."""

from __future__ import annotations

import difflib
from collections.abc import Iterable


def closest(name: str, candidates: Iterable[str], cutoff: float = 0.6) -> str | None:
    """The candidate most like ``name`` (case-insensitive), or ``None`` when nothing is close."""
    pool = {c.lower(): c for c in candidates}
    match = difflib.get_close_matches(name.lower(), list(pool), n=1, cutoff=cutoff)
    return pool[match[0]] if match else None


def did_you_mean(name: str, candidates: Iterable[str]) -> str:
    """`` (did you mean 'x'?)`` or an empty string; append it to an error message."""
    best = closest(name, candidates)
    return f" (did you mean {best!r}?)" if best else ""
