"""The wake phrase heard as sound-alike words ("face to earth, go to the workbench") is put back
when whisper agrees it may have been said; a greeting heard right, a name written as a name, or
an opening that sounds like something else is left alone, and talk stays talk. Real audio:
espeak-ng speaks at test time, noise is added at 10 dB SNR."""

from __future__ import annotations

import pytest

from speech_support import NEEDS_ESPEAK
from stuart_bt.hearing.audio import add_noise, read_audio
from stuart_bt.hearing.wake_repair import SOUND_TOLERANCE, phone_distance, wake_repaired
from stuart_bt.language.parse import Parser
from stuart_bt.language.resolve import Resolver
from stuart_bt.testing import lab_markers, speak

pytest.importorskip("pocketsphinx", reason="the 'hearing' extra is not installed (make test installs it)")


@pytest.fixture(scope="module")
def dictionary():
    from stuart_bt.hearing.sphinx import GrammarRecogniser

    return GrammarRecogniser().pronunciations


def test_a_word_has_every_pronunciation_the_dictionary_gives(dictionary):
    assert dictionary("stuart") == ["S T UW ER T", "S T Y UW ER T", "S T AO R T"]
    assert dictionary("hey") == ["HH EY"]
    assert dictionary("labrat")  # not in the dictionary: built from pieces it knows
    assert dictionary("☃") == []


def test_the_phone_distance_counts_a_sound_of_the_same_kind_and_an_h_as_half():
    assert phone_distance(["HH", "EY", "S", "T"], ["HH", "EY", "S", "T"]) == 0.0
    assert phone_distance(["T"], ["D"]) == 0.5  # two stops
    assert phone_distance(["T"], ["M"]) == 1.0
    assert phone_distance(["HH", "EY"], ["F", "EY"]) == 0.5  # "hey" heard as "fey"
    assert phone_distance(["HH", "EY"], ["EY"]) == 0.5
    assert phone_distance(["S", "T"], ["T"]) == 1.0
    assert phone_distance(["K", "EY", "S"], ["HH", "EY", "S"]) == phone_distance(["HH", "EY", "S"], ["K", "EY", "S"])


@pytest.mark.parametrize(("heard", "repaired"), [
    ("face to earth, go to the workbench and give me a hug.", "hey Stuart, go to the workbench and give me a hug."),
    ("taste you at go to the station 4.", "hey Stuart, go to the station 4."),
    ("case you stop.", "hey Stuart, stop."),
    ("case to it, turn left 90 degrees.", "hey Stuart, turn left 90 degrees."),
])
def test_an_opening_that_sounds_like_the_wake_phrase_is_offered_as_it(dictionary, heard, repaired):
    assert wake_repaired(heard, "Stuart", dictionary) == repaired


@pytest.mark.parametrize("heard", [
    "hey Steve, go to the kitchen.",  # the greeting heard right: the name after it is someone else's
    "okay guys, go to the kitchen.",
    "Stacey, go to the workbench.",  # whisper wrote a name
    "listen everyone, pick up the cup.",
    "I think the kitchen is closed today.",
    "in case you go to the kitchen, take the cup.",
    "hey Stuart, go to the kitchen.",  # the name is there: the wake filter reads it
    "thanks Stuart, turn around.",
    "stop.",  # nothing before the rest
])
def test_an_opening_that_is_a_greeting_a_name_or_other_words_is_left_alone(dictionary, heard):
    assert wake_repaired(heard, "Stuart", dictionary) is None


def test_talk_that_opens_with_such_sounds_is_offered_too_and_left_to_whisper_to_judge(dictionary):
    # the sounds alone cannot tell: whisper's score against the sound does (test below)
    assert wake_repaired("face to face meetings are better.", "Stuart", dictionary) == (
        "hey Stuart, face meetings are better.")


def test_another_robots_name_gives_its_own_wake_phrase(dictionary):
    assert wake_repaired("ex ray, turn left.", "Xray", dictionary) == "hey Xray, turn left."
    assert wake_repaired("ex ray, turn left.", "Stuart", dictionary) is None


def test_the_tolerance_lets_in_what_noise_made_of_the_wake_phrase_and_keeps_out_everyday_openings(dictionary):
    from stuart_bt.hearing.wake_repair import _phones

    wake = [*_phones("hey stuart", dictionary), *_phones("stuart", dictionary)]

    def far(words: str) -> float:
        return min(phone_distance(h, t) / len(t) for h in _phones(words, dictionary) for t in wake)

    for misheard in ("face to", "case you", "taste you", "face to earth", "case tour", "thanks to it"):
        assert far(misheard) <= SOUND_TOLERANCE, misheard
    for everyday in ("okay team", "in case you", "listen everyone", "hey guys", "so today", "the"):
        assert far(everyday) > SOUND_TOLERANCE, everyday


# (said, voice, speed, noise seed): whisper alone heard the wake phrase as other words ("case
# you", "face to", "thanks to it", "case viewer"), noise suppressed as always; tiny.en, beam 5
LOST_WAKE = [
    ("Hey Stuart, turn left 90 degrees", "en-gb-x-rp", 150, 1),
    ("Hey Stuart, go to the entrance", "en-gb-x-rp", 150, 2),
    ("Hey Stuart, pick up the cup", "en-us+f2", 150, 2),
    ("Hey Stuart, go to the kitchen and wave", "en-gb-x-rp", 150, 2),
    ("Hey Stuart, turn around", "en-gb-x-rp", 170, 1),
    ("Hey Stuart, stop", "en-gb-x-rp", 150, 1),
]


