"""The motion family: "go to the kitchen", "head home", "walk forward two metres", "come
back", "turn left", "take me to the lab", "stop by station 3". A motion verb leads to a place, a
relative move, a turn, or into another verb ("go get the cup", "get the bottle": a pick, read
by that family through ``ParseState.read_as``).
"""

from __future__ import annotations

from ..intents import NAVIGATE
from ..numbers import LENGTH, read_quantity, word_value
from .amounts import read_move, read_turn_terms
from .lexicon import (
    ALL_VERBS,
    BOUNDARY,
    DETERMINERS,
    DIRECTIONS,
    HOME,
    OBJECT_PRONOUNS,
    SURFACES,
    TO_WORDS,
    TRAILING,
)
from .nouns import read_go, read_noun_phrase, read_place
from .state import Found, ParseState, Result, may_end


def read_motion(s: ParseState, i: int) -> Result:
    """go / move / walk / head / come / return / visit / step / back ...: a navigation ("to the
    kitchen", "home"), a relative move ("forward 2 m"), or a verb that leads into another ("go
    get the cup")."""
    verb = s.toks[i]
    start = _past_motion_verb(s, verb, i + 1)
    if isinstance(start, Found):
        return start.result
    j, back = start
    t = s.at(j)
    if verb == "make":
        return s.read_as("light_verbs", i)
    if verb == "get" and t not in TO_WORDS and t not in HOME and t != "back":
        return s.read_as("pick", i)
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


def _onward_to(s: ParseState, j: int) -> bool:
    """Whether a place follows ``go on`` ("go on to", "go on over to", "go on ahead into"): then
    "on" only colours the walk; otherwise "go on" is "carry on" or a sign-off."""
    while s.at(j) in ("over", "ahead", "down", "up", "across", "right", "straight"):
        j += 1
    return s.at(j) in TO_WORDS


def _past_motion_verb(s: ParseState, verb: str, j: int) -> tuple[int, bool] | Found:
    """Past the words that only colour a motion ("go right over to", "walk me to", "come with us
    to", "back up", "go straight back to"): the position of the word that says where, and whether
    it is a way back."""
    toks, n = s.toks, s.n
    while j < n and toks[j] in ("over", "on", "yourself", "along", "right", "ahead", "directly", "quickly", "now",
                                "please", "just", "all", "the", "way") and not (
            toks[j] in ("right", "ahead") and (j + 1 >= n or toks[j + 1] in BOUNDARY
                                               or toks[j + 1] not in TO_WORDS | HOME)):
        if toks[j] == "the" and not (j + 1 < n and toks[j + 1] == "way"):
            break
        if toks[j] == "on" and verb in ("go", "carry", "continue") and not _onward_to(s, j + 1):
            break
        j += 1
    if s.at(j) in ("me", "us", "them", "him", "her") and s.at(j + 1) in TO_WORDS:
        j += 1  # "walk me to the kitchen"
    elif s.at(j) == "with" and s.at(j + 1) in ("me", "us", "them", "him", "her") and s.at(j + 2) in TO_WORDS:
        j += 2  # "come with me to the kitchen": company, not a place
    if verb == "back" and s.at(j) in ("up", "off", "away", "out"):
        j += 1
    elif verb == "back" and not s.first and may_end(s, j):
        return Found(None)  # "go to the bathroom and back": a return the grammar cannot place
    if s.at(j) == "straight" and s.at(j + 1) in TO_WORDS | HOME | {"back"}:
        j += 1
    back = s.at(j) == "back" and (s.at(j + 1) in TO_WORDS | HOME or (
        verb in ("come", "go", "get", "head") and s.at(j + 1) in ("over", "down", "up") and s.at(j + 2) in TO_WORDS))
    if back:
        j += 1
    if s.at(j) in ("over", "up", "down", "across", "round", "around", "through", "out", "off") and s.at(
            j + 1) in TO_WORDS:
        j += 1  # ("head off to the charging dock")
    return j, back


def _heard_as_to(s: ParseState, verb: str, j: int, t: str) -> str:
    """The word at ``j``, or "to" where a recogniser or a speaker said something else for it:
    "go two the kitchen", "go in the kitchen", "walk until the entrance"."""
    if t in ("2", "two", "too") and s.at(j + 1) in ("the", "your", "my", "our", "station"):
        return "to"  # a number needs a unit or a direction
    if s.at(j + 1) in ("the", "your", "my", "our") and (t == "in" and verb in ("go", "come", "head", "move") or (
            t == "until" and verb in UNTIL_VERBS)):
        return "to"
    if t == "at" and verb in ("go", "come", "walk", "head", "run") and s.at(j + 1) in ("the", "station"):
        return "to"  # "please to go at station 2", as a speaker of another language says it
    return t


