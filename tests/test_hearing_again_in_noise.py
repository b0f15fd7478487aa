"""An utterance said in noise and not heard as a command is heard a second time as it came (no
noise suppression), and the second hearing is taken when only it is a command; clean speech, and
a command heard as one, are heard once; talk in noise stays talk. Real audio: espeak-ng speaks at
test time, noise is added at 10 dB SNR; the real recogniser, with a count of its hearings."""

from __future__ import annotations

import pytest

from speech_support import NEEDS_ESPEAK
from stuart_bt.hearing.audio import add_noise, read_audio
from stuart_bt.hearing.pipeline import NOISY_SHARE, _share_removed, transcribe
from stuart_bt.hearing.second_opinion import COMMAND_MARGIN
from stuart_bt.language.parse import Parser
from stuart_bt.language.readings import READING_MARGIN, choose_reading
from stuart_bt.language.resolve import Resolver
from stuart_bt.testing import lab_markers, speak

pytest.importorskip("pocketsphinx", reason="the 'hearing' extra is not installed (make test installs it)")


class Counting:
    """The real recogniser, counting how often it hears."""

    def __init__(self, engine) -> None:
        self.engine, self.calls = engine, 0

    def transcribe(self, samples, vocabulary):
        self.calls += 1
        return self.engine.transcribe(samples, vocabulary)

    def heard_as_command(self, heard, vocabulary) -> bool:
        return self.engine.heard_as_command(heard, vocabulary)


# (said, voice, speed, noise seed): at 10 dB SNR the first hearing, noise suppressed, was no
# command ("... and enter the lounge", "... give me your hand"; "case do this, find the bottle" for "find the
# book" is now heard as "hey Stuart, find the bottle." the first time: the grammar engine heard "bottle" too)
HEARD_RIGHT_THE_SECOND_TIME = [
    ("Hey Stuart, go to the Electronics bench and then turn around", "en-gb+m3", 150, 55),
    ("Hey Stuart, go to the entrance and shake hands", "en-gb-x-rp", 170, 69),
    ("Hey Stuart, could you go to the Kitchen please", "en-us+f2", 160, 98),
    ("Hey Stuart, turn right 45 degrees", "en-us+m3", 175, 178),
    ("Hey Stuart, give me a hug", "en-gb-x-rp", 170, 189),
]


@pytest.fixture(scope="module")
def lab():
    resolver = Resolver.from_files(lab_markers())
    return Parser(), resolver, resolver.vocabulary()


def _meant(text: str, parser: Parser, resolver: Resolver) -> list[tuple[str, str]]:
    intents = parser.parse(text).intents
    return [(i.action, r.name if r is not None and r.ok else i.target)
            for i, r in zip(intents, resolver.resolve_all(intents), strict=True)]


def test_the_margin_is_the_language_stages():
    assert COMMAND_MARGIN == READING_MARGIN


@NEEDS_ESPEAK
def test_a_command_misheard_in_noise_is_heard_again_and_acted_on(recogniser, lab, tmp_path):
    parser, resolver, vocabulary = lab
    again = 0
    for n, (said, voice, speed, seed) in enumerate(HEARD_RIGHT_THE_SECOND_TIME):
        clip = add_noise(read_audio(speak(said, tmp_path / f"{n}.wav", voice, speed)), 10.0, seed=seed)
        counting = Counting(recogniser)
        readings = transcribe(counting, clip, vocabulary).transcript.readings()
        acted_on = readings[choose_reading(readings, parser, resolver)][0]
        print(f"{said!r}: heard {counting.calls}x, {acted_on!r} of {readings[:3]}")
        assert _meant(acted_on, parser, resolver) == _meant(said, parser, resolver)
        again += counting.calls == 2
    assert again >= 4  # most were commands only because they were heard again


@NEEDS_ESPEAK
def test_clean_speech_is_heard_once_even_when_it_is_no_command(recogniser, lab, tmp_path):
    _, _, vocabulary = lab
    clip = read_audio(speak("Hey Stuart, what a lovely morning it is", tmp_path / "talk.wav", "en-us", 160))
    assert _share_removed(clip, clip) == 0.0
    counting = Counting(recogniser)
    transcribe(counting, clip, vocabulary)
    assert counting.calls == 1


@NEEDS_ESPEAK
def test_talk_in_noise_is_heard_again_and_stays_talk(recogniser, lab, tmp_path):
    parser, _, vocabulary = lab
    for n, said in enumerate(["The kitchen is closed on Fridays", "Hey Steve, go to the kitchen",
                              "I think the robot went to the workbench"]):
        clip = add_noise(read_audio(speak(said, tmp_path / f"t{n}.wav", "en-gb", 160)), 10.0, seed=n)
        counting = Counting(recogniser)
        heard = transcribe(counting, clip, vocabulary).transcript
        print(f"{said!r}: heard {counting.calls}x, {heard.readings()[:2]}")
        assert counting.calls == 2 and parser.parse(heard.text).intents == []


def test_noise_is_told_by_the_share_of_energy_suppression_took_out():
    import numpy as np

    clip = (np.sin(np.linspace(0, 2000, 16_000)) * 8000).astype(np.int16)
    assert _share_removed(clip, clip) == 0.0
    assert _share_removed(clip, (clip * 0.9).astype(np.int16)) > NOISY_SHARE
    assert _share_removed(np.zeros(100, np.int16), np.zeros(100, np.int16)) == 0.0
