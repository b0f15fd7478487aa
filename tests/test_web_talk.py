"""Push-to-talk in a real browser: Chromium's fake microphone plays a sentence spoken by
espeak-ng (made here); holding the console's button for the length of it sends the audio over
``/ws/audio``; the console shows what was heard and the mission for the place starts."""

from __future__ import annotations

import shutil
import subprocess
import wave
from collections.abc import Callable
from pathlib import Path

import pytest

from web_support import Served, browser_tests, chromium_page

playwright_mod = browser_tests()
pytest.importorskip("faster_whisper", reason="hearing needs the hearing extra (make test installs it)")

pytestmark = pytest.mark.slow
WAIT = 60_000
SOX = shutil.which("sox")


def microphone_wav(tmp_path: Path, text: str) -> tuple[Path, float]:
    """``text`` spoken, with half a second of quiet either side, as the 48 kHz mono 16-bit WAV
    Chromium's fake capture device reads; and its length in seconds."""
    from stuart_bt.testing import speak

    if SOX is None or shutil.which("espeak-ng") is None:
        pytest.skip("needs sox and espeak-ng (make test installs them)")
    said = speak(text, tmp_path / "said.wav")
    wav = tmp_path / "microphone.wav"
    subprocess.run([SOX, str(said), "-r", "48000", "-c", "1", "-b", "16", str(wav), "pad", "0.5", "0.5"],
                   check=True, timeout=30)
    with wave.open(str(wav)) as w:
        return wav, w.getnframes() / w.getframerate()


@pytest.fixture
def talking_page(tmp_path: Path):
    wav, length = microphone_wav(tmp_path, "Hey Stuart, go to the kitchen")
    flags = ("--use-fake-ui-for-media-stream", "--use-fake-device-for-media-stream",
             f"--use-file-for-fake-audio-capture={wav}%noloop", "--autoplay-policy=no-user-gesture-required")
    for page in chromium_page(playwright_mod, tmp_path, flags):
        with Served("--mission", "--backend", "dry", "--speed", "20") as served:
            page.goto(served.url + "#console")
            page.wait_for_selector("#conn.ok")
            yield page, length


def hold(page, length: float, press: Callable[[], object], release: Callable[[], object]) -> str:
    """Press, hold while the fake microphone plays the sentence, release: the console's line
    saying what was heard (it must name the kitchen)."""
    press()
    page.wait_for_selector("#talk-button.recording")
    page.wait_for_timeout(int(length * 1000) + 500)
    release()
    spoken = page.locator("#console-log li.spoken").first
    spoken.wait_for(timeout=WAIT)
    text = spoken.text_content()
    assert "kitchen" in text.lower(), text
    return text


def test_holding_the_button_says_it_and_a_mission_starts(talking_page):
    page, length = talking_page
    page.hover("#talk-button")
    spoken = hold(page, length, page.mouse.down, page.mouse.up)
    assert "tasks" in spoken
    log = page.locator("#console-log")
    page.wait_for_selector('#queue-table tr[data-mission="1"]', timeout=WAIT)
    assert "navigate_to_marker(target=kitchen)" in log.locator("li.heard").first.text_content()
    assert "push-to-talk:" not in log.text_content()


def test_the_space_bar_talks_unless_typing(talking_page):
    page, length = talking_page
    page.focus("#say-input")
    page.keyboard.down("Space")  # typing a space: no recording
    page.keyboard.up("Space")
    assert page.input_value("#say-input") == " "
    assert page.locator("#talk-button.recording").count() == 0
    page.locator("#plan-view").click()  # the text box loses the focus
    hold(page, length, lambda: page.keyboard.down("Space"), lambda: page.keyboard.up("Space"))
    page.wait_for_selector('#queue-table tr[data-mission="1"]', timeout=WAIT)
