"""Voice activity: a stream is cut into utterances where people pause, silence and steady noise
give none, and what is heard while the robot talks is marked."""

from __future__ import annotations

import numpy as np
import pytest

from speech_support import ESPEAK, NEEDS_ESPEAK, joined
from stuart_bt.hearing.audio import RATE, read_audio
from stuart_bt.hearing.vad import Segmenter, SegmenterOptions
from stuart_bt.testing import speak

pytest.importorskip("webrtcvad", reason="the 'hearing' extra is not installed (make test installs it)")


def _cut(samples: np.ndarray, segmenter: Segmenter | None = None, block: int = 480) -> list:
    segmenter = segmenter or Segmenter()
    out = []
    for start in range(0, len(samples), block):
        out += segmenter.feed(samples[start:start + block])
    return out + segmenter.flush()


@pytest.fixture(scope="module")
def commands(tmp_path_factory) -> list[np.ndarray]:
    if ESPEAK is None:
        pytest.skip("espeak-ng is not installed (make test installs it)")
    folder = tmp_path_factory.mktemp("spoken")
    texts = ("Hey Stuart, go to the kitchen", "turn left", "Hey Stuart, stop")
    return [read_audio(speak(t, folder / f"{n}.wav", voice)) for n, (t, voice) in
            enumerate(zip(texts, ("en-us", "en-gb+m3", "en-us+f2"), strict=True))]


def test_silence_and_steady_quiet_noise_are_no_utterance():
    rng = np.random.default_rng(1)
    assert _cut(np.zeros(5 * RATE, np.int16)) == []
    assert _cut(rng.normal(0, 30, 5 * RATE).astype(np.int16)) == []  # a quiet room's hiss


@NEEDS_ESPEAK
def test_three_commands_with_pauses_are_three_utterances_in_place(commands):
    stream = joined(commands, gap_s=1.0)
    segments = _cut(stream)
    assert len(segments) == 3
    starts = np.cumsum([1.0] + [len(c) / RATE + 1.0 for c in commands])[:3]
    for segment, start, clip in zip(segments, starts, commands, strict=True):
        assert segment.start_s <= start + 0.2 and segment.end_s >= start + len(clip) / RATE - 0.4
        assert segment.end_s - segment.start_s < len(clip) / RATE + 0.6  # it ends in the pause, not later


@NEEDS_ESPEAK
def test_the_block_size_a_source_uses_does_not_change_the_cuts(commands):
    stream = joined(commands, gap_s=1.0)
    a = [(round(s.start_s, 2), round(s.end_s, 2)) for s in _cut(stream, block=480)]
    b = [(round(s.start_s, 2), round(s.end_s, 2)) for s in _cut(stream, block=1234)]
    assert a == b


@NEEDS_ESPEAK
def test_an_utterance_longer_than_the_limit_is_cut_at_the_limit(commands):
    talk = np.concatenate(commands * 3)  # no pauses
    segments = _cut(talk, Segmenter(SegmenterOptions(max_s=2.0)))
    assert len(segments) >= 2 and all(s.audio_s <= 2.0 + 1e-6 for s in segments)


@NEEDS_ESPEAK
def test_what_is_heard_while_the_robot_speaks_is_marked(commands):
    segmenter = Segmenter()
    quiet = np.zeros(RATE, np.int16)
    marked = []
    for speaking, clip in ((False, commands[0]), (True, commands[2])):
        segmenter.speaking = speaking
        marked += [s.over_robot_speech for s in _feed(segmenter, np.concatenate([quiet, clip, quiet]))]
    assert marked == [False, True]


def _feed(segmenter: Segmenter, samples: np.ndarray) -> list:
    out = []
    for start in range(0, len(samples), 480):
        out += segmenter.feed(samples[start:start + 480])
    return out


@NEEDS_ESPEAK
def test_while_the_robot_speaks_a_shorter_silence_ends_an_utterance(commands):
    """Barge-in: "Hey Stuart, stop" said over the robot is cut sooner after it ends; a pause
    shorter than the usual end of speech but longer than the barge-in one splits two phrases."""
    options = SegmenterOptions()
    gap = (options.barge_in_silence_s + options.end_silence_s) / 2
    first, second = (_trimmed(c) for c in commands[1:3])
    two_phrases = np.concatenate([np.zeros(RATE, np.int16), first, np.zeros(int(RATE * gap), np.int16), second,
                                  np.zeros(RATE, np.int16)])
    ends = {}
    for speaking in (False, True):
        segmenter = Segmenter(options)
        segmenter.speaking = speaking
        segments = _cut(two_phrases, segmenter)
        ends[speaking] = segments[0].end_s
        assert len(segments) == (2 if speaking else 1), (speaking, [(s.start_s, s.end_s) for s in segments])
    assert ends[True] < ends[False]


def _trimmed(clip: np.ndarray) -> np.ndarray:
    """The clip without the silence espeak-ng puts around it (so a gap is the gap made here)."""
    loud = np.flatnonzero(np.abs(clip.astype(np.int32)) > 300)
    return clip[loud[0]:loud[-1] + 1]
