"""Source -> utterances -> transcripts: the hearing stage as one loop.

:func:`hear` reads a source, cuts it into utterances (:mod:`.vad`) and transcribes each
(:mod:`.recognisers`), yielding :class:`Heard` in order. ``latency_s`` is measured from the end
of the utterance's audio (when the segmenter decided speech had ended, or, for a whole file,
when it was read) to the transcript; the caller adds the time its parse takes. What was heard
over the robot's own voice is marked, and a recogniser's empty or no-speech result is dropped
(noise the voice detector let through).
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

from .recognisers import Recogniser, Transcript
from .sources import Source
from .vad import Segment, Segmenter
from .vocabulary import Vocabulary

if TYPE_CHECKING:
    import numpy as np

NO_SPEECH = 0.6  # a transcript the recogniser itself thinks more likely silence than speech is dropped


@dataclass(frozen=True)
class Heard:
    """One utterance heard: the transcript, where it was in the stream, and how long after its
    end the transcript was ready."""

    transcript: Transcript
    start_s: float
    end_s: float
    latency_s: float
    over_robot_speech: bool = False
    source: str = ""

    @property
    def text(self) -> str:
        return self.transcript.text


def is_speech(transcript: Transcript) -> bool:
    """Did the recogniser hear words? (not nothing, not only punctuation, not a no-speech guess)"""
    return any(c.isalnum() for c in transcript.text) and transcript.no_speech < NO_SPEECH


def transcribe(recogniser: Recogniser, samples: np.ndarray, vocabulary: Vocabulary | None, start_s: float = 0.0,
               source: str = "", over_robot_speech: bool = False, ended_at: float | None = None) -> Heard:
    """One utterance's samples -> :class:`Heard` (``ended_at``: ``perf_counter()`` when its audio ended)."""
    ended = time.perf_counter() if ended_at is None else ended_at
    transcript = recogniser.transcribe(samples, vocabulary)
    return Heard(transcript, start_s, start_s + transcript.audio_s, time.perf_counter() - ended,
                 over_robot_speech, source)


def hear(source: Source, recogniser: Recogniser, vocabulary: Vocabulary | None = None,
         segmenter: Segmenter | None = None) -> Iterator[Heard]:
    """Every utterance in ``source`` that holds speech, transcribed, in order."""
    segmenter = segmenter or Segmenter()
    try:
        for block in source.blocks():
            for segment in segmenter.feed(block):
                heard = _heard(recogniser, segment, vocabulary, source.name)
                if heard is not None:
                    yield heard
        for segment in segmenter.flush():
            heard = _heard(recogniser, segment, vocabulary, source.name)
            if heard is not None:
                yield heard
    finally:
        source.close()


def _heard(recogniser: Recogniser, segment: Segment, vocabulary: Vocabulary | None, source: str) -> Heard | None:
    heard = transcribe(recogniser, segment.samples, vocabulary, segment.start_s, source, segment.over_robot_speech)
    return heard if is_speech(heard.transcript) else None
