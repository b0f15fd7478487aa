"""``listen --source robot``: the G1's own ears (its microphone array, or its recogniser's text)
heard through the ears daemon, against the fakes on loopback, drive missions like any other
source; the robot's own voice caught by its microphones never commands it, a stop said over it
still stops it, and Ctrl-C ends the ears daemon with the rest."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from ears_fakes import GROUP, free_port
from speech_support import NEEDS_ESPEAK
from speech_support import wait_event as _wait
from stuart_bt.core.events import Event, EventRecorder
from stuart_bt.mission.executor import MissionExecutor, MissionOptions
from stuart_bt.mission.listening import RobotVoice
from stuart_bt.mission.robot_ears import RobotEars

pytest.importorskip("unitree_sdk2py", reason="the robot's ears need the 'robot' extra (make test installs it)")


def _listening(e: Event) -> bool:
    return e.kind == "daemon" and e.data.get("family") == "ears" and e.data.get("type") == "accepted"


def _tts(cmd: str):
    return lambda e: e.kind == "command" and e.data.get("family") == "tts" and e.data.get("cmd") == cmd


def test_the_robot_voice_knows_when_it_spoke_over_an_utterance():
    robot = MissionExecutor(MissionOptions(backend="dry"))
    voice = RobotVoice(robot.events)
    before = time.perf_counter()
    robot.events.publish("command", family="tts", cmd="say", id="t1")
    time.sleep(0.2)
    robot.events.publish("daemon", family="tts", type="done", id="t1")
    after = time.perf_counter()
    assert voice.spoke_over(before + 0.05, before + 0.1), "began while the robot talked"
    assert voice.spoke_over(before - 0.05, after + 0.01), "mostly over the robot's voice"
    assert not voice.spoke_over(after + 0.01, after + 1.0), "after it stopped talking"
    assert not voice.spoke_over(before - 1.0, before + 0.05), "mostly before it began"


@pytest.fixture
def robot_mic(mic_array, tmp_path):
    """A dry robot whose ears are the ears daemon on the fake microphone array."""
    pytest.importorskip("faster_whisper", reason="the 'hearing' extra is not installed (make test installs it)")
    port = free_port()
    robot = MissionExecutor(MissionOptions(backend="dry", speed=0.5))
    events = EventRecorder(robot.events)
    ears = RobotEars(robot, "robot", {"group": GROUP, "port": port, "mic_interface": "lo", "interface": "lo"})
    robot.start()
    try:
        ears.start()
        _wait(events, _listening)
        yield robot, mic_array(port), events, ears
    finally:
        ears.close()
        robot.close()


@NEEDS_ESPEAK
def test_speech_at_the_robot_s_microphones_runs_a_mission_and_its_own_voice_does_not(robot_mic, tmp_path):
    from stuart_bt.hearing.audio import read_audio
    from stuart_bt.testing import speak

    robot, mic, events, ears = robot_mic
    mic.play(read_audio(speak("Hey Stuart, go to the bathroom", tmp_path / "go.wav", "en-gb+m3")))
    said = _wait(events, lambda e: e.kind == "utterance")
    assert said.data["source"] == "robot_mic" and [i["target"] for i in said.data["intents"]] == ["bathroom"]
    assert 0 < said.data["confidence"] <= 1 and said.data["audio_s"] > 1
    _wait(events, lambda e: e.kind == "mission" and e.data.get("phase") == "started")

    robot.submit("Hey Stuart, what can you do?")  # typed: the robot answers aloud, slowly (speed 0.5)
    _wait(events, _tts("say"))
    mic.play(read_audio(speak("Hey Stuart, go to the kitchen", tmp_path / "echo.wav", "en-us")))
    echo = _wait(events, lambda e: e.kind == "heard" and "kitchen" in e.data["text"].lower())
    assert echo.data["acted"] is False and echo.data["reason"] == "over_robot_speech", echo.data
    assert ears.voice.speaking, "the reply should still be playing (else this test proves nothing)"
    mic.play(read_audio(speak("Hey Stuart, stop", tmp_path / "stop.wav", "en-us+m3")))
    stop = _wait(events, lambda e: e.kind == "utterance" and e.data.get("kind") == "stop")
    assert stop.data["source"] == "robot_mic"
    _wait(events, _tts("stop"))
    missions = [e for e in events.events if e.kind == "mission" and e.data.get("phase") == "started"]
    assert len(missions) == 1, "the robot's own voice started a mission"


def _ears_daemons() -> set[int]:
    found = set()
    for proc in Path("/proc").iterdir():
        if proc.name.isdigit():
            try:
                if b"stuart_bt.skills.ears" in (proc / "cmdline").read_bytes():
                    found.add(int(proc.name))
            except OSError:
                continue
    return found


def test_listen_to_the_robot_s_recogniser_runs_missions_and_ctrl_c_ends_its_ears(robot_recogniser):
    domain, fake = robot_recogniser
    env = {**os.environ, "STUART_UNITREE_INTERFACE": "lo", "STUART_UNITREE_DOMAIN": str(domain)}
    before = _ears_daemons()
    argv = [sys.executable, "-m", "stuart_bt.cli", "listen", "--source", "robot:asr", "--speed", "20"]
    proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=env, start_new_session=True)
    lines: list[str] = []
    reader = threading.Thread(target=lambda: lines.extend(iter(proc.stdout.readline, "")), daemon=True)
    reader.start()

    def printed(pattern: str, timeout: float = 30.0, say: str | None = None) -> bool:
        end = time.monotonic() + timeout
        while time.monotonic() < end and proc.poll() is None:
            if say:
                fake.send(say)
            if any(re.search(pattern, line) for line in list(lines)):
                return True
            time.sleep(0.3)
        return False

    try:
        assert printed(r"hearing\s+'hello'", timeout=60, say="hello"), "".join(lines) + proc.stderr.read()
        fake.send("Hey Stuart, go to the bathroom")
        assert printed(r"mission 1 finished: succeeded"), "".join(lines)
        ears = _ears_daemons() - before
        assert len(ears) == 1, ears
        os.killpg(proc.pid, signal.SIGINT)
        assert proc.wait(timeout=20) == 130
        assert "Traceback" not in proc.stderr.read()
        assert not ears & _ears_daemons(), "the ears daemon outlived the listen command"
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        reader.join(5)
