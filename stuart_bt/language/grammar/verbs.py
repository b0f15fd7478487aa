"""The readers of each verb family (motion, turn, pick, find, stop, gesture, and the light verbs
do/make/give/take that lead into the others). Each reads from a position and returns the
intents it found and the position after them; what it does not understand ends the clause.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

from ..intents import FIND, GESTURE, MOVE, NAVIGATE, PICK, STOP, TURN, TURN_AROUND
from ..numbers import LENGTH, UNITS, read_quantity
from .amounts import NUMBER_STARTS, STEP_WORDS, read_move, read_turn_terms
from .lexicon import (
    ALL_VERBS,
    AROUND,
    BODY,
    BOUNDARY,
    CHOICES,
    DETERMINERS,
    DIRECTIONS,
    FIND_NOUN_LEADS,
    FIND_NOUNS,
    GESTURE_NOUNS,
    GESTURE_PHRASES,
    GESTURE_VERB_NAMES,
    GESTURES_BY_FIRST,
    GET_IDIOM_NEXT,
    HOME,
    NP_BLOCK,
    OBJECT_PRONOUNS,
    ROTATIONS,
    STOP_VERB_NEEDS,
    STRONG_VERBS,
    SURFACES,
    TO_WORDS,
    TRAILING,
)
from .nouns import read_go, read_noun_phrase, read_object, read_place, read_shared_list, read_way_to
from .state import ParseState, Result, Spec, may_end, skip_rest


def read_motion(s: ParseState, i: int) -> Result:
    """go / move / walk / head / come / return / visit / step / back ...: a navigation ("to the
    kitchen", "home"), a relative move ("forward 2 m"), or a verb that leads into another ("go
    get the cup")."""
    verb = s.toks[i]
    start = _past_motion_verb(s, verb, i + 1)
    if isinstance(start, _Found):
        return start.result
    j, back = start
    t = s.at(j)
    if verb == "make":
        return read_do(s, i)
    if verb == "get" and t not in TO_WORDS and t not in HOME and t != "back":
        return read_pick(s, i)
    t = _heard_as_to(s, verb, j, t)
    if t == "for" and (q := read_quantity(s.toks, j + 1)) is not None and q.dimension == LENGTH:
        return read_move(s, j, verb)  # "go straight for two metres": how far, not where
    if t in TO_WORDS and t != "for" or (t == "for" and verb in ("head", "make", "go")):
        return _motion_to(s, verb, j + 1)
    if t in HOME:
        return [(NAVIGATE, t, 0.0, 0.0, 0.0)], j + 1
    if t == "there" and (s.last_place or s.topic) and verb not in ("move", "step", "back"):
        return [(NAVIGATE, s.last_place or s.topic, 0.0, 0.0, 0.0)], j + 1  # "... and then go there again"
    if back or (verb == "come" and t in ("back", "here", "closer", "over", "")):
        return None  # "come back", "come here": towards the speaker, whom the grammar cannot place
    if verb in ("visit", "approach", "reach", "enter", "navigate", "goto"):
        words, e = read_noun_phrase(s, j)
        return read_go(s, read_place(s, words), e)
    return _motion_onwards(s, verb, j, t)


def _past_motion_verb(s: ParseState, verb: str, j: int) -> tuple[int, bool] | _Found:
    """Past the words that only colour a motion ("go right over to", "walk me to", "come with us
    to", "back up", "go straight back to"): the position of the word that says where, and whether
    it is a way back."""
    toks, n = s.toks, s.n
    while j < n and toks[j] in ("over", "on", "yourself", "along", "right", "directly", "quickly", "now", "please",
                                "just", "all", "the", "way") and not (
            toks[j] == "right" and (j + 1 >= n or toks[j + 1] in BOUNDARY or toks[j + 1] not in TO_WORDS | HOME)):
        if toks[j] == "the" and not (j + 1 < n and toks[j + 1] == "way"):
            break
        if toks[j] == "on" and verb in ("go", "carry", "continue") and not (j + 1 < n and toks[j + 1] in TO_WORDS):
            break
        j += 1
    if s.at(j) in ("me", "us", "them", "him", "her") and s.at(j + 1) in TO_WORDS:
        j += 1  # "walk me to the kitchen"
    elif s.at(j) == "with" and s.at(j + 1) in ("me", "us", "them", "him", "her") and s.at(j + 2) in TO_WORDS:
        j += 2  # "come with me to the kitchen": company, not a place
    if verb == "back" and s.at(j) in ("up", "off", "away", "out"):
        j += 1
    elif verb == "back" and not s.first and may_end(s, j):
        return _Found(None)  # "go to the bathroom and back": a return the grammar cannot place
    if s.at(j) == "straight" and s.at(j + 1) in TO_WORDS | HOME | {"back"}:
        j += 1
    back = s.at(j) == "back" and (s.at(j + 1) in TO_WORDS | HOME or (
        verb in ("come", "go", "get", "head") and s.at(j + 1) in ("over", "down", "up") and s.at(j + 2) in TO_WORDS))
    if back:
        j += 1
    if s.at(j) in ("over", "up", "down", "across", "round", "around", "through", "out") and s.at(j + 1) in TO_WORDS:
        j += 1
    return j, back


def _heard_as_to(s: ParseState, verb: str, j: int, t: str) -> str:
    """The word at ``j``, or "to" where a recogniser or a speaker said something else for it:
    "go two the kitchen", "go in the kitchen", "walk until the entrance"."""
    if t in ("2", "two", "too") and s.at(j + 1) in ("the", "your", "my", "our", "station"):
        return "to"  # a number needs a unit or a direction
    if s.at(j + 1) in ("the", "your", "my", "our") and (t == "in" and verb in ("go", "come", "head", "move") or (
            t == "until" and verb in ("go", "come", "walk", "run", "head", "move", "drive"))):
        return "to"
    return t


def _motion_to(s: ParseState, verb: str, k: int) -> Result:
    """What follows "to": a side ("move to the left"), a verb ("go to find the cup") or a place."""
    toks, n = s.toks, s.n
    k2 = k
    while k2 < n and toks[k2] in ("the", "your", "my"):
        k2 += 1
    if s.at(k2) in ("left", "right", "front", "back", "rear") and (
            k2 + 1 >= n or toks[k2 + 1] not in ("of", "side", "hand", "wall", "door", "room")):
        return read_move(s, k, verb)  # "move to the left"
    if k < n and toks[k] in ALL_VERBS and toks[k] not in ("back", "face", "stand", "hand", "end", "break"):
        return s.read_clause(s, k)  # "go to find the cup"
    words, e = read_noun_phrase(s, k)
    return read_go(s, read_place(s, words), e)


def _motion_onwards(s: ParseState, verb: str, j: int, t: str) -> Result:
    """No place was named: a verb it leads into ("go get the bottle", "go and wave"), a facing,
    or a relative move ("step back", "move forward two metres")."""
    if t in ALL_VERBS and t not in DIRECTIONS and verb in ("go", "come", "run", "hurry", "rush") and t not in (
            "stand", "back"):
        return s.read_clause(s, j)  # "go get the bottle", "come wave"
    if t == "and" and s.at(j + 1) in ALL_VERBS and verb in ("go", "come"):
        return s.read_clause(s, j + 1)  # "go and get the bottle"
    if verb == "face":
        return read_turn_terms(s, j, verb)
    if verb == "go" and t in ("ahead", "on", "forth") and may_end(s, j + 1):
        return None  # "go ahead", "go on": permission, not a direction
    return read_move(s, j, verb, default_back=verb in ("back", "retreat", "reverse"))


def read_guide(s: ParseState, i: int) -> Result:
    """lead / guide / escort / accompany / usher (me) (the way) to X: navigate_to_marker."""
    j = i + 1
    while s.at(j) in OBJECT_PRONOUNS or s.at(j) in ("the", "way", "back", "over", "our", "visitors", "guests"):
        j += 1
    if s.at(j) not in TO_WORDS:  # "escort our new guest to ...": whoever is guided, then where
        _, j = read_noun_phrase(s, j)
        while s.at(j) in ("the", "way", "back", "over"):
            j += 1
    if s.at(j) not in TO_WORDS:
        return None
    words, e = read_noun_phrase(s, j + 1)
    return read_go(s, read_place(s, words), e)


def read_turn(s: ParseState, i: int) -> Result:
    """turn / rotate / spin / face ...: "turn left", "turn 90 degrees to the right", "turn around",
    "face the other way". ``None`` for "turn on the light" and "turn towards the door"."""
    verb = s.toks[i]
    return read_turn_terms(s, i + 1, verb)


def read_pick(s: ParseState, i: int) -> Result:
    """pick up / grab / get / fetch / bring / take / hand me ...: pick_up, with a source ("from
    the kitchen": go there first) or a destination ("to the workbench": go there after)."""
    verb = s.toks[i]
    opener = _PICK_OPENERS.get(verb)
    start = opener(s, i) if opener is not None else i + 1
    if isinstance(start, _Found):
        return start.result
    start = _past_recipient(s, verb, i, start)
    if isinstance(start, _Found):
        return start.result
    words, e = read_noun_phrase(s, start)
    target = read_object(s, words)
    if target is None or (verb == "take" and words[-1] in NP_BLOCK):
        return None  # "take a short break", "take a deep breath": idioms whatever the adjective
    targets = [target]
    more, e_more = read_shared_list(s, e)
    if more:  # "fetch the cup and the bottle from the kitchen": the source is both objects'
        targets += more
        e = e_more
    if verb == "pick" and s.at(e) in ("up", "out"):
        e += 1
    if s.at(e) == "up" and verb in ("pick", "lift", "take", "scoop", "grab"):
        e += 1
    out: list[Spec] = []
    source, e, k = _pick_source(s, verb, e)
    if source is not None:
        out.append(source)
    if not (words[0] in ("it", "them", "that", "this") and s.last_action == PICK and target == s.last_object):
        out += [(PICK, t, 0.0, 0.0, 0.0) for t in targets]  # "grab the apple and bring it to ...": picked already
    destination, e = _pick_destination(s, verb, k, e)
    if destination is not None:
        out.append(destination)
    return out, e


def _after_pick(s: ParseState, i: int) -> int | _Found:
    """ "pick up", "pick the cup up"; "pick a card" is choosing, not lifting."""
    j = i + 1
    if s.at(j) in ("up", "out"):
        return j + 1
    if "up" not in s.toks[j:j + 8]:
        words, _ = read_noun_phrase(s, j)
        if not words or words[-1] in CHOICES:
            return _Found(None)
    return j


def _after_lift(s: ParseState, i: int) -> int | _Found:
    """ "lift the box"; "lift your hands" is a gesture."""
    j = i + 1
    k = j + 1 if s.at(j) in ("your", "both", "the", "my") else j
    if s.at(k) in BODY or s.at(k) in ("right", "left", "both") and s.at(k + 1) in BODY:
        return _Found(_raise(s, i))
    return j


def _after_get(s: ParseState, i: int) -> int | _Found:
    """ "get the cup"; "get to the kitchen" is a walk, "get going", "get over it" are neither."""
    j = i + 1
    t = s.at(j)
    if t not in GET_IDIOM_NEXT:
        return j
    if t in ("to", "back", "home") or (t == "over" and s.at(j + 1) in TO_WORDS):
        return _Found(read_motion(s, i))  # (read_motion hands "get" without a destination back here)
    if t in ("a", "an", "it", "some"):
        return j
    return _Found(None)  # "get over it", "get ready", "get lost"


def _after_give(s: ParseState, i: int) -> int | _Found:
    """ "give me a high five" is a gesture; "hand over the screwdriver" an object."""
    j = k = i + 1
    if s.at(k) in OBJECT_PRONOUNS and s.at(k) not in ("them", "you", "yourself"):
        k += 1
    elif s.at(k) == "over" and s.toks[i] in ("hand", "pass"):
        j = k = k + 1  # "hand over the screwdriver"
    k2 = k + 1 if s.at(k) in DETERMINERS else k
    g = s.phrase_at(k2, GESTURES_BY_FIRST)
    if g is not None:
        return _Found(([(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], skip_gesture_tail(s, k2 + len(g))))
    return j


_PICK_OPENERS: dict[str, Callable[[ParseState, int], int | _Found]] = {
    "pick": _after_pick, "lift": _after_lift, "raise": _after_lift, "get": _after_get,
    **dict.fromkeys(("give", "hand", "pass"), _after_give),
}


def _past_recipient(s: ParseState, verb: str, i: int, j: int) -> int | _Found:
    """Past who the object is for ("bring me the cup", "bring to me the bottle"); "bring me to
    the kitchen" is being guided there."""
    if verb in ("bring", "carry") and s.at(j) in ("me", "us", "them", "him", "her") and s.at(j + 1) in TO_WORDS:
        return _Found(read_guide(s, i))  # "bring me to the kitchen"
    if verb in ("bring", "get", "fetch", "grab", "hand", "pass", "give", "find", "buy", "pour") and s.at(j) in (
            "me", "us", "him", "her") and j + 1 < s.n and s.toks[j + 1] not in BOUNDARY and s.toks[j + 1] not in (
            "to", "here", "over", "back"):
        return j + 1
    if s.at(j) in ("to", "for") and s.at(j + 1) in ("me", "us") and s.at(j + 2) in DETERMINERS:
        return j + 2  # "bring to me the bottle": who it is for, said first
    return j


def _pick_source(s: ParseState, verb: str, e: int) -> tuple[Spec | None, int, int]:
    """ "... from the kitchen": where to go first (``(navigation, end, next)``). "from the
    table" is where the object lies, not a place to go."""
    toks, n = s.toks, s.n
    k = e
    while k < n and toks[k] in ("for", "me", "us", "please", "over", "here", "back", "and", "bring", "it", "up"):
        if toks[k] == "and" and not (s.at(k + 1) in ("bring", "carry", "take") and s.at(k + 2) in ("it", "them")):
            break
        k += 1
    if not (s.at(k) == "from" or (s.at(k) in ("off", "out") and s.at(k + 1) in ("of", "the"))):
        return None, e, k
    src_words, e2 = read_noun_phrase(s, k + 1 + (1 if s.at(k + 1) == "of" else 0))
    src = read_place(s, src_words)
    if src is not None and src_words[-1] in SURFACES:
        return None, e2, k
    if src is not None and verb in ("bring", "get", "fetch", "grab", "take", "retrieve", "collect", "pick",
                                    "carry", "pass", "hand", "give"):
        return (NAVIGATE, src, 0.0, 0.0, 0.0), e2, e2
    return None, e, k


def _pick_destination(s: ParseState, verb: str, k: int, e: int) -> tuple[Spec | None, int]:
    """ "... to the workbench": where to take the object afterwards (not "to me", "here")."""
    if s.at(k) not in ("to", "into", "over", "towards", "toward") or verb not in (
            "bring", "take", "carry", "deliver", "fetch", "get", "move"):
        return None, e
    k2 = k + 1 + (1 if s.at(k) == "over" and s.at(k + 1) == "to" else 0)
    dest_words, e2 = read_noun_phrase(s, k2)
    dest = " ".join(dest_words)
    if dest_words and dest not in OBJECT_PRONOUNS and dest not in ("here", "me", "us", "the user"):
        place = read_place(s, dest_words)
        if place is not None:
            return (NAVIGATE, place, 0.0, 0.0, 0.0), e2
    return None, e2


class _Found(NamedTuple):
    """A find verb's words already made the whole reading (or showed it is no find: ``None``)."""

    result: Result


def read_find(s: ParseState, i: int, verb: str = "") -> Result:
    """find / locate / look for / search for / check for ...: find; "search the kitchen for the
    cup" goes to the kitchen first. ``None`` for "look left", "find out ...". ``verb`` overrides
    the word at ``i`` (a noun read as a verb: "have a peek for ...")."""
    verb = verb or s.toks[i]
    if verb in ("look", "hunt", "scan", "search", "seek", "track", "check"):
        after = _after_search_verb(s, verb, i + 1)
    elif verb == "find":
        after = _after_find(s, i + 1)
    else:  # locate, spot, detect
        after = (i + 1, None)
    if isinstance(after, _Found):
        return after.result
    j, area = after
    words, e = read_noun_phrase(s, j)
    if not words and s.at(e) == "and" and s.at(e + 1) in ALL_VERBS:
        both = s.read_clause(s, e + 1)  # "locate and pick up the bottle": both verbs have the bottle
        if both is not None and both[0] and both[0][-1][1]:
            return [(FIND, both[0][-1][1], 0.0, 0.0, 0.0), *both[0]], both[1]
        return None
    target = "me" if verb == "find" and words == ["me"] else read_object(s, words)
    if target is None:
        return None
    return [*([(NAVIGATE, area, 0.0, 0.0, 0.0)] if area is not None else []), (FIND, target, 0.0, 0.0, 0.0)], e


def _after_search_verb(s: ParseState, verb: str, j: int) -> tuple[int, str | None] | _Found:
    """Past "look (around) for", "search the kitchen for", "track down": where the object's
    words start and the area to search first, if one was named."""
    while s.at(j) in ("around", "about", "out", "everywhere", "all", "over", "round"):
        j += 1
    if s.at(j) == "for":
        return j + 1, None
    if verb in ("search", "scan", "check"):
        if s.at(j) in ("in", "inside", "through", "of"):
            j += 1  # "search in the kitchen for ...", "have a search of the kitchen for ..."
        words, e = read_noun_phrase(s, j)
        area = read_place(s, words)
        if area is None:
            return _Found(None)
        if s.at(e) != "for":  # "search the kitchen": a place to search; "check the kitchen": vague
            return _Found(([(FIND, area, 0.0, 0.0, 0.0)], e) if verb != "check" else None)
        return e + 1, area
    if verb in ("track", "hunt") and s.at(j) == "down":
        return j + 1, None
    if verb in ("look", "hunt", "seek", "check"):
        return _Found(None)  # "look left", "check it out"
    return j, None


def _after_find(s: ParseState, j: int) -> tuple[int, str | None] | _Found:
    """Past "find (me)", "find for me": where the object's words start. "find out" is no find;
    "find your way to" is a walk."""
    if s.at(j) == "out":
        return _Found(None)
    if s.at(j) == "your" and s.at(j + 1) == "way":
        return _Found(read_way_to(s, j + 2))
    if s.at(j) in ("me", "us") and j + 1 < s.n and s.toks[j + 1] not in BOUNDARY and s.toks[j + 1] not in TRAILING:
        return j + 1, None
    if s.at(j) in ("to", "for") and s.at(j + 1) in ("me", "us") and s.at(j + 2) in DETERMINERS:
        return j + 2, None  # "find for me the cup"
    return j, None


def read_find_noun(s: ParseState, i: int) -> Result:
    """A light verb with the noun of a find verb: "have a look for the keys", "take a quick look
    around for the cup", "do a search for the bottle": read as that find verb. ``None`` when no
    such noun follows ("take a look at this" has no "for": no object to find)."""
    k = i + 1
    if s.at(k) not in ("a", "an", "another"):
        return None
    k += 1
    if s.at(k) in ("quick", "little", "good", "proper", "careful", "fast", "short"):
        k += 1
    if s.at(k) not in FIND_NOUNS:
        return None
    m = k + 1
    while s.at(m) in ("around", "about", "round"):
        m += 1
    if s.at(m) == "for":
        return read_find(s, k, "look")
    # "have a search of the kitchen for the cup", "take a look around the kitchen for the cup"
    return read_find(s, m - 1 if s.at(m) in ("of", "in", "inside", "through") else k, "check")


def read_stop(s: ParseState, i: int) -> Result:
    """stop / halt / freeze / wait / stay / hold on / never mind ...: stop. Reads to the next
    connector ("stop what you are doing and turn around")."""
    toks, n = s.toks, s.n
    verb = toks[i]
    j = i + 1
    nxt = s.at(j)
    needs = STOP_VERB_NEEDS.get(verb)
    if needs is not None and nxt not in needs:
        return None  # "stand in line", "never again", "cut the cake": not a stop
    if verb in ("stop", "halt") and nxt in ("me", "us", "him", "her", "them", "everyone", "everybody", "people"):
        return None  # "stop me if you've heard this one": someone else is stopped
    if verb in ("wait", "stay", "stand") and nxt in ("at", "by", "in", "near", "inside", "beside") and s.at(
            j + 1) in ("the", "your", "my", "our", "station"):
        words, e = read_noun_phrase(s, j + 1)  # "wait at the entrance": go there, then stay
        place = read_place(s, words)
        if place is not None and words[-1] not in SURFACES:
            return [(NAVIGATE, place, 0.0, 0.0, 0.0), (STOP, "", 0.0, 0.0, 0.0)], skip_rest(s, e)
    if verb == "stand" and nxt not in ("still", "there", "by", "put", "here", "fast", "your", "right"):
        return None  # "stand in line"
    while j < n and toks[j] not in BOUNDARY:
        if j > i + 1 and toks[j] in STRONG_VERBS and toks[j] not in ("move", "go", "stop", "turn", "walk"):
            break
        j += 1
    return [(STOP, "", 0.0, 0.0, 0.0)], j

VISIT_VERBS = frozenset({"stop", "swing", "drop", "come", "pop", "go", "pass", "nip", "call"})


def read_visit_by(s: ParseState, i: int) -> Result:
    """ "stop by the kitchen", "swing by the workbench", "drop by station 3": a visit
    (navigate_to_marker). Only with a place after "by": "stand by" and "stop by 5" are not."""
    if s.at(i + 1) != "by" or s.at(i + 2) not in ("the", "your", "my", "our", "station"):
        return None
    words, e = read_noun_phrase(s, i + 2)
    place = read_place(s, words)
    return ([(NAVIGATE, place, 0.0, 0.0, 0.0)], e) if place and words[-1] not in SURFACES else None


def skip_gesture_tail(s: ParseState, j: int) -> int:
    """Words after a gesture that change nothing: "gesture", "with your hands", "at me", "to
    the camera", "for the visitors", "hello", "goodbye"."""
    toks, n = s.toks, s.n
    while j < n and toks[j] not in BOUNDARY:
        if toks[j] in STRONG_VERBS and toks[j] not in ("wave",) and j + 1 < n and toks[j + 1] not in BOUNDARY:
            break
        j += 1
    return j


def read_gesture(s: ParseState, i: int) -> Result:
    """wave / clap / hug / shake hands / blow a kiss / raise your hands / put your arms down..."""
    verb, j = s.toks[i], i + 1
    if verb in GESTURE_VERB_NAMES:
        if verb == "wave" and s.at(j) in ("the", "a") and s.at(j + 1) in ("flag", "wand", "banner", "sign"):
            return None  # "wave the flag": a thing is waved, not a hello
        return [(GESTURE, GESTURE_VERB_NAMES[verb], 0.0, 0.0, 0.0)], skip_gesture_tail(s, j)
    reader = _GESTURE_READERS.get(verb)
    return reader(s, i) if reader is not None else None


def _say_with_gesture(s: ParseState, i: int) -> Result:
    """ "say hello with a wave": the gesture; saying alone is speech, not a gesture."""
    for k in range(i + 1, min(i + 6, s.n)):
        if s.toks[k] == "with":
            m = k + 1 + (1 if s.at(k + 1) in DETERMINERS else 0)
            g = s.phrase_at(m, GESTURES_BY_FIRST)
            if g is not None:
                return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], skip_gesture_tail(s, m + len(g))
        if s.toks[k] in BOUNDARY:
            break
    return None


def _shake_hands(s: ParseState, i: int) -> Result:
    """ "shake hands", "shake my hand": a handshake ("shake the bottle" is none)."""
    for k in range(i + 1, min(i + 5, s.n)):
        if s.toks[k] in ("hand", "hands"):
            return [(GESTURE, "shake hand", 0.0, 0.0, 0.0)], skip_gesture_tail(s, k + 1)
        if s.toks[k] in BOUNDARY:
            break
    return None


def _kiss(s: ParseState, i: int) -> Result:
    """ "blow us a kiss", "kiss", "blow a kiss with your left hand"."""
    verb, k = s.toks[i], i + 1
    while k < s.n and s.toks[k] in ("me", "us", "a", "an", "the", "everyone", "them", "him", "her", "some", "big"):
        k += 1
    if verb != "kiss" and s.at(k) not in ("kiss", "kisses"):
        return None
    tail = skip_gesture_tail(s, k + (1 if verb == "blow" else 0))
    words = s.toks[k:tail]
    name = "left kiss" if "left" in words else "right kiss" if "right" in words else "two hand kiss"
    return [(GESTURE, name, 0.0, 0.0, 0.0)], tail


def _lower_arms(s: ParseState, i: int) -> Result:
    """ "lower your arms", "relax your hands", "release the arm": the arms back down."""
    j = i + 1
    k = j + 1 if s.at(j) in ("your", "both", "the", "my") else j
    if s.at(k) in BODY or (s.at(k) == "arm" or (s.at(k) in ("both",) and s.at(k + 1) in BODY)):
        return [(GESTURE, "release arm", 0.0, 0.0, 0.0)], skip_gesture_tail(s, k + 1)
    return None


def _raise(s: ParseState, i: int) -> Result:
    """raise / lift / put + your hands: "hands up", "right hand up" or (down) "release arm"."""
    toks = s.toks
    verb = toks[i]
    j = i + 1
    side = ""
    plural = False
    k = j
    while k < s.n and toks[k] in ("your", "both", "the", "my", "right", "left", "two"):
        if toks[k] in ("right", "left"):
            side = toks[k]
        if toks[k] in ("both", "two"):
            plural = True
        k += 1
    if s.at(k) not in BODY:
        return None
    plural = plural or toks[k] in ("hands", "arms")
    k += 1
    down = False
    if verb == "put":
        if s.at(k) in ("down",):
            down = True
        elif s.at(k) not in ("up", "in", "into", "high", "above", "over"):
            return None
    if down:
        return [(GESTURE, "release arm", 0.0, 0.0, 0.0)], skip_gesture_tail(s, k)
    if side == "left" and not plural:
        return None  # the library has no left-hand-up gesture
    name = "hands up" if plural else "right hand up"
    return [(GESTURE, name, 0.0, 0.0, 0.0)], skip_gesture_tail(s, k)


# gesture verbs that need more than their name: what follows decides
_GESTURE_READERS: dict[str, Callable[[ParseState, int], Result]] = {
    "say": _say_with_gesture, "shake": _shake_hands, "kiss": _kiss, "blow": _kiss,
    **dict.fromkeys(("raise", "put", "lift"), _raise),
    **dict.fromkeys(("lower", "drop", "relax", "release", "rest"), _lower_arms),
}


def read_do(s: ParseState, i: int) -> Result:
    """do / make / perform / give / show / take / throw: a gesture ("do a high five", "show me a
    heart"), a turn ("make a u-turn", "do a 180", "take a left", "make a quarter turn"), a way
    ("make your way to the kitchen", "show me the way to the kitchen"), or for give/take/show the
    pick and navigation readings."""
    verb = s.toks[i]
    if verb in FIND_NOUN_LEADS and (got := read_find_noun(s, i)) is not None:
        return got
    led = _led_somewhere(s, verb, i)
    if led is not None:
        return led.result
    j = _past_audience(s, i + 1)
    k = _past_modifiers(s, j)
    g = s.phrase_at(k, GESTURES_BY_FIRST)
    if g is not None and not (s.toks[k] in ("five",) and verb not in ("give",)):
        return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], skip_gesture_tail(s, k + len(g))
    if verb in ("do", "make", "perform", "take", "try", "pull", "execute", "throw"):
        return _do_a_motion(s, verb, i, j, k)
    if verb == "give" and (s.at(i + 1) in ("me", "us") or s.at(i + 1) in DETERMINERS):
        return read_pick(s, i)
    return None


