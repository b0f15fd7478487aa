"""Noise suppression in front of the recogniser: a steady hiss taken out of an utterance.

A small recogniser loses words first under steady noise (a fan, a motor, the robot's own
cooling): at 10 dB SNR of white noise ``tiny.en`` heard the wake phrase as "face to it". The
utterance the segmenter cuts keeps some silence around the speech (its pre-roll and the pause
after it), so the noise can be measured where nobody speaks: the power spectrum of the quietest
frames is the noise estimate, and every frame's spectrum is scaled by a Wiener-like gain,
``1 - OVER * noise / power``, kept above a floor (so the result never has holes that sound like
words) and smoothed over neighbouring frames and frequencies (so it does not warble). A clean
utterance is left nearly as it was: its quiet frames are quiet.

Measured on the hearing benchmark's 202 utterances (bench/hearing.py): at 10 dB SNR 47.4 ->
58.4 % of commands heard exactly, clean ones unchanged (91.2 %), no command made of a
non-command; a stronger suppression (more subtraction, a lower floor) made commands of
non-commands on a subset and was not kept.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .audio import RATE

if TYPE_CHECKING:
    import numpy as np

WINDOW = 512  # samples (32 ms at 16 kHz)
HOP = 128
QUIET_SHARE = 0.15  # the quietest share of the frames is taken as noise
OVER = 1.5  # how much of the noise estimate is taken out
FLOOR = 0.1  # the least gain (-20 dB): suppression never leaves silence with holes in it
MIN_S = 0.25  # shorter than this, nothing can be measured: returned as it is


def suppress_noise(samples: np.ndarray) -> np.ndarray:
    """16 kHz mono int16 ``samples`` with their steady noise suppressed (same length and type)."""
    import numpy as np

    if len(samples) < MIN_S * RATE:
        return samples
    x = samples.astype(np.float64)
    window = np.hanning(WINDOW)
    padded = np.concatenate([np.zeros(WINDOW), x, np.zeros(WINDOW)])
    starts = np.arange(0, len(padded) - WINDOW, HOP)
    frames = np.stack([padded[s:s + WINDOW] for s in starts]) * window
    spectra = np.fft.rfft(frames, axis=1)
    power = np.abs(spectra) ** 2
    energy = power.sum(axis=1)
    quiet = energy <= np.quantile(energy, QUIET_SHARE)
    noise = power[quiet].mean(axis=0)
    gain = np.maximum(1.0 - OVER * noise / np.maximum(power, 1e-12), FLOOR)
    gain = _smooth(gain)
    frames_out = np.fft.irfft(spectra * gain, n=WINDOW, axis=1) * window
    out = np.zeros(len(padded))
    norm = np.zeros(len(padded))
    for k, s in enumerate(starts):
        out[s:s + WINDOW] += frames_out[k]
        norm[s:s + WINDOW] += window ** 2
    y = out / np.maximum(norm, 1e-8)
    return np.clip(y[WINDOW:WINDOW + len(x)], -32768, 32767).astype(np.int16)


def _smooth(gain: np.ndarray) -> np.ndarray:
    """The mean of each gain and its eight neighbours in time and frequency."""
    import numpy as np

    padded = np.pad(gain, 1, mode="edge")
    rows, cols = gain.shape
    total = np.zeros_like(gain)
    for i in range(3):
        for j in range(3):
            total += padded[i:i + rows, j:j + cols]
    return total / 9.0
