"""The command-only grammar engine (pocketsphinx held to a JSGF grammar made from the robot's
vocabulary) as whisper's second opinion, engine ``whisper+grammar``: the grammar says only what
the command grammar reads, every word in it can be pronounced, a command whisper misheard is
heard right, and talk, which the grammar engine alone hears as some command, stays talk. Real
audio: espeak-ng speaks at test time."""

from __future__ import annotations

import random
import re

import pytest

from speech_support import NEEDS_ESPEAK
from stuart_bt.hearing.audio import add_noise, read_audio
from stuart_bt.hearing.command_grammar import jsgf, matcher, normalise, rules, words
from stuart_bt.hearing.pronounce import by_rule, number_words, pronounce
from stuart_bt.hearing.second_opinion import splice, splices
from stuart_bt.hearing.vocabulary import Vocabulary
from stuart_bt.language.parse import Parser
from stuart_bt.language.readings import choose_reading, rival_reading
from stuart_bt.language.resolve import Resolver
from stuart_bt.testing import VOICES, lab_markers, speak

pytest.importorskip("pocketsphinx", reason="the 'hearing' extra is not installed (make test installs it)")

PHONES = frozenset({"AA", "AE", "AH", "AO", "AW", "AY", "B", "CH", "D", "DH", "EH", "ER", "EY", "F", "G", "HH", "IH",
                    "IY", "JH", "K", "L", "M", "N", "NG", "OW", "OY", "P", "R", "S", "SH", "T", "TH", "UH", "UW", "V",
                    "W", "Y", "Z", "ZH"})  # the en-US model's phones


@pytest.fixture(scope="module")
def resolver():
    return Resolver.from_files(lab_markers())


@pytest.fixture(scope="module")
def engine():
    from stuart_bt.hearing.recognisers import make_recogniser

    pytest.importorskip("faster_whisper", reason="the 'hearing' extra is not installed (make test installs it)")
    return make_recogniser("whisper+grammar")


def _expand(rule: str, table: dict[str, str], rng: random.Random) -> list[str]:
    """One random sentence of a JSGF rule body (alternatives, groups, optionals, references)."""
    tokens = re.findall(r"<[^>]+>|[()\[\]|]|[^\s()\[\]|<>]+", rule)

    def sequence(i: int) -> tuple[list[list[str]], int]:
        alternatives: list[list[str]] = [[]]
        while i < len(tokens) and tokens[i] not in (")", "]"):
            token = tokens[i]
            if token == "|":
                alternatives.append([])
                i += 1
            elif token in ("(", "["):
                inner, i = sequence(i + 1)
                if token == "(" or rng.random() < 0.5:
                    alternatives[-1] += rng.choice(inner)
                i += 1
            elif token.startswith("<"):
                alternatives[-1] += _expand(table[token[1:-1]], table, rng)
                i += 1
            else:
                alternatives[-1].append(token)
                i += 1
        return alternatives, i

    alternatives, _ = sequence(0)
    return rng.choice(alternatives)


def test_every_sentence_of_the_grammar_is_a_clear_command_to_the_robot(resolver):
    vocabulary = resolver.vocabulary()
    table = rules(vocabulary)
    parser, rng = Parser(), random.Random(14)
    sentence = matcher(vocabulary)
    for _ in range(400):
        said = splice("", _expand(table["addressed"], table, rng), vocabulary)  # as the engine writes it
        result = parser.parse(said)
        resolved = resolver.resolve_all(result.intents)
        print(f"{said!r} -> {[(i.action, i.target) for i in result.intents]}")
        assert result.wake and result.intents, said
        # asked about as if typed: an amount past the robot's limits ("walk 15 metres"), and a
        # word of a place's name the command grammar did not read after "find the cup in the"
        # ("Robot arms": "arms" is read as a part of the body there)
        unread = [w for d in result.doubt if d.reason == "unused" for w in d.detail.split(": ", 1)[1].split()]
        assert {d.reason for d in result.doubt} <= {"amount", "unused"}, said
        assert all(any(w in place.lower().split() for place in vocabulary.places) for w in unread), said
        assert all(r is None or r.ok for r in resolved), said
        assert sentence.fullmatch(normalise(said)), said


def test_the_grammar_names_every_place_object_and_gesture_of_the_vocabulary():
    vocabulary = Vocabulary.of("Robbie", places=["Loading bay", "lab_7"], objects=["mug"], gestures=["wave"])
    grammar = jsgf(vocabulary)
    assert "(loading bay)" in grammar and "(lab 7)" in grammar and "mug" in grammar and "robbie" in grammar
    sentence = matcher(vocabulary)
    for said in ("hey Robbie, go to the loading bay.", "Robbie, go to lab 7 and pick up the mug", "hi robbie, wave"):
        assert sentence.fullmatch(normalise(said)), said
    for said in ("hey Stuart, go to the loading bay", "hey Robbie, go to the kitchen", "hey Robbie, how are you?"):
        assert not sentence.fullmatch(normalise(said)), said


