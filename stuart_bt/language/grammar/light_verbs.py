"""The light verbs do / make / perform / give / show / take / throw, whose object says what
is meant: a gesture ("do a high five"), a pick ("take the cup"), a search ("do a search for
the keys"), a turn ("do a 180", "make a U-turn") or a walk ("take two steps forward", "take me
to the kitchen").
"""

from __future__ import annotations

import math

from ..intents import GESTURE, MOVE, NAVIGATE, TURN, TURN_AROUND
from ..numbers import UNITS
from .amounts import NUMBER_STARTS, STEP_WORDS, read_move, read_turn_terms
from .finding import read_find_noun
from .gestures import skip_gesture_tail
from .lexicon import (
    ALL_VERBS,
    AROUND,
    BOUNDARY,
    DETERMINERS,
    FIND_NOUN_LEADS,
    GESTURE_NOUNS,
    GESTURE_PHRASES,
    GESTURES_BY_FIRST,
    ROTATIONS,
    TO_WORDS,
    TRAILING,
)
from .motion import read_guide
from .nouns import read_noun_phrase, read_place, read_way_to
from .picking import read_pick
from .state import Found, ParseState, Result, may_end


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
    if verb == "show" and s.at(i + 2) == "how" and s.at(i + 3) in ("you", "to") and s.at(i + 4) in ALL_VERBS:
        return s.read_clause(s, i + 4)  # "show me how you shake hands": do it
    j = _past_audience(s, i + 1)
    k = _past_modifiers(s, j)
    g = s.phrase_at(k, GESTURES_BY_FIRST)
    if g is None and verb in ("give", "show") and (named := _past_someone(s, j)) > j:
        k = _past_modifiers(s, named)  # "give Lily a high five", "give the lady a hug"
        g = s.phrase_at(k, GESTURES_BY_FIRST)
    if g is not None and not (s.toks[k] in ("five",) and verb not in ("give",)):
        return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], skip_gesture_tail(s, k + len(g))
    if verb in ("do", "make", "perform", "take", "try", "pull", "execute", "throw"):
        return _do_a_motion(s, verb, i, j, k)
    if verb == "give" and (turned := _turn_amount(s, verb, j)) is not None:
        return turned  # "give us a quarter turn to the right"
    if verb == "give" and (s.at(i + 1) in ("me", "us") or s.at(i + 1) in DETERMINERS):
        return read_pick(s, i)
    return None


# people the robot may take somewhere ("take the kids to the drone cage")
_PEOPLE = frozenset({"visitors", "visitor", "guests", "guest", "kids", "children", "students", "group", "people",
                     "family", "class", "team", "delegation", "parents", "folks", "lady", "ladies", "gentleman",
                     "gentlemen", "man", "woman", "boy", "girl", "professor", "investors", "guys"})


def _led_somewhere(s: ParseState, verb: str, i: int) -> Found | None:
    """ "take me to the kitchen", "take yourself over to the lab", "show me to the bathroom",
    "show us the way to ...", "show me where the kitchen is": a walk there."""
    j = i + 1
    if verb == "take" and s.at(j) in ("our", "the", "these", "those", "my", "your", "this", "that") and s.at(
            j + 1) in _PEOPLE:
        j += 1  # "take our visitors to the 3D printers": people are guided, not picked up
    if verb == "take" and (s.at(j) in ("me", "us", "him", "her", "them", "yourself", "everyone", "everybody")
                           or s.at(j) in _PEOPLE):
        k = j + 2 if s.at(j + 1) in ("over", "off", "down", "up", "back", "across") else j + 1
        if s.at(k) in TO_WORDS:  # "take me to the kitchen", "take yourself over to the reading room"
            words, e = read_noun_phrase(s, k + 1)
            return Found(_walk_to(s, words, e))
    if verb != "show" or s.at(j) not in ("me", "us", "them", "him", "her", "everyone"):
        return None
    k = j + 1
    if s.at(k) in TO_WORDS:
        return Found(read_guide(s, i))  # "show me to the bathroom"
    if s.at(k) == "the" and s.at(k + 1) == "way" and s.at(k + 2) in TO_WORDS:
        words, e = read_noun_phrase(s, k + 3)
        return Found(_walk_to(s, words, e))
    if s.at(k) == "where" and k + 1 < s.n:
        words, e = read_noun_phrase(s, k + 1 + (1 if s.at(k + 1) in ("the",) else 0))
        return Found(_walk_to(s, words, e + 1) if s.at(e) in ("is", "are") else None)
    return None


def _walk_to(s: ParseState, words: list[str], end: int) -> Result:
    target = read_place(s, words)
    return ([(NAVIGATE, target, 0.0, 0.0, 0.0)], end) if target else None


def _past_audience(s: ParseState, j: int) -> int:
    """Past whom (or what) it is done for: "show me", "do the guests a ...", "give everyone a
    wave", "give it a quarter turn to the left" (the robot's own turn: "it" is any thing)."""
    if s.at(j) in ("the", "our") and s.at(j + 1) in ("guests", "visitors", "kids", "children", "audience",
                                                     "crowd", "people", "group", "class", "team"):
        return j + 2
    if s.at(j) in ("me", "us", "him", "her", "them", "everyone", "everybody", "you") or (
            s.at(j) == "it" and s.at(j + 1) in ("a", "an")):
        return j + 1
    return j


def _past_someone(s: ParseState, j: int) -> int:
    """Past a person named or described before what is given ("give Lily a ...", "give the
    lady a ...", "give my little sister a ..."): up to the "a" that opens the thing given, within
    four words; ``j`` when there is none."""
    for k in range(j + 1, min(j + 5, s.n)):
        t = s.toks[k]
        if t in ("a", "an"):
            return k
        if t in BOUNDARY:
            break
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