def _led_somewhere(s: ParseState, verb: str, i: int) -> _Found | None:
    """ "take me to the kitchen", "show me to the bathroom", "show us the way to ...", "show me
    where the kitchen is": a walk there."""
    j = i + 1
    if verb == "take" and s.at(j) in ("me", "us", "him", "her", "them") and s.at(j + 1) in TO_WORDS:
        words, e = read_noun_phrase(s, j + 2)
        return _Found(_walk_to(s, words, e))
    if verb != "show" or s.at(j) not in ("me", "us", "them", "him", "her", "everyone"):
        return None
    k = j + 1
    if s.at(k) in TO_WORDS:
        return _Found(read_guide(s, i))  # "show me to the bathroom"
    if s.at(k) == "the" and s.at(k + 1) == "way" and s.at(k + 2) in TO_WORDS:
        words, e = read_noun_phrase(s, k + 3)
        return _Found(_walk_to(s, words, e))
    if s.at(k) == "where" and k + 1 < s.n:
        words, e = read_noun_phrase(s, k + 1 + (1 if s.at(k + 1) in ("the",) else 0))
        return _Found(_walk_to(s, words, e + 1) if s.at(e) in ("is", "are") else None)
    return None


def _walk_to(s: ParseState, words: list[str], end: int) -> Result:
    target = read_place(s, words)
    return ([(NAVIGATE, target, 0.0, 0.0, 0.0)], end) if target else None


