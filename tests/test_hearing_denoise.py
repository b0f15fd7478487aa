"""Noise suppression in front of the recogniser: steady noise goes down, speech stays."""

from __future__ import annotations

import numpy as np
import pytest

from speech_support import NEEDS_ESPEAK
from stuart_bt.hearing.audio import RATE, add_noise, read_audio
from stuart_bt.hearing.denoise import suppress_noise
from stuart_bt.testing import speak


def _db(signal: np.ndarray, error: np.ndarray) -> float:
    return 10 * np.log10(np.sum(signal.astype(float) ** 2) / max(np.sum(error.astype(float) ** 2), 1e-9))


@pytest.fixture(scope="module")
def clip(tmp_path_factory) -> np.ndarray:
    folder = tmp_path_factory.mktemp("said")
    return read_audio(speak("Hey Stuart, go to the kitchen", folder / "go.wav", "en-gb+m3"))


def test_steady_noise_alone_is_turned_down_by_eight_db_or_more():
    noise = np.random.default_rng(0).normal(0, 500, 3 * RATE).astype(np.int16)
    quieter = suppress_noise(noise)
    assert quieter.dtype == np.int16 and len(quieter) == len(noise)
    assert _db(noise, np.zeros(1)) - _db(quieter, np.zeros(1)) >= 8


@NEEDS_ESPEAK
def test_speech_in_noise_comes_out_closer_to_the_clean_speech(clip):
    padded = np.concatenate([np.zeros(RATE // 2, np.int16), clip, np.zeros(RATE // 2, np.int16)])
    noisy = add_noise(padded, 10.0, seed=1)
    before = _db(padded, noisy.astype(float) - padded)
    after = _db(padded, suppress_noise(noisy).astype(float) - padded)
    assert after >= before + 3, (before, after)


@NEEDS_ESPEAK
def test_clean_speech_is_left_nearly_as_it_was(clip):
    padded = np.concatenate([np.zeros(RATE // 2, np.int16), clip, np.zeros(RATE // 2, np.int16)])
    assert _db(padded, suppress_noise(padded).astype(float) - padded) >= 15


def test_a_clip_too_short_to_measure_is_returned_as_it_is():
    short = np.random.default_rng(2).normal(0, 500, RATE // 10).astype(np.int16)
    assert suppress_noise(short) is short