def test_words_missing_from_the_dictionary_are_pronounced_from_pieces_it_knows():
    pytest.importorskip("pocketsphinx")
    from pocketsphinx import Decoder, get_model_path

    lookup = Decoder(hmm=get_model_path("en-us/en-us"), dict=get_model_path("en-us/cmudict-en-us.dict"),
                     loglevel="FATAL").lookup_word
    assert lookup("3d") is None and lookup("xray") is None and lookup("labrat") is None
    assert pronounce("3d", lookup) == "TH R IY D IY"  # a number and a letter
    assert pronounce("1", lookup) == "W AH N"
    assert pronounce("270", lookup) == f"{lookup('two')} {lookup('hundred')} {lookup('seventy')}"
    assert pronounce("xray", lookup) == f"{lookup('x')} {lookup('ray')}"  # two dictionary words run together
    assert pronounce("labrat", lookup) == f"{lookup('lab')} {lookup('rat')}"
    assert pronounce("pcb", lookup) == f"{lookup('p')} {lookup('c')} {lookup('b')}"  # no vowel: spelled
    assert pronounce("kitchen", lookup) == lookup("kitchen")
    assert by_rule("zorbleth") == "Z AO R B L EH TH"  # nothing known: letter-to-sound rules
    for word in ("3d", "xray", "labrat", "pcb", "zorbleth", "qwfxz"):
        assert set(pronounce(word, lookup).split()) <= PHONES, word
    assert number_words(180) == ["one", "hundred", "eighty"]


def test_every_word_of_the_lab_grammar_has_a_pronunciation(resolver):
    from pocketsphinx import Decoder, get_model_path

    lookup = Decoder(hmm=get_model_path("en-us/en-us"), dict=get_model_path("en-us/cmudict-en-us.dict"),
                     loglevel="FATAL").lookup_word
    for word in words(jsgf(resolver.vocabulary())):
        phones = pronounce(word, lookup)
        assert phones and set(phones.split()) <= PHONES, word


@NEEDS_ESPEAK
def test_a_place_no_rule_can_pronounce_is_left_out_and_the_others_are_heard(tmp_path):
    from stuart_bt.hearing.sphinx import GrammarRecogniser

    engine = GrammarRecogniser()
    vocabulary = Vocabulary.of("Stuart", places=["kitchen", "厨房"], objects=["cup"], gestures=["wave"])
    assert engine.pronunciation("厨房") in ("", None)
    clip = read_audio(speak("Hey Stuart, go to the kitchen", tmp_path / "said.wav", "en-gb+m3", 160))
    assert engine.hear(clip, vocabulary)[-5:] == ["stuart", "go", "to", "the", "kitchen"]  # "hey" or "hi"


def test_the_grammar_engines_words_go_into_whispers_reading_where_they_differ(resolver):
    vocabulary = resolver.vocabulary()
    for whisper, grammar, spliced in (
            ("hey Stuart, go to the kitchen and enter around.", "hey stuart go to the kitchen and then turn around",
             "hey Stuart, go to the kitchen and then turn around."),
            ("head to it, turn right 45 degrees.", "hey stuart turn right forty five degrees",
             "hey Stuart, turn right 45 degrees."),
            ("Face to it, go to the three printers.", "hey stuart go to the 3d printers",
             "Hey Stuart, go to the 3D printers."),
            ("hey Stuart, pick up my screwdriver.", "hey stuart pick up my screwdriver now",
             "hey Stuart, pick up my screwdriver now."),
            ("", "stuart give me a high five", "Stuart, give me a high five")):
        assert splice(whisper, grammar.split(), vocabulary) == spliced


def test_every_choice_of_the_places_where_they_differ_is_a_candidate(resolver):
    vocabulary = resolver.vocabulary()
    heard = "case Stuart, I'm the screwdriver."
    candidates = splices(heard, ["hey", "stuart", "find", "the", "screwdriver", "and", "hug"], vocabulary)
    assert "hey Stuart, find the screwdriver." in candidates  # the wake phrase and "find", not the extra "and hug"
    assert "hey Stuart, find the screwdriver and hug." in candidates and len(candidates) == 7


def test_neighbouring_words_that_differ_one_for_one_are_each_a_place_of_their_own(resolver):
    vocabulary = resolver.vocabulary()
    grammar = "hey stuart come to the workbench and then turn around"
    candidates = splices("face, user, go to the workbench and then turn around.", grammar.split(" "), vocabulary)
    assert "hey, Stuart, go to the workbench and then turn around." in candidates  # the wake phrase, not "come"
    assert "hey, Stuart, come to the workbench and then turn around." in candidates and len(candidates) == 7
    uneven = splices("hey Stuart, and enter around.", ["hey", "stuart", "and", "then", "turn", "around"], vocabulary)
    assert uneven == ["hey Stuart, and then turn around."]  # one word for two: one place


def test_a_place_where_the_engines_name_different_things_is_in_every_candidate(resolver):
    vocabulary = resolver.vocabulary()
    candidates = splices("case do this, find the bottle.", ["hey", "stuart", "find", "the", "book"], vocabulary)
    assert candidates and all("book" in c and "bottle" not in c for c in candidates), candidates


