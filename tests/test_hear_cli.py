"""``stuart-bt hear``: one JSON line per file in order, with the parse object and what hearing
adds; an unreadable file is one error line and the rest go on; --split and raw PCM on stdin cut
a recording into its utterances."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from speech_support import NEEDS_ESPEAK, joined
from stuart_bt.hearing.audio import read_audio
from stuart_bt.testing import speak

pytest.importorskip("faster_whisper", reason="the 'hearing' extra is not installed (make test installs it)")
PARSE_FIELDS = {"utterance", "wake", "command", "intents", "conversational"}
HEARING_FIELDS = {"file", "transcript", "audio_s", "confidence", "no_speech", "latency_s", "engine", "readings"}


def _hear(*args: str, stdin: bytes | None = None) -> tuple[int, list[dict]]:
    proc = subprocess.run([sys.executable, "-m", "stuart_bt.cli", "hear", *args], input=stdin, capture_output=True,
                          timeout=120)
    assert b"Traceback" not in proc.stderr, proc.stderr.decode()
    return proc.returncode, [json.loads(line) for line in proc.stdout.decode().splitlines()]


@NEEDS_ESPEAK
def test_each_file_is_one_line_in_order_and_a_bad_file_is_an_error_line(tmp_path):
    go = speak("Hey Stuart, go to the bathroom", tmp_path / "go.wav", "en-gb+m3")
    junk = tmp_path / "junk.wav"
    junk.write_bytes(b"\x00garbage" * 100)
    quiet = tmp_path / "quiet.wav"
    from stuart_bt.hearing.audio import write_wav
    write_wav(quiet, np.zeros(16_000, np.int16))
    code, lines = _hear(str(go), str(junk), str(tmp_path / "missing.flac"), str(quiet),
                        "--markers", "sim/maps/lab_markers.json")
    assert code == 1 and [line["file"] for line in lines] == [str(go), str(junk), str(tmp_path / "missing.flac"),
                                                               str(quiet)]
    first = lines[0]
    assert PARSE_FIELDS | HEARING_FIELDS | {"resolution"} <= set(first)
    assert [(i["action"], i["target"]) for i in first["intents"]] == [("navigate_to_marker", "bathroom")]
    assert first["resolution"][0]["name"] == "bathroom" and first["transcript"] == first["utterance"]
    assert 0 < first["confidence"] <= 1 and first["latency_s"] > 0 and first["audio_s"] > 1
    scores = [score for _, score in first["readings"]]
    assert first["readings"] and scores == sorted(scores, reverse=True), "the recogniser's readings, best first"
    assert first["transcript"] in [text for text, _ in first["readings"]]
    assert "cannot read it as audio" in lines[1]["error"] and "no such file" in lines[2]["error"]
    assert lines[3]["transcript"] == "" and lines[3]["intents"] == [] and lines[3]["wake"] is False


@NEEDS_ESPEAK
def test_split_and_stdin_pcm_find_each_utterance_of_a_recording(tmp_path):
    said = ["Hey Stuart, turn left", "Hey Stuart, stop"]
    clips = [read_audio(speak(t, tmp_path / f"{n}.wav", "en-us")) for n, t in enumerate(said)]
    recording = joined(clips, gap_s=1.2)
    from stuart_bt.hearing.audio import write_wav
    long = write_wav(tmp_path / "long.wav", recording)
    for args, stdin in ((["--split", str(long)], None), (["-"], recording.astype("<i2").tobytes())):
        code, lines = _hear(*args, stdin=stdin)
        assert code == 0
        assert [[i["action"] for i in line["intents"]] for line in lines] == [["turn_by_angle"], ["stop"]]
        assert lines[0]["start_s"] < lines[0]["end_s"] < lines[1]["start_s"] < lines[1]["end_s"]