# verbs after which "until the ..." says where to ("go until the entrance"), not until when
UNTIL_VERBS = frozenset({"go", "come", "walk", "run", "head", "move", "drive"})


def _motion_to(s: ParseState, verb: str, k: int) -> Result:
    """What follows "to": a side ("move to the left"), a verb ("go to find the cup") or a place."""
    toks, n = s.toks, s.n
    k2 = k
    while k2 < n and toks[k2] in ("the", "your", "my"):
        k2 += 1
    if s.at(k2) in ("left", "right", "front", "back", "rear") and (
            k2 + 1 >= n or toks[k2 + 1] not in ("of", "side", "hand", "wall", "door", "room")):
        return read_move(s, k, verb)  # "move to the left"
    if k < n and toks[k] in ALL_VERBS and toks[k] not in ("back", "face", "stand", "hand", "end", "break") and not (
            toks[k] == "like" and s.at(k + 1) in DETERMINERS):  # ("go to like the kitchen": a filler)
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
    if verb in _BARE_PLACE_VERBS and _may_name_a_place(s, t):
        return _bare_place(s, j)
    if verb in _BARE_PLACE_VERBS and t == "," and _may_name_a_place(s, s.at(j + 1)):
        return _bare_place(s, j + 1)  # "let's go, kitchen, chop chop": where, after a breath
    return read_move(s, j, verb, default_back=verb in ("back", "retreat", "reverse"))


# verbs that may name a place with no "to", as people short of words or in a hurry say it ("go
# kitchen", "head station two"); the place is resolved against the map like any other, so a word
# that names none ("go crazy") is asked about, never walked to
_BARE_PLACE_VERBS = frozenset({"go", "head", "walk", "run", "hurry", "rush", "drive"})
_HOW_NOT_WHERE = frozenset({"faster", "slower", "quicker", "closer", "further", "farther", "crazy", "wild", "quiet",
                            "slow", "fast", "quick", "easy", "alone", "together", "outside", "inside", "away", "first",
                            "last", "again", "already", "instead", "nuts", "mad", "live", "off", "out", "up", "down",
                            "another"})  # ("walk another metre": how far, said again)


def _bare_place(s: ParseState, j: int) -> Result:
    """A place named with no "to" at ``j``, up to a pause or the next verb ("go kitchen", "you go
    bathroom now"); a verb right after it is the next command, said with no "and" ("go kitchen
    take apple")."""
    j += s.at(j) in ("the", "your", "our")  # "go the kitchen"
    e = j
    while e < s.n and e < j + 4 and s.toks[e] not in s.stop_words and s.toks[e] not in ALL_VERBS:
        e += 1
    if any((q := read_quantity(s.toks, k)) is not None and q.dimension for k in range(j, e)):
        return None  # "go backside one metre": an amount, so a move the grammar did not read, no place
    place = read_place(s, list(s.toks[j:e]))
    if place is None:
        return None
    if may_end(s, e):
        return read_go(s, place, e)
    more = s.read_clause(s, e) if s.at(e) in ALL_VERBS else None
    if more is None:
        return None
    specs, end = more
    return [(NAVIGATE, place, 0.0, 0.0, 0.0), *specs], end


def _may_name_a_place(s: ParseState, t: str) -> bool:
    """Whether ``t``, right after a motion verb, may start a place's name: a word, and none the
    grammar knows as something else (a direction, a verb, an amount, an adverb or a filler)."""
    return (t.isalpha() and (t not in DETERMINERS or t in ("the", "your", "our")) and t not in s.stop_words
            and t not in ALL_VERBS and t not in DIRECTIONS
            and t not in TRAILING and t not in HOME and t not in _HOW_NOT_WHERE and word_value(t) is None
            and not t.endswith("ly"))


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


VISIT_VERBS = frozenset({"stop", "swing", "drop", "come", "pop", "go", "pass", "nip", "call"})


def read_visit_by(s: ParseState, i: int) -> Result:
    """ "stop by the kitchen", "swing by the workbench", "drop by station 3": a visit
    (navigate_to_marker). Only with a place after "by": "stand by" and "stop by 5" are not."""
    if s.at(i + 1) != "by" or s.at(i + 2) not in ("the", "your", "my", "our", "station"):
        return None
    words, e = read_noun_phrase(s, i + 2)
    place = read_place(s, words)
    return ([(NAVIGATE, place, 0.0, 0.0, 0.0)], e) if place and words[-1] not in SURFACES else None
