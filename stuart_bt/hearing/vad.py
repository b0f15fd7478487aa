"""Voice activity: a stream of sound cut into utterances.

WebRTC's voice detector judges each 30 ms frame; an utterance starts when most of the last few
frames are voiced (one click or cough is not speech) and ends after ``end_silence_s`` of
unvoiced frames (a pause between words is shorter), or at ``max_s`` (someone who never stops,
or a noise the detector takes for a voice). The frames just before the start are kept
(``pre_roll_s``), because the detector notices speech a little after it began and the first
consonant matters ("stop" without its s is "top").

While the robot itself speaks (``speaking = True``, set from the tts daemon's activity), the
segmenter keeps listening but marks an utterance that began while the robot spoke, or was
heard mostly over its voice (``Segment.over_robot_speech``), so that the pipeline acts on such
an utterance only when it is a stop: the robot's own voice can never trigger a command, a person
can still interrupt it (barge-in), and a person who goes on talking as the robot starts a short
sentence is still heard (docs/hearing.md).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from typing import TYPE_CHECKING

from .audio import RATE

if TYPE_CHECKING:
    import numpy as np

FRAME = int(RATE * 0.03)  # samples per detector frame (30 ms: one of the three lengths WebRTC's detector takes)
QUIET_RMS = 60.0  # int16 RMS (about -55 dBFS) below which a frame is silence whatever the detector says


@dataclass(frozen=True)
class Segment:
    """One utterance: its samples and where it lies in the stream (seconds from the start)."""

    samples: np.ndarray
    start_s: float
    end_s: float
    over_robot_speech: bool = False

    @property
    def audio_s(self) -> float:
        return len(self.samples) / RATE


@dataclass
class SegmenterOptions:
    """How speech is told from silence. Why these: 0.7 s of silence ends a command (people pause
    for 0.2-0.5 s between words of a command, and longer when done); while the robot talks,
    0.35 s does, so that "Hey Stuart, stop" stops it sooner (a longer pause after the wake phrase
    cuts it in two, and a bare wake phrase holds the robot's attention for the stop that
    follows: :mod:`stuart_bt.mission.attention`); 15 s is longer than any spoken command; a
    start needs 5 voiced frames of the last 8 (~0.15 s of voice)."""

    aggressiveness: int = 2  # 0 (lenient) .. 3 (strict): how readily WebRTC calls a frame voiced
    end_silence_s: float = 0.7
    barge_in_silence_s: float = 0.35  # while the robot talks: only a stop is acted on then, and it is short
    max_s: float = 15.0
    pre_roll_s: float = 0.3
    start_window: int = 8
    start_voiced: int = 5
    min_speech_s: float = 0.2  # shorter voiced spans are dropped (a click, a door)


class Segmenter:
    """Feed it blocks of 16 kHz mono int16; it returns the utterances it completed."""

    def __init__(self, options: SegmenterOptions | None = None) -> None:
        import webrtcvad

        self.options = options or SegmenterOptions()
        self._vad = webrtcvad.Vad(self.options.aggressiveness)
        self.speaking = False  # the robot is talking: see the module docstring
        self._pending: list[np.ndarray] = []  # samples not yet a whole frame
        self._pending_n = 0
        self._pre: deque[np.ndarray] = deque(maxlen=max(1, round(self.options.pre_roll_s / 0.03)))
        self._recent: deque[bool] = deque(maxlen=self.options.start_window)
        self._frames: list[np.ndarray] = []  # the utterance being heard ([] when idle)
        self._voiced_frames = 0
        self._trailing = 0  # unvoiced frames at the end of the utterance so far
        self._started_over_speech = False  # the utterance began while the robot spoke
        self._speech_frames = 0  # its frames heard while the robot spoke
        self._t = 0  # samples consumed
        self._start = 0

    def feed(self, block: np.ndarray) -> list[Segment]:
        import numpy as np

        self._pending.append(block)
        self._pending_n += len(block)
        if self._pending_n < FRAME:
            return []
        data = np.concatenate(self._pending)
        whole = len(data) - len(data) % FRAME
        self._pending, self._pending_n = [data[whole:]], len(data) - whole
        out: list[Segment] = []
        for start in range(0, whole, FRAME):
            segment = self._frame(data[start:start + FRAME])
            if segment is not None:
                out.append(segment)
        return out

    def flush(self) -> list[Segment]:
        """The end of the stream: an utterance still open is complete."""
        segment = self._cut() if self._frames else None
        return [segment] if segment is not None else []

    def _frame(self, frame: np.ndarray) -> Segment | None:
        voiced = self._voiced(frame)
        self._t += FRAME
        if not self._frames:
            self._idle(frame, voiced)
            return None
        self._frames.append(frame)
        self._speech_frames += self.speaking
        if voiced:
            self._voiced_frames += 1
            self._trailing = 0
        else:
            self._trailing += 1
        o = self.options
        end_silence = o.barge_in_silence_s if self.speaking or self._started_over_speech else o.end_silence_s
        if self._trailing * 0.03 >= end_silence or (len(self._frames) + 1) * 0.03 > o.max_s:
            return self._cut()
        return None

    def _idle(self, frame: np.ndarray, voiced: bool) -> None:
        """Not in an utterance: keep the pre-roll, and start one when enough frames are voiced."""
        self._pre.append(frame)
        self._recent.append(voiced)
        if sum(self._recent) >= self.options.start_voiced:
            self._frames = list(self._pre)
            self._start = self._t - FRAME * len(self._frames)
            self._voiced_frames = sum(self._recent)
            self._trailing = 0
            self._started_over_speech = self.speaking
            self._speech_frames = len(self._frames) if self.speaking else 0
            self._pre.clear()
            self._recent.clear()

    def _cut(self) -> Segment | None:
        import numpy as np

        keep = len(self._frames) - max(0, self._trailing - round(0.2 / 0.03))  # keep 0.2 s of the silence after
        frames, voiced, start = self._frames[:keep], self._voiced_frames, self._start
        over = self._started_over_speech or 2 * self._speech_frames > len(self._frames)
        self._frames, self._voiced_frames, self._trailing, self._speech_frames = [], 0, 0, 0
        if voiced * 0.03 < self.options.min_speech_s:
            return None
        samples = np.concatenate(frames)
        return Segment(samples, start / RATE, (start + len(samples)) / RATE, over)

    def _voiced(self, frame: np.ndarray) -> bool:
        import numpy as np

        if float(np.sqrt(np.mean(frame.astype(np.float32) ** 2))) < QUIET_RMS:
            return False
        return bool(self._vad.is_speech(frame.astype("<i2").tobytes(), RATE))
