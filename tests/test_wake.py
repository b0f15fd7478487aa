"""The wake filter: "Hey Stuart" as recognisers spell it, near-misses that must stay asleep,
where the name may stand, the command left over, and a configurable name."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser
from stuart_bt.language.wake import WakeFilter, key_distance, phonetic_key


@pytest.fixture(scope="module")
def wake() -> WakeFilter:
    return WakeFilter()


@pytest.mark.parametrize("heard", ["stuart", "stewart", "steward", "stuert", "stuard", "stewert", "stuwart",
                                   "stu art", "stew art", "st uart", "Stuart", "STEWART"])
def test_spellings_of_the_name_have_the_same_key(heard: str) -> None:
    assert phonetic_key(heard.replace(" ", "")) == phonetic_key("stuart") == "STUART"


@pytest.mark.parametrize("utterance", [
    "Hey Stuart, go", "hey stewart go", "hey steward go", "hey stuert go", "hey swart go", "hey stu art go",
    "a stuart go", "hey stuard go", "hay stewart go", "hi stuart go", "hello Stuart go", "ok stuart go",
    "okay stuart go", "o.k. stuart go", "HEY STUART GO", "hey, Stuart! go", "heystuart go", "hey-stuart go",
    "Hey Stuart's, go", "hey stuarts go", "yo stuart go", "excuse me stuart go",
])
def test_wakes_on_recogniser_variants(wake: WakeFilter, utterance: str) -> None:
    m = wake.match(utterance)
    assert m.woke, utterance
    assert m.command.lower() == "go"


@pytest.mark.parametrize("utterance", [
    "hey start the engine", "hey stewardess, where is my seat?", "Stuart Little is a film", "hey star",
    "hey smart speaker", "hey stupid", "hey sweetheart", "hey stewie", "hey stu", "hey sturt", "hey stuff",
    "hey siri", "I told Stuart to go", "ask stuart to stop", "stuart go to the kitchen", "hello there", "",
    "   ", "?!", "heystart",
])
def test_near_misses_stay_asleep(wake: WakeFilter, utterance: str) -> None:
    assert not wake.match(utterance).woke, utterance


def test_swart_wakes_but_start_does_not_although_both_are_one_letter_away() -> None:
    # the reason for a phonetic key: losing the "u" sound costs more than losing a "t"
    assert key_distance(phonetic_key("swart"), "STUART") < key_distance(phonetic_key("start"), "STUART")
    assert WakeFilter().match("hey swart stop").woke and not WakeFilter().match("hey start stop").woke


@pytest.mark.parametrize("utterance,command", [
    ("um, hey Stuart, go to the kitchen", "go to the kitchen"),
    ("uh oh hey there Stuart turn left", "turn left"),
    ("so hey stuart wave", "wave"),
    ("ok so hey stuart wave", "wave"),
])
def test_filler_before_the_wake_phrase(wake: WakeFilter, utterance: str, command: str) -> None:
    m = wake.match(utterance)
    assert m.woke and m.command == command


def test_a_bare_name_wakes_only_with_a_pause_after_it(wake: WakeFilter) -> None:
    assert wake.match("Stuart, stop!").command == "stop!"
    assert wake.match("Stuart.").woke and wake.match("Stuart").woke
    assert not wake.match("Stuart stop").woke
    assert not WakeFilter(bare_name=False).match("Stuart, stop!").woke


@pytest.mark.parametrize("utterance", ["case Stuart, stop", "hate Stewart, go to the kitchen", "pay Stuart: wave",
                                       "um, day Stuart, turn left"])
def test_a_misheard_greeting_wakes_like_a_bare_name_with_a_pause_after_it(wake: WakeFilter, utterance: str) -> None:
    m = wake.match(utterance)
    assert m.woke and m.command and not m.command.startswith((",", ":")), m
    assert m.distance > 0, "a guessed greeting is a less sure match than a heard one"


@pytest.mark.parametrize("utterance", ["case Stuart go to the kitchen", "thanks to Stuart, that was great",
                                       "I think Stuart, is tired", "the tall Stuart, went home",
                                       "tell Stuart, go away", "poor Stuart, he is tired",
                                       "is Stuart, the robot, here?"])
def test_a_word_before_the_name_without_a_pause_or_unlike_hey_does_not_wake(wake: WakeFilter, utterance: str) -> None:
    assert not wake.match(utterance).woke


@pytest.mark.parametrize("utterance,command", [("thanks Stuart, that was great", "that was great"),
                                               ("Cheers Stuart, you can go back to the dock now",
                                                "you can go back to the dock now"),
                                               ("sorry Stuart, wrong place, go to the kitchen",
                                                "wrong place, go to the kitchen")])
def test_thanks_praise_or_sorry_before_the_name_addresses_the_robot(wake: WakeFilter, utterance: str,
                                                                    command: str) -> None:
    m = wake.match(utterance)
    assert m.woke and m.command == command


def test_command_keeps_its_spelling_and_a_final_question_mark(wake: WakeFilter) -> None:
    m = wake.match("Hey Stuart... What can you pick up?")
    assert m.command == "What can you pick up?"
    assert m.phrase == "Hey Stuart" and m.heard_name == "stuart" and m.distance == 0.0
    assert wake.match("Hey Stuart").command == ""


def test_wake_phrase_only_at_the_start(wake: WakeFilter) -> None:
    assert not wake.match("go to the kitchen hey stuart").woke
    assert not wake.match("the robot is called stuart").woke


def test_name_and_greetings_are_configurable() -> None:
    robbie = WakeFilter(name="Robbie", greetings=("hey", "yo"))
    assert robbie.match("hey robby, stop").command == "stop"
    assert robbie.match("yo robbie stop").woke
    assert not robbie.match("hey stuart stop").woke
    assert not robbie.match("hello robbie stop").woke  # not one of its greetings
    only_hi = WakeFilter(greetings=("hi",))
    assert only_hi.match("hi stuart go").woke and not only_hi.match("hey stuart go").woke


def test_two_word_names_and_short_names() -> None:
    mary = WakeFilter(name="Mary Jane")
    assert mary.match("hey mary jane, wave").command == "wave"
    max_ = WakeFilter(name="Max")
    assert max_.match("hey max stop").woke
    assert not max_.match("hey mix stop").woke  # short names need the exact sound key


def test_tolerance_is_a_knob() -> None:
    assert not WakeFilter(tolerance=0.0).match("hey swart go").woke
    assert WakeFilter(tolerance=1.0).match("hey start go").woke


def test_no_letters_in_the_name_is_refused() -> None:
    with pytest.raises(ValueError):
        WakeFilter(name="!!")


def test_long_and_odd_input_is_fine(wake: WakeFilter) -> None:
    assert wake.match("hey stuart " + "go " * 100_000).woke
    assert not wake.match("\x00\ufffd" * 1000).woke


def test_a_term_of_address_after_a_bare_name_belongs_to_it():
    from stuart_bt.language.wake import WakeFilter

    wake = WakeFilter("Stuart")
    match = wake.match("Stuart mate, do us a favour and find my cup.")
    assert match.woke and match.command == "do us a favour and find my cup."
    assert not wake.match("Stuart mate is a nice name").woke


@pytest.mark.parametrize("utterance", ["stuart go to the reading room",
                                       "stuart stop stop stop you're going the wrong way",
                                       "stuart can you please go to station four",
                                       "stuart when you get to the workbench find the screwdriver"])
def test_a_bare_name_with_no_pause_wakes_when_a_command_follows(utterance):
    got = Parser().parse(utterance)
    assert got.wake and got.intents, got


@pytest.mark.parametrize("utterance", ["stuart what can you do", "stuart do you like the kitchen"])
def test_a_bare_name_with_no_pause_wakes_for_a_question_put_to_the_robot(utterance):
    got = Parser().parse(utterance)
    assert got.wake and got.conversational and not got.intents, got


@pytest.mark.parametrize("utterance", ["stuart went to the kitchen", "stuart is in the kitchen",
                                       "stuart turns left at the door", "stuart said go to the kitchen",
                                       "stuart walking to the kitchen is slow", "stuart would like to go home"])
def test_a_bare_name_with_no_pause_before_a_sentence_about_the_robot_does_not_wake(utterance):
    got = Parser().parse(utterance)
    assert not got.wake and not got.intents, got


@pytest.mark.parametrize("utterance", ["stuart you're late so just stop", "stuart is in the way so stop",
                                       "stuart no no freeze there's a kid behind you"])
def test_a_bare_name_with_no_pause_wakes_for_a_stop_said_anywhere_after_it(utterance):
    got = Parser().parse(utterance)
    assert got.wake and [i.action for i in got.intents] == ["stop"], got


@pytest.mark.parametrize("utterance", ["stuart stuart give me a high five", "Stuart, Stuart, wave",
                                       "hey stuart stuart wave"])
def test_a_name_said_twice_is_the_name_once(utterance):
    got = Parser().parse(utterance)
    assert got.wake and [i.action for i in got.intents] == ["gesture"], got


@pytest.mark.parametrize(("utterance", "command"), [("Would you mind picking up the cup, Stuart?",
                                                     "Would you mind picking up the cup?"),
                                                    ("Go to the kitchen, Stuart.", "Go to the kitchen")])
def test_the_name_last_after_a_pause_addresses_what_came_before_it(utterance, command):
    got = Parser().parse(utterance)
    assert got.wake and got.command == command and got.intents, got


@pytest.mark.parametrize("utterance", ["I was talking to Stuart", "we took a photo with stuart"])
def test_the_name_last_without_a_pause_after_words_about_it_does_not_wake(utterance):
    assert not Parser().parse(utterance).wake


@pytest.mark.parametrize("utterance,woke", [
    ("could you clap for us stuart", True), ("turn left please stewart", True),
    ("could you go to the kitchen stuart?", True), ("where are you stuart", True), ("go to the kitchen stuart", True),
    ("go and say hello to stuart", False), ("I told the visitors about stuart", False),
    ("the kids really like stuart", False), ("wave at stuart", False),
])
def test_the_name_last_with_no_pause_wakes_only_after_words_said_to_the_robot(utterance: str, woke: bool) -> None:
    from stuart_bt.language.parse import Parser

    assert Parser().parse(utterance).wake is woke


@pytest.mark.parametrize("utterance,action", [
    ("Oh wow, Stuart, go to the 3D printers!", "navigate_to_marker"),
    ("oh no Stuart, you're heading straight for the bags, stop, stop!", "stop"),
    ("um so like stuart pick up the bottle you know", "pick_up"),
    ("oops stuart turn around", "turn_around"),
    ("gosh, Stuart, clap", "gesture"),
])
def test_exclamations_and_discourse_words_before_the_name_change_nothing(utterance, action):
    got = Parser().parse(utterance)
    assert got.wake and [i.action for i in got.intents] == [action], got


@pytest.mark.parametrize("utterance", ["Wait, Stuart!", "Whoa, whoa, whoa, Stuart!"])
def test_a_stop_before_the_name_is_no_filler(utterance):
    assert [i.action for i in Parser().parse(utterance).intents] == ["stop"]
