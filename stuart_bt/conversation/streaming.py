"""Collecting a streamed reply while timing it (time to first token, total): shared by backends."""

from __future__ import annotations

import time
from collections.abc import Iterable


def collect_timed(pieces: Iterable[str]) -> tuple[str, dict[str, float]]:
    """The joined, stripped text of a token stream and ``{"first_token_s", "total_s"}``."""
    start, first, parts = time.perf_counter(), None, []
    for piece in pieces:
        if first is None:
            first = time.perf_counter() - start
        parts.append(piece)
    total = time.perf_counter() - start
    return "".join(parts).strip(), {"first_token_s": total if first is None else first, "total_s": total}
