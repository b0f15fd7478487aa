"""Spoken test audio made at test time (no recordings in the repository): espeak-ng speaks a
sentence to WAV in a voice and at a speed; helpers add noise at a given signal-to-noise ratio
and join clips with silence. Registered as a pytest plugin for the session-wide recogniser."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

ESPEAK = shutil.which("espeak-ng")
SOX = shutil.which("sox")
NEEDS_ESPEAK = pytest.mark.skipif(ESPEAK is None, reason="espeak-ng is not installed (make test installs it)")
NEEDS_SOX = pytest.mark.skipif(SOX is None, reason="sox is not installed (make test installs it)")
VOICES = ("en-us", "en-gb+m3", "en-us+f2", "en-gb-x-rp", "en-us+m3", "en-gb+f3")


def speak(text: str, path: Path, voice: str = "en-us", speed: int = 160) -> Path:
    """``text`` spoken by espeak-ng into the WAV ``path`` (22.05 kHz mono, as espeak writes it)."""
    assert ESPEAK is not None
    subprocess.run([ESPEAK, "-v", voice, "-s", str(speed), "-w", str(path), text], check=True, timeout=30,
                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return path


def with_noise(samples, snr_db: float, seed: int = 0):
    """``samples`` (16 kHz int16) plus white noise ``snr_db`` below the speech's power."""
    import numpy as np

    x = samples.astype(np.float64)
    voiced = x[np.abs(x) > 0.02 * np.abs(x).max()]  # the speech, not the silence around it
    noise = np.random.default_rng(seed).normal(0.0, 1.0, len(x))
    noise *= np.sqrt(np.mean(voiced ** 2) / 10 ** (snr_db / 10.0))
    return np.clip(x + noise, -32768, 32767).astype(np.int16)


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
    """One whisper recogniser for the whole session (the model loads in ~1 s)."""
    pytest.importorskip("faster_whisper", reason="the 'hearing' extra is not installed (make test installs it)")
    from stuart_bt.hearing.recognisers import make_recogniser

    return make_recogniser("whisper")


@pytest.fixture(scope="session")
def lab_vocabulary():
    """What the robot expects in the lab: its markers, objects and gestures."""
    from stuart_bt.cli.hear import _lab_markers, vocabulary_of
    from stuart_bt.language.resolve import Resolver

    return vocabulary_of(Resolver.from_files(_lab_markers()), "Stuart")
