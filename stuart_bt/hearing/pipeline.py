"""Source -> utterances -> transcripts: the hearing stage as one loop.

:func:`hear` reads a source, cuts it into utterances (:mod:`.vad`) and transcribes each
(:mod:`.recognisers`, after :mod:`.denoise` took the steady noise out), yielding :class:`Heard`
in order. ``latency_s`` is measured from the end of the utterance's audio (when the segmenter
decided speech had ended, or, for a whole file, when it was read) to the transcript; the
caller adds the time its parse takes. What was heard over the robot's own voice is marked, and
a recogniser's empty or no-speech result is dropped (noise the voice detector let through).
"""

from __future__ import annotations

import queue
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

from .audio import AudioError
from .denoise import suppress_noise
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
               source: str = "", over_robot_speech: bool = False, ended_at: float | None = None,
               denoise: bool = True) -> Heard:
    """One utterance's samples -> :class:`Heard` (``ended_at``: ``perf_counter()`` when its audio
    ended), its steady noise suppressed first unless ``denoise`` is False (:mod:`.denoise`)."""
    ended = time.perf_counter() if ended_at is None else ended_at
    transcript = recogniser.transcribe(suppress_noise(samples) if denoise else samples, vocabulary)
    return Heard(transcript, start_s, start_s + transcript.audio_s, time.perf_counter() - ended,
                 over_robot_speech, source)


def hear(source: Source, recogniser: Recogniser, vocabulary: Vocabulary | None = None,
         segmenter: Segmenter | None = None) -> Iterator[Heard]:
    """Every utterance in ``source`` that holds speech, transcribed, in order. A live source is
    cut on its own thread while utterances are recognised, so the voice detector sees each block
    when it is heard (what the robot was doing then, e.g. speaking, is what it was doing when
    the sound was made) and the next utterance is cut while the last one is still recognised."""
    segmenter = segmenter or Segmenter()
    cuts = _cut_live(source, segmenter) if source.live else _cut(source, segmenter)
    try:
        for segment, ended_at in cuts:
            heard = transcribe(recogniser, segment.samples, vocabulary, segment.start_s, source.name,
                               segment.over_robot_speech, ended_at)
            if is_speech(heard.transcript):
                yield heard
    finally:
        source.close()


def _cut(source: Source, segmenter: Segmenter) -> Iterator[tuple[Segment, float]]:
    for block in source.blocks():
        for segment in segmenter.feed(block):
            yield segment, time.perf_counter()
    for segment in segmenter.flush():
        yield segment, time.perf_counter()


def _cut_live(source: Source, segmenter: Segmenter) -> Iterator[tuple[Segment, float]]:
    cuts: queue.Queue[tuple[Segment, float] | BaseException | None] = queue.Queue()

    def cut() -> None:
        try:
            for item in _cut(source, segmenter):
                cuts.put(item)
        except AudioError as e:  # a source that fails (a device unplugged): the reader raises it
            cuts.put(e)
        finally:
            cuts.put(None)

    threading.Thread(target=cut, name="hearing-vad", daemon=True).start()
    while (item := cuts.get()) is not None:
        if isinstance(item, BaseException):
            raise item
        yield item