def _acted_on(transcript, parser, resolver) -> list[tuple[str, str]]:
    """What the robot does with a transcript: the reading chosen, nothing when in doubt."""
    from stuart_bt.mission.commands import MIN_CONFIDENCE

    readings = transcript.readings()
    if not readings:
        return []
    chosen = choose_reading(readings, parser, resolver)
    result = parser.parse(readings[chosen][0])
    if result.doubt or transcript.confidence < MIN_CONFIDENCE or rival_reading(readings, chosen, parser, resolver):
        return []
    return [(i.action, i.target) for i in result.intents]


# Commands whisper tiny.en mishears in these voices (with white noise at the SNR given: the wake
# phrase as "thanks to it", "case to her"; "look for the work"), and talk in which the grammar
# engine alone hears a command ("Hey Stuart, what time is it" -> "hi stuart walk right").
MISHEARD = [
    ("Hey Stuart, pick up the apple", "en-us+f2", 175, None, [("pick_up", "apple")]),
    ("Hey Stuart, look for the book in the bathroom", "en-gb-x-rp", 160, 10.0, [("find", "book")]),
    ("Hey Stuart, turn around", "en-us+m3", 140, 10.0, [("turn_around", "")]),
]
TALK = [
    ("Hey Stuart, do you like the kitchen", "en-us", 150),
    ("I left my book in the bathroom yesterday", "en-gb+m3", 160),
    ("the workbench is very tidy today", "en-us+f2", 170),
    ("Hey Stuart, what time is it", "en-gb-x-rp", 150),
    ("could you believe how cold it is outside", "en-us+m3", 175),
    ("Hey Stuart, the apple on the table is mine", "en-gb+f3", 160),
]


@NEEDS_ESPEAK
def test_a_command_whisper_mishears_is_acted_on_as_said_with_the_grammar_engine(engine, resolver, tmp_path):
    from stuart_bt.hearing.pipeline import transcribe

    parser, vocabulary = Parser(), resolver.vocabulary()
    for n, (said, voice, speed, snr_db, meant) in enumerate(MISHEARD):
        clip = read_audio(speak(said, tmp_path / f"{n}.wav", voice, speed))
        if snr_db is not None:
            clip = add_noise(clip, snr_db, seed=VOICES.index(voice))
        alone = transcribe(engine.whisper, clip, vocabulary).transcript
        both = transcribe(engine, clip, vocabulary).transcript
        print(f"{said!r} ({voice}, {speed} wpm, {snr_db or 'no'} dB SNR): whisper {alone.text!r} -> "
              f"{_acted_on(alone, parser, resolver)}; with the grammar engine {both.text!r} -> "
              f"{_acted_on(both, parser, resolver)}")
        assert _acted_on(alone, parser, resolver) != meant  # whisper alone: the mishearing this is about
        assert _acted_on(both, parser, resolver) == meant
        assert both.engine == "whisper+grammar" and alone.text in [text for text, _ in both.readings()]


@NEEDS_ESPEAK
@pytest.mark.parametrize("snr_db", [None, 10.0])
def test_talk_stays_talk_though_the_grammar_engine_alone_hears_a_command_in_it(engine, resolver, tmp_path, snr_db):
    from stuart_bt.hearing.denoise import suppress_noise
    from stuart_bt.hearing.pipeline import is_speech, transcribe

    parser, vocabulary = Parser(), resolver.vocabulary()
    forced = 0
    for n, (said, voice, speed) in enumerate(TALK):
        clip = read_audio(speak(said, tmp_path / f"{n}.wav", voice, speed))
        if snr_db is not None:
            clip = add_noise(clip, snr_db, seed=n)
        command = engine.grammar.hear(suppress_noise(clip), vocabulary)
        heard = transcribe(engine, clip, vocabulary).transcript
        acted = _acted_on(heard, parser, resolver) if is_speech(heard) else []
        print(f"{said!r}: grammar engine alone {' '.join(command)!r}; heard {heard.text!r} -> {acted}")
        forced += bool(command)
        assert acted == []
    assert forced >= len(TALK) // 2  # the grammar engine did make commands of talk: whisper kept them out


@NEEDS_ESPEAK
def test_the_grammar_engine_hears_the_same_sound_the_same_way_whatever_it_heard_before(engine, resolver, tmp_path):
    from stuart_bt.hearing.denoise import suppress_noise

    def noisy(text: str, voice: str, speed: int, seed: int):
        clip = read_audio(speak(text, tmp_path / f"{seed}.wav", voice, speed))
        return suppress_noise(add_noise(clip, 10.0, seed=seed))

    vocabulary = resolver.vocabulary()
    stop = noisy("Stuart, stop", "en-us+m3", 175, 64)
    others = [noisy("Hey Stuart, turn right 90 degrees", "en-gb-x-rp", 170, 27),
              noisy("Hey Stuart, find the cup", "en-gb-x-rp", 170, 15)]
    heard = []
    for _ in range(3):
        heard.append(engine.grammar.hear(stop, vocabulary))
        for clip in others:
            engine.grammar.hear(clip, vocabulary)
    assert heard[1:] == heard[:1] * 2, heard  # this sound was "stuart halt", then "stuart stop", before
