"""What the robot says when a mission fails (stuart_bt.mission.failures): one clause in words people
use, built from the failure's facts (the code, the skill and its object or place, what blocked
it), for every code a mission can fail with; the technical reason stays in the report."""

from __future__ import annotations

import re

import pytest

from stuart_bt.daemon.protocol import ERROR_CODES
from stuart_bt.mission.failures import FAMILY_OF, LEAF_CODES, SAYINGS, Failure, Words, in_words
from stuart_bt.mission.speech import could_not, said_could_not

PLACES = {"station_4": "electronics bench", "kitchen": "kitchen"}
CODES = sorted(set(ERROR_CODES) | set(LEAF_CODES.values()) | {"unknown_object", "bad_result"})
TECHNICAL = re.compile(r"\d|_|\(|\)")  # numbers, identifiers, coordinates


def unreachable(skill: str, goal: str | None, blocked_by: list[str], **args: object) -> Failure:
    detail = {"blocked_by": blocked_by, "x": 4.35, "y": 1.85, **({"goal": goal} if goal else {})}
    return Failure("unreachable: no free spot to stand within 0.39 m of (4.35, 1.85)", "unreachable", skill, args,
                   detail)


def test_every_code_a_daemon_or_a_leaf_can_fail_with_has_words_of_its_own():
    missing = [code for code in CODES if code not in SAYINGS]
    assert not missing, f"no words for {missing}: add them to SAYINGS in stuart_bt/mission/failures.py"


@pytest.mark.parametrize("code", CODES)
@pytest.mark.parametrize("skill", sorted(FAMILY_OF))
def test_no_failure_is_said_with_codes_coordinates_or_identifiers(code, skill):
    failure = Failure(f"{code}: the daemon at (4.35, 1.85) went wrong", code, skill,
                      {"object": "teddy_bear", "marker": "station_4", "play": "high wave"},
                      {"blocked_by": ["kitchen table"], "saw": ["cup"]})
    said = in_words(failure, Words("fetch the cup", PLACES))
    assert said and not TECHNICAL.search(said), said
    assert "went wrong" not in said, f"the technical reason was repeated: {said}"


@pytest.mark.parametrize("label", ["apple", "cup", "teddy_bear"])
@pytest.mark.parametrize("blocked_by", [[], ["kitchen table"], ["workbench", "wall"]])
def test_what_could_not_be_reached_and_what_blocked_it_come_from_the_facts(label, blocked_by):
    name = label.replace("_", " ")
    close = in_words(unreachable("approach", "reach", blocked_by, object=label), Words("wave"))
    look = in_words(unreachable("view", "view", blocked_by, object=label), Words("wave"))
    assert close.startswith(f"I can't get close enough to the {name}"), close
    assert look.startswith(f"I can't find a spot where I can see the {name}"), look
    in_the_way = {0: "", 1: f" - the {blocked_by[0]} is in the way" if blocked_by else "",
                  2: " - the workbench and the wall are in the way"}[len(blocked_by)]
    assert close.endswith(f"the {name}{in_the_way}") and look.endswith(f"the {name}{in_the_way}"), (close, look)


def test_an_object_the_person_named_is_it_and_a_place_is_said_as_people_say_it():
    failure = unreachable("approach", "reach", ["kitchen table"], object="apple")
    assert said_could_not(["pick up the apple"], 0, failure, Words()) == (
        "Sorry, I could not pick up the apple: I can't get close enough to it - the kitchen table is in the way.")
    walk = unreachable("navigate", "pose", ["drone cage"], marker="station_4")
    assert in_words(walk, Words("go there", PLACES)) == (
        "I can't find a way to the electronics bench - the drone cage is in the way")
    step = unreachable("navigate", "relative", ["bookshelf"], dx=1.0)
    assert in_words(step, Words()) == "I can't move that way - the bookshelf is in the way"
    too_far = Failure("unreachable: bottle is 3.2 m away; reach is 1.2 m", "unreachable", "pick", {"object": "bottle"},
                      {"distance": 3.2, "reach": 1.2})
    assert in_words(too_far, Words()) == "the bottle is out of my arm's reach"


def test_a_look_that_saw_other_things_says_what_it_saw_instead():
    failure = Failure("not_found: no apple in view after 12 frames (saw: bottle, orange)", "not_found", "find",
                      {"object": "apple"}, {"saw": ["bottle", "orange"]})
    assert in_words(failure, Words("find the apple")) == (
        "I looked, but I can't see it - I only see a bottle and an orange")
    assert in_words(Failure("not_found: no 'apple' known", "not_found", "find", {"object": "apple"}),
                    Words("wave")) == "I looked, but I can't see the apple"


@pytest.mark.parametrize(("reason", "kind"), [
    ("timed out after 180 s", "timed_out"),
    ("unknown_object: no remembered position for 'botle'; find it first (did you mean 'bottle'?)", "unknown_object"),
    ("unknown marker 'garage'", "unknown_marker"),
    ("already_holding: already holding 'bottle'; release it first", "already_holding"),
    ("bad_result: loco daemon's result for r3 is unusable: x", "bad_result"),
    ("the tree said no", "other"),
])
def test_a_leafs_own_failure_is_recognised_from_how_its_reason_starts(reason, kind):
    assert Failure(reason).kind == kind


def test_the_mission_reason_keeps_the_technical_sentence_next_to_the_spoken_one():
    failure = unreachable("approach", "reach", ["kitchen table"], object="apple")
    assert could_not(["pick up the apple"], 0, failure.reason) == (
        "Sorry, I could not pick up the apple: no free spot to stand within 0.39 m of (4.35, 1.85).")
    assert failure.to_dict() == {"code": "unreachable", "skill": "approach", "object": "apple", "goal": "reach",
                                 "blocked_by": ["kitchen table"], "reason": failure.reason}