def _past_audience(s: ParseState, j: int) -> int:
    """Past whom it is done for: "show me", "do the guests a ...", "give everyone a wave"."""
    if s.at(j) in ("the", "our") and s.at(j + 1) in ("guests", "visitors", "kids", "children", "audience",
                                                     "crowd", "people", "group", "class", "team"):
        return j + 2
    if s.at(j) in ("me", "us", "him", "her", "them", "everyone", "everybody", "you"):
        return j + 1
    return j


def _past_modifiers(s: ParseState, k: int) -> int:
    """Past "a nice little", "your famous", "another quick": up to the noun."""
    toks, n = s.toks, s.n
    while k < n and toks[k] in ("a", "an", "the", "your", "some", "another", "that", "this", "my", "nice", "little",
                                "quick", "cool", "famous", "special", "full", "lovely", "big"):
        if toks[k] in ("full",) or (toks[k] in ("big", "little") and s.at(k + 1) in GESTURE_NOUNS):
            break
        k += 1
    return k


def _do_a_motion(s: ParseState, verb: str, i: int, j: int, k: int) -> Result:
    """ "do a u-turn", "take a left", "make your way to", "take two steps back", "make a quarter
    turn to the left", "do a spin"; a "take" that is none of these is a pick."""
    t = s.at(k)
    got = _turn_idiom(s, verb, k)
    if got is not None:
        return got
    if verb in ("make", "do") and (t == "way" or (t == "your" and s.at(k + 1) == "way")):
        return read_way_to(s, k + (1 if t == "way" else 2))
    if verb in ("take", "make", "do") and (t in STEP_WORDS or s.at(k + 1) in STEP_WORDS or s.at(
            k + 2) in STEP_WORDS):
        return _steps(s, j, k)
    got = _turn_amount(s, verb, j)
    if got is not None:
        return got
    if verb in ("do", "make") and s.at(k) == "spin":
        return [(TURN, "", 0.0, 0.0, 2 * math.pi)], k + 1
    return read_pick(s, i) if verb == "take" else None


