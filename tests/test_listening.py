"""A robot with ears: speech on a live stream becomes missions like typed text, the robot's
own voice never commands it, and "Hey Stuart, stop" said over its voice still stops it."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

from speech_support import NEEDS_ESPEAK
from speech_support import wait_event as _wait
from stuart_bt.core.events import EventRecorder
from stuart_bt.hearing.audio import RATE, read_audio
from stuart_bt.hearing.sources import PcmSource
from stuart_bt.mission.executor import MissionExecutor, MissionOptions
from stuart_bt.mission.listening import Listener
from stuart_bt.testing import speak

pytestmark = NEEDS_ESPEAK


class Microphone:
    """A live stream the test speaks into: clips written to a pipe at the speed they were said."""

    def __init__(self) -> None:
        read, self._write = os.pipe()
        self.source = PcmSource(os.fdopen(read, "rb"))
        self._quiet = np.zeros(RATE // 10, np.int16)
        self._lock = threading.Lock()

    def say(self, clip: np.ndarray, then_quiet_s: float = 1.2) -> None:
        samples = np.concatenate([clip, np.zeros(int(RATE * then_quiet_s), np.int16)])
        start = time.monotonic()
        with self._lock:
            for i in range(0, len(samples), 480):
                time.sleep(max(0.0, start + i / RATE - time.monotonic()))
                os.write(self._write, samples[i:i + 480].astype("<i2").tobytes())

    def close(self) -> None:
        os.close(self._write)


@pytest.fixture
def ears(recogniser, lab_vocabulary):
    robot = MissionExecutor(MissionOptions(backend="dry", speed=0.5))
    events = EventRecorder(robot.events)
    mic = Microphone()
    listener = Listener(robot, mic.source, recogniser, lab_vocabulary)
    robot.start()
    listener.start()
    try:
        yield robot, mic, events, listener
    finally:
        mic.close()
        listener.close()
        robot.close()


def test_a_spoken_command_becomes_a_mission_with_where_it_came_from(ears, tmp_path):
    robot, mic, events, _ = ears
    mic.say(read_audio(speak("Hey Stuart, go to the bathroom", tmp_path / "go.wav", "en-gb+m3")))
    said = _wait(events, lambda e: e.kind == "utterance")
    assert said.data["kind"] == "tasks" and said.data["source"] == "stdin"
    assert [i["target"] for i in said.data["intents"]] == ["bathroom"]
    assert 0 < said.data["confidence"] <= 1 and said.data["audio_s"] > 1 and said.data["latency_s"] > 0
    _wait(events, lambda e: e.kind == "mission" and e.data.get("phase") == "started")


def test_the_robot_s_own_voice_is_ignored_and_a_stop_over_it_still_stops_it(ears, tmp_path):
    robot, mic, events, listener = ears
    robot.submit("Hey Stuart, what can you do?")  # typed: the robot answers aloud, slowly (speed 0.5)
    _wait(events, lambda e: e.kind == "command" and e.data.get("family") == "tts" and e.data.get("cmd") == "say")
    assert listener.voice.speaking
    # what the robot would hear of itself if it said a command (an echo through the room)
    mic.say(read_audio(speak("Hey Stuart, go to the kitchen", tmp_path / "echo.wav", "en-us")))
    echo = _wait(events, lambda e: e.kind == "heard")
    assert echo.data["acted"] is False and echo.data["reason"] == "over_robot_speech"
    assert not [e for e in events.events if e.kind == "mission"], "the robot's own voice started a mission"
    assert listener.voice.speaking, "the reply should still be playing (else this test proves nothing)"
    mic.say(read_audio(speak("Hey Stuart, stop", tmp_path / "stop.wav", "en-us+m3")))
    stop = _wait(events, lambda e: e.kind == "utterance" and e.data.get("kind") == "stop")
    assert stop.data["source"] == "stdin"
    _wait(events, lambda e: e.kind == "command" and e.data.get("family") == "tts" and e.data.get("cmd") == "stop")
    _wait(events, lambda e: not listener.voice.speaking, timeout=5.0)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
        return True
    except ProcessLookupError:
        return False


def test_listen_hears_a_recording_runs_the_mission_and_stops_every_daemon(tmp_path):
    folder = tmp_path / "said"
    folder.mkdir()
    speak("Hey Stuart, go to the bathroom", folder / "1.wav", "en-us+f2")
    proc = subprocess.run([sys.executable, "-m", "stuart_bt.cli", "listen", "--source", f"file:{folder}",
                           "--speed", "20"], capture_output=True, text=True, timeout=120)
    out = proc.stdout
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    assert re.search(r"hearing   'hey Stuart, go to the bathroom\.?' \(confidence 0\.\d\d", out, re.IGNORECASE), out
    assert "mission 1 finished: succeeded" in out
    pids = [int(p) for p in re.findall(r"\w+ (\d+)", out.split("daemons   up:")[1].splitlines()[0])]
    assert len(pids) >= 4 and not [p for p in pids if _alive(p)]


def test_listening_to_a_microphone_that_is_not_there_is_one_clear_line(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "stuart_bt.cli", "listen", "--source", "mic:no such device"],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 1 and "Traceback" not in proc.stderr
    assert proc.stderr.strip().startswith("stuart-bt: no ") and len(proc.stderr.strip().splitlines()) == 1


def test_hey_stuart_then_a_pause_then_stop_over_the_robot_s_voice_still_stops_it(ears, tmp_path):
    """The shorter end of speech while the robot talks cuts "Hey Stuart ... stop" in two at a
    long pause; the bare wake phrase holds the robot's attention for the stop."""
    robot, mic, events, listener = ears
    robot.submit("Hey Stuart, what can you do?")
    _wait(events, lambda e: e.kind == "command" and e.data.get("family") == "tts" and e.data.get("cmd") == "say")
    mic.say(read_audio(speak("Hey Stuart.", tmp_path / "wake.wav", "en-gb+m3")), then_quiet_s=0.6)
    mic.say(read_audio(speak("stop", tmp_path / "stop.wav", "en-us")))
    stop = _wait(events, lambda e: e.kind == "utterance" and e.data.get("kind") == "stop")
    assert stop.data["wake_held"] is True
    heard = [e.data for e in events.events if e.kind == "heard"]
    assert len(heard) >= 2 and heard[0]["acted"] is False, "the wake phrase came as an utterance of its own"
    _wait(events, lambda e: e.kind == "command" and e.data.get("family") == "tts" and e.data.get("cmd") == "stop")
