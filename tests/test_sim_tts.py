"""Speech on the sim backend: real audio (espeak-ng), and speech overlapping a gesture."""

from __future__ import annotations

import shutil
import wave
from pathlib import Path

import pytest

ESPEAK = shutil.which("espeak-ng")


def wav_seconds(path: str) -> float:
    with wave.open(path, "rb") as w:
        return w.getnframes() / w.getframerate()


@pytest.mark.skipif(ESPEAK is None, reason="espeak-ng is not installed (make installs it: apt-get install espeak-ng)")
def test_speech_writes_a_wav_as_long_as_the_utterance_in_the_report(stuart_sim, tmp_path: Path):
    result = stuart_sim(text="""
root:
  sequence:
    - speak: {name: short, text: "Hello."}
    - speak: {name: long, text: "Behind this net is the drone cage, where flying robots practise."}
""", daemon_options={"tts": {"audio_dir": str(tmp_path), "engine": "espeak-ng"}})

    result.assert_success()
    short, long = result.utterances()
    for said in (short, long):
        assert Path(said["wav"]).parent == tmp_path
        assert wav_seconds(said["wav"]) == pytest.approx(said["duration"], abs=0.001)
        assert said["end"] - said["start"] >= said["duration"]  # the tree waited for the words
    assert long["duration"] > short["duration"] + 2.0


def test_speech_and_gesture_in_a_parallel_overlap_on_the_sim(stuart_sim):
    result = stuart_sim(text="""
root:
  parallel:
    name: hello
    children:
      - speak: "Hi there! I'm Stuart."
      - gesture: wave
""")

    result.assert_success()
    result.assert_said("I'm Stuart")
    result.assert_gestured("high wave")
    result.assert_speech_overlaps_gestures("hello/")