def _turn_idiom(s: ParseState, verb: str, k: int) -> Result:
    """ "a u-turn", "an about face", "a 180", "a left (turn)"."""
    t = s.at(k)
    if (t in ("u", "you") and s.at(k + 1) in ("turn", "turnaround")) or (
            t == "about" and s.at(k + 1) in ("face", "turn")):
        return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + 2
    if t in ("turnaround", "one80"):
        return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + 1
    width = 1 if t == "180" else 2
    if verb != "take" and (t == "180" or (t == "one" and s.at(k + 1) == "eighty")) and s.at(k + width) not in UNITS:
        return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + width
    if t in ("left", "right") and (s.at(k + 1) in ("turn", "") or s.at(k + 1) in BOUNDARY or s.at(
            k + 1) in TRAILING):
        return [(TURN, "", 0.0, 0.0, ROTATIONS[t] * math.radians(s.defaults.turn_deg))], k + (
            2 if s.at(k + 1) == "turn" else 1)
    return None


def _steps(s: ParseState, j: int, k: int) -> Result:
    """ "take two steps back", "take a small step to the left", "take a small step" (forward)."""
    got = read_move(s, j, "step")
    at = next(m for m in range(k, k + 3) if s.toks[m] in STEP_WORDS)
    if got is None and s.toks[at] in ("step", "pace"):  # "take a small step to the left": one step that way
        got = read_move(s, at + 1, "step")
        if got is None and may_end(s, at + 1):  # "take a small step": forward, like "take a step"
            got = [(MOVE, "", s.defaults.step_m, 0.0, 0.0)], at + 1
    return got


def _turn_amount(s: ParseState, verb: str, j: int) -> Result:
    """ "make a quarter turn to the left", "do a full turn", "do a 360", "take a left"; "take
    five" is a break, not a turn."""
    toks, n = s.toks, s.n
    k0 = j
    while k0 < n and toks[k0] in ("a", "an", "the"):
        if s.at(k0 + 1) in NUMBER_STARTS or s.at(k0 + 1)[:1].isdigit() or s.at(k0 + 1) in ("full", "complete",
                                                                                              "whole", "turn"):
            break
        k0 += 1
    got = read_turn_terms(s, k0, verb)
    if got is not None and verb == "take" and not any(w in ROTATIONS or w in UNITS for w in toks[k0:got[1]]):
        return None  # "take a left", "take a quarter turn" say how they turn
    if got is not None and (got[0][0][0] != TURN_AROUND or s.at(k0) in AROUND):
        return got
    return None
