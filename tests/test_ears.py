"""The ears daemon over the protocol: dry texts; the unitree backend hearing the G1's microphone
array (espeak-ng speech made here, sent as 16 kHz int16 UDP multicast on loopback, paced like
the robot) through the whisper pipeline in the daemon; and the robot's own recogniser's text on
DDS ``rt/audio_msg`` from a fake publisher on a private loopback domain. Each heard line's text
goes through the grammar to the intents it should give."""

from __future__ import annotations

import dataclasses
import time
from typing import Any

import pytest

from ears_fakes import GROUP, free_port
from speech_support import NEEDS_ESPEAK, joined
from stuart_bt.daemon.client import Request
from stuart_bt.daemon.supervisor import Supervisor
from stuart_bt.language.parse import Parser
from unitree_fake import start_failure, supervisor


@pytest.fixture
def ears(tmp_path):
    """``ears(backend, **options)``: a started ears daemon; shut down after the test."""
    made: list[Supervisor] = []

    def start(backend: str, **options: Any) -> Supervisor:
        made.append(supervisor(backend, "ears", options, tmp_path))
        made[-1].start()
        return made[-1]

    yield start
    for sup in made:
        sup.shutdown()


def heard(sup: Supervisor, request: Request, n: int, timeout: float = 60.0) -> list[dict[str, Any]]:
    """The first ``n`` utterances ``request`` (a listen) reported, waiting up to ``timeout`` s."""
    deadline = time.monotonic() + timeout
    while True:
        lines = [e.data["data"]["heard"] for e in sup.recorder.of_kind("daemon")
                 if e.data.get("id") == request.id and e.data.get("type") == "progress"]
        if len(lines) >= n or request.finished or time.monotonic() > deadline:
            return lines
        sup.wait(request, timeout=0.05)


def intents(text: str) -> list[tuple[str, str]]:
    return [(i.action, i.target) for i in Parser().parse(text).intents]


# -- dry -----------------------------------------------------------------------------------------

def test_dry_ears_hear_their_texts_one_per_progress_line_then_end(ears):
    sup = ears("dry", texts=["Hey Stuart, go to the bathroom", "Hey Stuart, stop"], interval_s=0.1)
    request = sup.client("ears").request("listen")
    lines = heard(sup, request, 2, timeout=10)
    assert sup.wait(request, timeout=10).ok, request.reason
    assert [line["source"] for line in lines] == ["dry", "dry"]
    assert [intents(line["text"]) for line in lines] == [[("navigate_to_marker", "bathroom")], [("stop", "")]]
    assert request.result == {"heard": 2}


def test_a_bad_option_refuses_to_start_with_one_clear_message(tmp_path):
    message = start_failure("ears", {"texts": "go"}, tmp_path, backend="dry")
    assert "ears dry options: 'texts' must be a list of strings" in message and "Traceback" not in message


def test_an_unknown_mode_refuses_to_start(tmp_path):
    pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")
    message = start_failure("ears", {"mode": "ears"}, tmp_path)
    assert "ears unitree options" in message and "mode" in message and "Traceback" not in message


# -- the robot's microphone array --------------------------------------------------------------------

@NEEDS_ESPEAK
def test_speech_sent_to_the_multicast_group_is_heard_in_the_daemon(ears, mic_array, lab_vocabulary, tmp_path):
    pytest.importorskip("faster_whisper", reason="the 'hearing' extra is not installed (make test installs it)")
    pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")
    from stuart_bt.hearing.audio import read_audio
    from stuart_bt.testing import speak

    port = free_port()
    vocabulary = {k: list(v) for k, v in dataclasses.asdict(lab_vocabulary).items() if k != "name"}
    sup = ears("unitree", mode="mic", group=GROUP, port=port, mic_interface="lo", vocabulary=vocabulary)
    client = sup.client("ears")
    request = client.request("listen")
    sup.wait(request, timeout=0.5)
    clips = [read_audio(speak("Hey Stuart, go to the bathroom", tmp_path / "go.wav", "en-gb+m3")),
             read_audio(speak("Hey Stuart, stop", tmp_path / "stop.wav", "en-us"))]
    mic_array(port).play(joined(clips))
    lines = heard(sup, request, 2)
    assert [intents(line["text"]) for line in lines] == [[("navigate_to_marker", "bathroom")], [("stop", "")]], lines
    assert all(line["source"] == "robot_mic" and 0 < line["confidence"] <= 1 for line in lines)
    assert lines[0]["audio_s"] > 1.0 and lines[1]["start_s"] > lines[0]["start_s"] >= 0.5
    cancel = sup.wait(client.request("cancel", {"target": request.id}), timeout=10)
    assert cancel.ok and request.error_code == "cancelled"


@NEEDS_ESPEAK
def test_a_unicast_loopback_address_works_as_the_group_and_listen_again_rejoins(ears, tmp_path):
    pytest.importorskip("faster_whisper", reason="the 'hearing' extra is not installed (make test installs it)")
    pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")
    port = free_port()
    sup = ears("unitree", mode="mic", group="127.0.0.1", port=port, mic_interface="127.0.0.1")
    client = sup.client("ears")
    for _ in range(2):  # a cancelled listen lets go of the port; the next one binds it again
        request = client.request("listen")
        sup.wait(request, timeout=0.5)
        assert request.status == "accepted", request.reason
        sup.wait(client.request("cancel", {"target": request.id}), timeout=10)
        assert request.error_code == "cancelled"


# -- the robot's own recogniser ------------------------------------------------------------------------

def test_robot_recogniser_text_plain_or_json_is_heard_and_a_malformed_sample_is_a_warning(ears, robot_recogniser):
    domain, fake = robot_recogniser
    sup = ears("unitree", mode="asr", interface="lo", domain=domain)
    request = sup.client("ears").request("listen")
    deadline = time.monotonic() + 30
    while not heard(sup, request, 1, timeout=0.3) and time.monotonic() < deadline:  # until DDS has matched
        fake.send("hello")
    mark = len(heard(sup, request, 100, timeout=0.3))
    fake.send('{"text": "Hey Stuart, go to the bathroom", "index": 3}')
    fake.send("{not json")
    fake.send("Hey Stuart, stop")
    lines = heard(sup, request, mark + 2, timeout=20)[mark:]
    assert [intents(line["text"]) for line in lines] == [[("navigate_to_marker", "bathroom")], [("stop", "")]], lines
    assert all(line["source"] == "robot_asr" and line["confidence"] is None for line in lines)
    warnings = [e.data["message"] for e in sup.recorder.of_kind("log") if e.data.get("level") == "warning"]
    assert any("rt/audio_msg" in w and "not JSON" in w for w in warnings), warnings
    assert not request.finished
