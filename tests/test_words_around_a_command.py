"""Words said around a command that change nothing are neither targets nor doubt: the one
spoken to at the end of a target ("go find the apple buddy"), framing adverbs before the verb
("so basically just turn left")."""

from __future__ import annotations

import pytest

from stuart_bt.language.parse import Parser


@pytest.mark.parametrize("text,want", [
    ("stuart go find the book buddy", [("find", "book")]),
    ("stuart go to the entrance mate", [("navigate_to_marker", "entrance")]),
    ("Stuart, so basically just wave and then clap, cheers.", [("gesture", "wave"), ("gesture", "clap")]),
    ("Stuart, honestly, turn around", [("turn_around", "")]),
])
def test_words_that_change_nothing_are_neither_targets_nor_doubt(text, want):
    result = Parser().parse(text)
    assert [(i.action, i.target) for i in result.intents] == want and result.doubt == [], text


def test_a_name_that_is_part_of_a_place_stays():
    assert [i.target for i in Parser().parse("stuart go to the charging dock").intents] == ["charging dock"]


@pytest.mark.parametrize("text,want", [
    ("hey stuart um go to the like the humanoid corner you know", [("navigate_to_marker", "humanoid corner")]),
    ("hey stuart go to like the kitchen", [("navigate_to_marker", "kitchen")]),
    ("stuart find the apple its my lunch", [("find", "apple")]),
    ("Stuart, find the apple, it's my lunch.", [("find", "apple")]),
    ("Stuart, go to the workbench, Dr Patel needs you there.", [("navigate_to_marker", "workbench")]),
    ("Stuart, pick up the cup, Sam wants it.", [("pick_up", "cup")]),
    ("stuart um hands up everybody's watching", [("gesture", "hands up")]),
    ("stuart after you pick up the book take it to the reading room",
     [("pick_up", "book"), ("navigate_to_marker", "reading room")]),
    ("stuart go to the charging dock your battery's low", [("navigate_to_marker", "charging dock")]),
    ("stuart grab the bottle mate cheers", [("pick_up", "bottle")]),
    ("Stuart, would you please take our visitors to the 3D printers?", [("navigate_to_marker", "3d printers")]),
    ("stuart go to the parking lot", [("navigate_to_marker", "parking lot")]),
    ("Stuart, wave, kids love that.", [("gesture", "wave")]),
    ("Stuart, give it a quarter turn to the left.", [("turn_by_angle", "")]),
    ("righto stuart head to the bathroom cheers", [("navigate_to_marker", "bathroom")]),
    ("Stuart, find the book, yaar.", [("find", "book")]),
    ("stuart head off to the charging dock now there's a good lad", [("navigate_to_marker", "charging dock")]),
    ("Stuart, come on, go to the bathroom, there's a good robot.", [("navigate_to_marker", "bathroom")]),
    ("stuart okay again move forward one metre", [("move_relative", "")]),
    ("stuart maybe try going to station five", [("navigate_to_marker", "station five")]),
    ("stuart find the cup thank you very much", [("find", "cup")]),
    ("stuart pick up the cup for my little girl", [("pick_up", "cup")]),
    ("stuart walk to the entrance we're heading home now", [("navigate_to_marker", "entrance")]),
    ("Stuart, let's go to the kitchen, shall we?", [("navigate_to_marker", "kitchen")]),
    ("stuart i would really appreciate it if you could pick up the book", [("pick_up", "book")]),
    ("stuart it would be awesome if you gave me a high five", [("gesture", "high five")]),
    ("stuart buddy find the screwdriver", [("find", "screwdriver")]),
    ("Stuart, old pal, go to the workbench.", [("navigate_to_marker", "workbench")]),
    ("hey stuart you know what, turn around", [("turn_around", "")]),
    ("Stuart, go to the kitchen, the floor there is dry now.", [("navigate_to_marker", "kitchen")]),
    ("stuart walk another two metres", [("move_relative", "")]),
    ("stuart pick up the cup for us grown ups", [("pick_up", "cup")]),
    ("Stuart, you know, just turn around.", [("turn_around", "")]),
    ("stuart turn round and face the other way", [("turn_around", "")]),
    ("stuart ok so first go to the bathroom and then wave", [("navigate_to_marker", "bathroom"), ("gesture", "wave")]),
    ("stuart go to the workbench you'll find the screwdriver there", [("navigate_to_marker", "workbench")]),
    ("Stuart, pick up the apple, you've earned it.", [("pick_up", "apple")]),
    ("stuart yaw right forty five degrees", [("turn_by_angle", "")]),
    ("stuart once you reach the reading room put your hands up",
     [("navigate_to_marker", "reading room"), ("gesture", "hands up")]),
    ("stuart first find the cup second pick it up third go to the kitchen",
     [("find", "cup"), ("pick_up", "cup"), ("navigate_to_marker", "kitchen")]),
    ("stuart ok buddy turn around", [("turn_around", "")]),
    ("Stuart, bring me back over to the entrance.", [("navigate_to_marker", "entrance")]),
    ("stuart stay by the workbench for now", [("stop", "")]),
    ("stuart wait at the workbench", [("navigate_to_marker", "workbench"), ("stop", "")]),
])
def test_fillers_and_remarks_with_no_pause_are_never_targets(text, want):
    result = Parser().parse(text)
    assert [(i.action, i.target) for i in result.intents] == want and result.doubt == [], text