@pytest.fixture(scope="module")
def resolver():
    return Resolver.from_files(lab_markers())


def _meant(text: str, parser: Parser, resolver: Resolver) -> list[tuple[str, str]]:
    intents = parser.parse(text).intents
    return [(i.action, r.name if r is not None and r.ok else i.target)
            for i, r in zip(intents, resolver.resolve_all(intents), strict=True)]


@NEEDS_ESPEAK
def test_a_command_whose_wake_phrase_noise_took_is_acted_on(recogniser, resolver, tmp_path):
    from stuart_bt.hearing.pipeline import transcribe

    parser, vocabulary = Parser(), resolver.vocabulary()
    repaired = 0
    for n, (said, voice, speed, seed) in enumerate(LOST_WAKE):
        clip = add_noise(read_audio(speak(said, tmp_path / f"{n}.wav", voice, speed)), 10.0, seed=seed)
        alone = transcribe(recogniser.whisper, clip, vocabulary).transcript
        both = transcribe(recogniser, clip, vocabulary).transcript
        print(f"{said!r} ({voice}, {speed} wpm): whisper {alone.text!r}; heard {both.text!r}")
        assert _meant(both.text, parser, resolver) == _meant(said, parser, resolver)
        repaired += not parser.parse(alone.text).wake
    assert repaired >= 4  # most of them were commands only because the wake phrase was put back


# said to someone else, or talk that opens with sounds like the wake phrase: never a command
NOT_TO_THE_ROBOT = [
    ("Hey Steve, go to the kitchen", "en-us", 160),
    ("Stacy, pick up the cup", "en-gb", 150),
    ("Okay team, go to the workbench", "en-us+m3", 170),
    ("In case you go to the kitchen, take the cup", "en-gb+f3", 160),
    ("Just to be sure, the entrance is closed", "en-us+f2", 150),
    ("Based on the map, the kitchen is near", "en-gb-x-rp", 160),
    ("Hey Stan, go to the station 3", "en-us+f2", 160),  # "face 10, ..." to whisper, "hey stuart" to the grammar
]


@NEEDS_ESPEAK
@pytest.mark.parametrize("snr_db", [None, 10.0])
def test_words_said_to_someone_else_stay_talk(recogniser, resolver, tmp_path, snr_db):
    from stuart_bt.hearing.pipeline import is_speech, transcribe

    parser, vocabulary = Parser(), resolver.vocabulary()
    for n, (said, voice, speed) in enumerate(NOT_TO_THE_ROBOT):
        clip = read_audio(speak(said, tmp_path / f"{n}.wav", voice, speed))
        if snr_db is not None:
            clip = add_noise(clip, snr_db, seed=n)
        heard = transcribe(recogniser, clip, vocabulary).transcript
        acted = _meant(heard.text, parser, resolver) if is_speech(heard) else []
        print(f"{said!r} ({snr_db or 'no'} dB SNR): heard {heard.text!r} -> {acted}")
        assert acted == []


@pytest.mark.parametrize(("heard", "someone_else"), [
    ("hey Steve, go to the kitchen.", True),
    ("Hi Sarah, pick up the cup.", True),
    ("Stacey, go to the workbench.", True),
    ("hey Stewart, go to the kitchen.", False),  # the robot's name spelled another way
    ("Hey Stuart, go to the kitchen.", False),
    ("Steward, stop.", False),
    ("hey guys, go to the kitchen.", False),  # not written as a name
    ("Sorry, go to the kitchen.", False),  # a word a sentence opens with
    ("I think Steve went to the kitchen.", False),  # no one addressed
])
def test_a_name_written_as_someone_elses_is_told_from_the_robots_by_its_sounds(dictionary, heard, someone_else):
    from stuart_bt.hearing.wake_repair import said_to_someone_else

    assert said_to_someone_else(heard, "Stuart", dictionary) is someone_else


@pytest.mark.parametrize(("heard", "names"), [
    ("hey Stuart, go to the kitchen.", True),
    ("Stewart, stop.", True),
    ("steward, stop.", True),
    ("face 10, go to the station 3.", False),
    ("hey Steve, go to the kitchen.", False),
    ("", False),
])
def test_the_robots_name_is_found_however_it_is_spelled(dictionary, heard, names):
    from stuart_bt.hearing.wake_repair import names_the_robot

    assert names_the_robot(heard, "Stuart", dictionary) is names


def test_a_correction_that_puts_the_robots_name_back_is_held_to_the_wake_repairs_margin(recogniser):
    from stuart_bt.hearing.second_opinion import CORRECTION_MARGIN, REPAIR_MARGIN
    from stuart_bt.hearing.vocabulary import Vocabulary

    vocabulary = Vocabulary()
    assert REPAIR_MARGIN < CORRECTION_MARGIN
    assert recogniser._margin("face 10, go to the station 3.", "hey Stuart, go to the station 3.",
                              vocabulary) == REPAIR_MARGIN
    assert recogniser._margin("hey Stuart, and enter around.", "hey Stuart, and then turn around.",
                              vocabulary) == CORRECTION_MARGIN  # the name was heard: other words corrected
    assert recogniser._margin("Stewart, stop.", "Stuart, stop.", vocabulary) == CORRECTION_MARGIN
