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
from dataclasses import dataclass, replace
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

# The share of an utterance's energy the noise suppression took out above which it was heard in
# noise (measured on the hearing benchmark's clips: clean at most 0.004, 30 dB SNR ~0.01, 20 dB
# ~0.05, 10 dB ~0.28): then an utterance not heard as a command is heard a second time, as it
# came, before the robot gives up on it (:func:`transcribe`).
NOISY_SHARE = 0.03


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
    cleaned = suppress_noise(samples) if denoise else samples
    transcript = recogniser.transcribe(cleaned, vocabulary)
    if denoise and vocabulary is not None:
        transcript = _heard_again(recogniser, samples, cleaned, transcript, vocabulary)
    return Heard(transcript, start_s, start_s + transcript.audio_s, time.perf_counter() - ended,
                 over_robot_speech, source)


def _heard_again(recogniser: Recogniser, samples: np.ndarray, cleaned: np.ndarray, heard: Transcript,
                 vocabulary: Vocabulary) -> Transcript:
    """``heard``, or the utterance heard a second time as it came (no noise suppression) when it
    was said in noise and only that second hearing is a command. Noise suppression helps the
    recogniser on the whole (docs/hearing.md) but costs it some words, and not the same ones as
    the noise does: at 10 dB SNR the second hearing was a command where the first was none in 7 of
    137 commands and in none of the 65 non-commands. Only a recogniser that can tell a command
    form (``heard_as_command``: the command grammar) hears twice, and only in noise, for speech
    not already heard as a command: a clear command costs nothing more."""
    judge = getattr(recogniser, "heard_as_command", None)
    if judge is None or not is_speech(heard) or _share_removed(samples, cleaned) < NOISY_SHARE or judge(
            heard, vocabulary):
        return heard
    again = recogniser.transcribe(samples, vocabulary)
    if not is_speech(again) or not judge(again, vocabulary):
        return replace(heard, seconds=heard.seconds + again.seconds)
    return replace(again, alternatives=(*again.alternatives, *heard.readings()), seconds=heard.seconds + again.seconds)


def _share_removed(samples: np.ndarray, cleaned: np.ndarray) -> float:
    """The share of the energy of ``samples`` that noise suppression took out."""
    import numpy as np  # the hearing extra's: imported when there is sound

    before = float(np.dot(samples.astype(np.float64), samples.astype(np.float64)))
    after = float(np.dot(cleaned.astype(np.float64), cleaned.astype(np.float64)))
    return 1.0 - after / before if before > 0 else 0.0


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
