"""Recognition on real audio: commands spoken by espeak-ng in several voices and speeds are
heard as the grammar's intents, also with noise at 10 dB SNR; silence and noise alone are heard
as nothing; the words the robot expects come from its map, objects and gestures."""

from __future__ import annotations

import numpy as np
import pytest

from speech_support import NEEDS_ESPEAK
from stuart_bt.hearing.audio import RATE, read_audio
from stuart_bt.hearing.audio import add_noise as with_noise
from stuart_bt.hearing.pipeline import hear, is_speech, transcribe
from stuart_bt.hearing.sources import FileSource
from stuart_bt.language.parse import Parser
from stuart_bt.testing import VOICES, speak

# (said, the (action, target) intents it means). One per command family; voices and speeds vary.
COMMANDS = [
    ("Hey Stuart, go to the kitchen", [("navigate_to_marker", "kitchen")]),
    ("Hey Stuart, turn right", [("turn_by_angle", "")]),
    ("Hey Stuart, find the apple", [("find", "apple")]),
    ("Hey Stuart, go to the workbench and wave", [("navigate_to_marker", "workbench"), ("gesture", "wave")]),
    ("Hey Stuart, stop", [("stop", "")]),
    ("Hey Stuart, walk forward two metres", [("move_relative", "")]),
]
SPEEDS = (150, 175, 140, 165, 185, 155)


def _meaning(text: str) -> list[tuple[str, str]]:
    return [(i.action, i.target) for i in Parser().parse(text).intents]


def _score(recogniser, vocabulary, folder, snr_db: float | None) -> list[bool]:
    """Each command spoken in its own voice and speed (with noise at ``snr_db``), heard, and
    compared with what it means; one line printed per command."""
    right = []
    for n, (said, meant) in enumerate(COMMANDS):
        clip = read_audio(speak(said, folder / f"{n}.wav", VOICES[n], SPEEDS[n]))
        if snr_db is not None:
            clip = with_noise(clip, snr_db, seed=n)
        heard = transcribe(recogniser, clip, vocabulary)
        right.append(_meaning(heard.text) == meant)
        assert 0.0 <= heard.transcript.confidence <= 1.0 and heard.transcript.audio_s == pytest.approx(len(clip) / RATE)
        print(f"{'ok  ' if right[-1] else 'MISS'} {VOICES[n]:>10} {SPEEDS[n]} wpm: {said!r} -> {heard.text!r} "
              f"(confidence {heard.transcript.confidence:.2f})")
    return right


# A small model misses a word now and then, more often under noise (the wake phrase first: "thanks
# Stuart", "face to us"); these tests ask for the behaviour, and bench/hearing.py measures the
# rates on a generated corpus.
@NEEDS_ESPEAK
def test_spoken_commands_in_six_voices_are_heard_as_their_intents(recogniser, lab_vocabulary, tmp_path):
    right = _score(recogniser, lab_vocabulary, tmp_path, None)
    assert sum(right) >= len(COMMANDS) - 1, f"{sum(right)} of {len(COMMANDS)} heard right"


@NEEDS_ESPEAK
def test_half_or_more_of_the_commands_are_still_heard_under_white_noise_at_10_db_snr(recogniser, lab_vocabulary,
                                                                                      tmp_path):
    right = _score(recogniser, lab_vocabulary, tmp_path, 10.0)
    assert sum(right) >= len(COMMANDS) // 2, f"{sum(right)} of {len(COMMANDS)} heard right at 10 dB SNR"


def test_silence_and_noise_alone_are_heard_as_nothing(recogniser, lab_vocabulary, tmp_path):
    rng = np.random.default_rng(7)
    for name, clip in (("silence", np.zeros(3 * RATE, np.int16)),
                       ("white noise", rng.normal(0, 3000, 3 * RATE).astype(np.int16)),
                       ("hum", (3000 * np.sin(2 * np.pi * 50 * np.arange(3 * RATE) / RATE)).astype(np.int16))):
        heard = transcribe(recogniser, clip, lab_vocabulary)
        print(f"{name}: {heard.text!r} (no speech {heard.transcript.no_speech:.2f})")
        assert not is_speech(heard.transcript) or _meaning(heard.text) == []


@NEEDS_ESPEAK
def test_a_recording_of_several_commands_is_heard_as_each_in_order(recogniser, lab_vocabulary, tmp_path):
    files = [speak(COMMANDS[n][0], tmp_path / f"{n}.wav", VOICES[n], SPEEDS[n]) for n in (0, 2, 4)]
    heard = list(hear(FileSource(files), recogniser, lab_vocabulary))
    assert [_meaning(h.text) for h in heard] == [COMMANDS[n][1] for n in (0, 2, 4)]
    assert [h.start_s for h in heard] == sorted(h.start_s for h in heard)
    assert all(h.latency_s >= h.transcript.seconds > 0 for h in heard)


def test_the_prompt_names_the_robot_the_places_objects_and_gestures(lab_vocabulary):
    prompt = lab_vocabulary.prompt()
    for word in ("Stuart", "kitchen", "Electronics bench", "bottle", "high five", "degrees"):
        assert word in prompt
    assert len(prompt) <= 600
