"""The unitree tts backend against the fake voice service: TtsMaker payloads, PlayStream chunks of
16 kHz mono int16, volume and LED at start-up, cancel with PlayStop, and a missing piper voice."""

from __future__ import annotations

import shutil

import pytest

from stuart_bt.daemon.supervisor import Supervisor
from unitree_fake import start_failure

pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")
NEEDS_ESPEAK = pytest.mark.skipif(shutil.which("espeak-ng") is None,
                                  reason="local synthesis needs espeak-ng (apt-get install espeak-ng)")


@pytest.fixture
def tts(unitree_daemon):
    return lambda factor=8.0, **options: unitree_daemon("tts", factor, **options)


def say(sup: Supervisor, text: str, timeout: float = 20.0):
    return sup.wait(sup.client("tts").request("say", {"text": text}), timeout=timeout)


def test_the_robot_voice_gets_the_text_and_speaker_and_the_tree_gets_a_duration(robot, tts):
    sup = tts(volume=70, led=[0, 128, 255])
    assert robot.rpc("voice", 1006)[-1]["parameter"] == {"volume": 70}
    assert robot.rpc("voice", 1010)[-1]["parameter"] == {"R": 0, "G": 128, "B": 255}
    result = say(sup, "Hello and welcome to the robotics lab")
    assert result.ok, result.reason
    call = robot.rpc("voice", 1001)[-1]["parameter"]
    assert (call["text"], call["speaker_id"]) == ("Hello and welcome to the robotics lab", 1)
    assert result.accepted_data["duration"] > 1.0
    assert result.result["duration"] == result.accepted_data["duration"]


@NEEDS_ESPEAK
def test_local_speech_streams_16_khz_int16_in_three_second_chunks(robot, tts):
    sup = tts(engine="espeak-ng", lead_seconds=100.0)  # send every chunk at once: the test checks them all
    before = len(robot.rpc("voice", 1003))
    text = "This sentence is long enough to need more than one chunk of three seconds of audio to be spoken aloud."
    result = say(sup, text)
    assert result.ok, result.reason
    chunks = robot.rpc("voice", 1003)[before:]
    duration = result.accepted_data["duration"]
    assert len(chunks) == result.accepted_data["chunks"] >= 2
    assert all(c["binary"] == 3 * 16000 * 2 for c in chunks[:-1])  # 3 s of int16 at 16 kHz
    assert sum(c["binary"] for c in chunks) == round(duration * 16000) * 2
    assert {c["parameter"]["app_name"] for c in chunks} == {"stuart_bt"}
    assert len({c["parameter"]["stream_id"] for c in chunks}) == 1


@NEEDS_ESPEAK
def test_cancelling_streamed_speech_sends_play_stop(robot, tts):
    sup = tts(factor=1.0, engine="espeak-ng")
    client = sup.client("tts")
    mark = len(robot.records)
    request = client.request("say", {"text": "A long sentence that will be cut short by a cancel from the tree."})
    robot.wait_for(lambda r: r.get("api") == 1003, what="the first chunk", since=mark)
    sup.wait(client.request("cancel", {"target": request.id}), timeout=5)
    assert request.error_code == "cancelled"
    assert robot.rpc("voice", 1004)[-1]["parameter"] == {"app_name": "stuart_bt"}


def test_piper_without_a_voice_file_refuses_to_start_with_one_clear_message(robot, tmp_path):
    message = start_failure("tts", robot.options(engine="piper"), tmp_path)
    assert "piper needs the 'piper' program and a local voice model (piper_model option)" in message
    assert "Traceback" not in message


def test_a_voice_service_error_fails_the_utterance_with_its_code(robot, tts):
    sup = tts()
    robot.fault("voice", 1001, 3204)
    result = say(sup, "hello")
    assert (result.error_code, result.vendor_code) == ("backend_error", 3204)
    assert "rejected the parameters" in result.reason