@pytest.mark.parametrize("text", ["stuart go to the bathroom scratch that", "Stuart, turn left, my bad"])
def test_a_correction_with_nothing_after_it_takes_the_command_back(text):
    assert Parser().parse(text).intents == []


def test_a_joke_taken_back_after_words_the_grammar_cannot_read_takes_everything_back():
    said = "stuart why don't you just walk to the kitchen and make us all a cup of tea haha i'm only joking"
    assert Parser().parse(said).intents == []


def test_write_where_only_a_side_can_be_meant_is_right():
    [step] = Parser().parse("stuart slide to the write a little").intents
    assert (step.action, step.y) == ("move_relative", -0.5)
    assert Parser().parse("stuart write it down").intents == []


@pytest.mark.parametrize("text", ["stuart give us a hug actually forget it",
                                  "stuart walk to the moon and back ha just messing with you"])
def test_a_retraction_with_no_pause_takes_back_a_gesture_or_a_walk(text):
    assert Parser().parse(text).intents == []


@pytest.mark.parametrize("run_together,apart", [
    ("stuart backup please", "stuart back up please"),
    ("stuart stepforward", "stuart step forward"),
    ("stuart turnright ninety degrees", "stuart turn right ninety degrees"),
    ("stuart give them a facewave", "stuart give them a face wave"),
    ("stuart handsup", "stuart hands up"),
])
def test_a_verb_and_its_particle_run_together_are_read_apart(run_together, apart):
    got, want = Parser().parse(run_together), Parser().parse(apart)
    assert got.intents and [(i.action, i.target, i.x, i.yaw) for i in got.intents] == [
        (i.action, i.target, i.x, i.yaw) for i in want.intents] and got.doubt == []


def test_turning_around_twice_is_still_two_turns():
    assert [i.action for i in Parser().parse("stuart turn around and turn around again").intents] == [
        "turn_around", "turn_around"]


@pytest.mark.parametrize("text", [
    "stuart you pick up cups faster than my kids tidy their room",
    "Stuart, you walk to the kitchen quicker than I do.",
    "stuart fetch me the book and a sandwich ha ha only kidding",
    "Stuart, go to the entrance and the car park, just joking",
    "stuart turn around and wave at the bathroom haha not really",
])
def test_comparisons_and_jokes_taken_back_after_talk_move_nothing(text):
    assert Parser().parse(text).intents == [], text
