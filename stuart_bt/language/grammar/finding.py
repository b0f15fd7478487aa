"""The find family: "find the cup", "look for my keys", "search the kitchen for the apple",
and the noun form "a search for the bottle". A find names what to look for and, maybe, where.
"""

from __future__ import annotations

from ..intents import FIND, NAVIGATE
from .lexicon import (
    ALL_VERBS,
    BOUNDARY,
    DETERMINERS,
    FIND_NOUNS,
    TRAILING,
)
from .nouns import read_noun_phrase, read_object, read_place, read_way_to
from .state import Found, ParseState, Result


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
    if isinstance(after, Found):
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


def _after_search_verb(s: ParseState, verb: str, j: int) -> tuple[int, str | None] | Found:
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
            return Found(None)
        if s.at(e) != "for":  # "search the kitchen": a place to search; "check the kitchen": vague
            return Found(([(FIND, area, 0.0, 0.0, 0.0)], e) if verb != "check" else None)
        return e + 1, area
    if verb in ("track", "hunt") and s.at(j) == "down":
        return j + 1, None
    if verb in ("look", "hunt", "seek", "check"):
        return Found(None)  # "look left", "check it out"
    return j, None


def _after_find(s: ParseState, j: int) -> tuple[int, str | None] | Found:
    """Past "find (me)", "find for me": where the object's words start. "find out" is no find;
    "find your way to" is a walk."""
    if s.at(j) == "out":
        return Found(None)
    if s.at(j) == "your" and s.at(j + 1) == "way":
        return Found(read_way_to(s, j + 2))
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
