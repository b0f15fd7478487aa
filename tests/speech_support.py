"""Spoken test audio made at test time (no recordings in the repository): espeak-ng speaks a
sentence to WAV in a voice and at a speed (``stuart_bt.testing.speak``), noise is added at a
given signal-to-noise ratio (``stuart_bt.hearing.audio.add_noise``), clips are joined with
silence. Registered as a pytest plugin for the session-wide recogniser."""

from __future__ import annotations

import shutil
import time

import pytest

ESPEAK = shutil.which("espeak-ng")
SOX = shutil.which("sox")
NEEDS_ESPEAK = pytest.mark.skipif(ESPEAK is None, reason="espeak-ng is not installed (make test installs it)")
NEEDS_SOX = pytest.mark.skipif(SOX is None, reason="sox is not installed (make test installs it)")


def joined(clips, gap_s: float = 1.0):
    """Clips one after another with ``gap_s`` of silence before, between and after them."""
    import numpy as np

    gap = np.zeros(int(16_000 * gap_s), np.int16)
    parts = [gap]
    for clip in clips:
        parts += [clip, gap]
    return np.concatenate(parts)


@pytest.fixture(scope="session")
def recogniser():
    """One recogniser of the default engine for the whole session (the models load in ~1 s)."""
    pytest.importorskip("faster_whisper", reason="the 'hearing' extra is not installed (make test installs it)")
    pytest.importorskip("pocketsphinx", reason="the 'hearing' extra is not installed (make test installs it)")
    from stuart_bt.hearing.recognisers import make_recogniser

    return make_recogniser()


@pytest.fixture(scope="session")
def lab_vocabulary():
    """What the robot expects in the lab: its markers, objects and gestures."""
    from stuart_bt.language.resolve import Resolver
    from stuart_bt.testing import lab_markers

    return Resolver.from_files(lab_markers()).vocabulary()


def wait_event(events, match, timeout: float = 60.0):
    """The last event ``events`` (an EventRecorder) holds that ``match``es, waiting up to
    ``timeout`` s; on a timeout the assertion shows the last events."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        found = [e for e in list(events.events) if match(e)]
        if found:
            return found[-1]
        time.sleep(0.05)
    raise AssertionError("timed out waiting for an event; last events: " +
                         "; ".join(f"{e.kind} {e.data}" for e in list(events.events)[-8:]))
