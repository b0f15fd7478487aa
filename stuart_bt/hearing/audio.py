"""Sound as the recognisers want it: 16 kHz, mono, 16-bit samples in a numpy ``int16`` array.

Every source hands on this one shape, whatever it read: a 44.1 kHz stereo FLAC, an 8 kHz WAV or
a 48 kHz microphone are converted here once (PyAV, which the recogniser already needs, decodes
any container and resamples with a proper filter), so nothing further down knows about rates.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from ..core.errors import StuartError

if TYPE_CHECKING:
    import numpy as np

RATE = 16_000  # samples per second, everywhere after a source
SAMPLE_BYTES = 2  # int16


class AudioError(StuartError):
    """Sound that cannot be read: a missing or unreadable file, a format with no audio, no device."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason, "audio")


def seconds(samples: np.ndarray) -> float:
    return len(samples) / RATE


def read_audio(path: str | Path) -> np.ndarray:
    """The audio of a file (WAV, FLAC, MP3, OGG, ...; any rate and channel count) as 16 kHz mono
    int16. Raises :class:`AudioError` with the file and the reason, never a decoder traceback."""
    import av
    import numpy as np

    path = Path(path)
    if not path.is_file():
        raise AudioError(f"{path}: no such file" if not path.exists() else f"{path}: not a file")
    try:
        with av.open(str(path), metadata_errors="ignore") as container:
            if not container.streams.audio:
                raise AudioError(f"{path}: the file holds no audio")
            resampler = av.AudioResampler(format="s16", layout="mono", rate=RATE)
            chunks = [_frame_samples(out) for frame in container.decode(audio=0) for out in resampler.resample(frame)]
            chunks += [_frame_samples(out) for out in resampler.resample(None)]
    except AudioError:
        raise
    except (av.FFmpegError, OSError, ValueError, UnicodeDecodeError) as e:
        raise AudioError(f"{path}: cannot read it as audio ({_short(e)})") from None
    return np.concatenate(chunks) if chunks else np.zeros(0, np.int16)


def resample(samples: np.ndarray, rate: int, channels: int = 1) -> np.ndarray:
    """Interleaved int16 ``samples`` at ``rate`` with ``channels`` -> 16 kHz mono int16 (a
    microphone that only opens at 44.1 or 48 kHz)."""
    import av
    import numpy as np

    if rate == RATE and channels == 1:
        return samples.astype(np.int16, copy=False)
    layout = "mono" if channels == 1 else "stereo" if channels == 2 else f"{channels}c"
    frame = av.AudioFrame.from_ndarray(samples.reshape(1, -1).astype(np.int16), format="s16", layout=layout)
    frame.sample_rate = rate
    resampler = av.AudioResampler(format="s16", layout="mono", rate=RATE)
    out = [_frame_samples(f) for f in resampler.resample(frame)] + [_frame_samples(f) for f in resampler.resample(None)]
    return np.concatenate(out) if out else np.zeros(0, np.int16)


def to_float(samples: np.ndarray) -> np.ndarray:
    """int16 -> float32 in [-1, 1), what the recognisers take."""
    import numpy as np

    return samples.astype(np.float32) / 32768.0


def add_noise(samples: np.ndarray, snr_db: float, seed: int = 0) -> np.ndarray:
    """A copy of ``samples`` with white noise ``snr_db`` below the power of the speech in it
    (the loud part, not the silence around it): how tests and benchmarks ask "does it still hear
    this in a noisy room?" with a number that means the same for every clip."""
    import numpy as np

    x = samples.astype(np.float64)
    if not len(x) or not np.abs(x).max():
        return samples.copy()
    voiced = x[np.abs(x) > 0.02 * np.abs(x).max()]
    noise = np.random.default_rng(seed).normal(0.0, 1.0, len(x))
    noise *= np.sqrt(np.mean(voiced ** 2) / 10 ** (snr_db / 10.0))
    return np.clip(x + noise, -32768, 32767).astype(np.int16)


def write_wav(path: str | Path, samples: np.ndarray) -> Path:
    """16 kHz mono int16 samples to a WAV file (a segment kept for a bug report or a test)."""
    import wave

    path = Path(path)
    with wave.open(str(path), "wb") as out:
        out.setnchannels(1)
        out.setsampwidth(SAMPLE_BYTES)
        out.setframerate(RATE)
        out.writeframes(samples.astype("<i2").tobytes())
    return path


def _frame_samples(frame: object) -> np.ndarray:
    return frame.to_ndarray().reshape(-1)  # type: ignore[attr-defined]


def _short(error: Exception) -> str:
    """The decoder's reason without its errno and file name ("Invalid data found when processing input")."""
    text = getattr(error, "strerror", None) or str(error).strip() or type(error).__name__
    return text if len(text) <= 160 else text[:157] + "..."
