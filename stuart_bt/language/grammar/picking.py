"""The pick family: "pick up the cup", "grab the bottle from the table", "lift the box",
"get the apple", "give me the book", "bring the cup to the kitchen". A pick names the object
and, maybe, where it is and where it should go.
"""

from __future__ import annotations

from collections.abc import Callable

from ..intents import GESTURE, NAVIGATE, PICK
from .gestures import read_raise, skip_gesture_tail
from .lexicon import (
    BODY,
    BOUNDARY,
    CHOICES,
    DETERMINERS,
    GESTURE_PHRASES,
    GESTURES_BY_FIRST,
    GET_IDIOM_NEXT,
    NP_BLOCK,
    OBJECT_PRONOUNS,
    SURFACES,
    TO_WORDS,
)
from .motion import read_guide, read_motion
from .nouns import read_noun_phrase, read_object, read_place, read_shared_list
from .state import Found, ParseState, Result, Spec


def read_pick(s: ParseState, i: int) -> Result:
    """pick up / grab / get / fetch / bring / take / hand me ...: pick_up, with a source ("from
    the kitchen": go there first) or a destination ("to the workbench": go there after)."""
    verb = s.toks[i]
    opener = _PICK_OPENERS.get(verb)
    start = opener(s, i) if opener is not None else i + 1
    if isinstance(start, Found):
        return start.result
    start = _past_recipient(s, verb, i, start)
    if isinstance(start, Found):
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


def _after_pick(s: ParseState, i: int) -> int | Found:
    """ "pick up", "pick the cup up"; "pick a card" is choosing, not lifting."""
    j = i + 1
    if s.at(j) in ("up", "out"):
        return j + 1
    if "up" not in s.toks[j:j + 8]:
        words, _ = read_noun_phrase(s, j)
        if not words or words[-1] in CHOICES:
            return Found(None)
    return j


def _after_lift(s: ParseState, i: int) -> int | Found:
    """ "lift the box"; "lift your hands" is a gesture."""
    j = i + 1
    k = j + 1 if s.at(j) in ("your", "both", "the", "my") else j
    if s.at(k) in BODY or s.at(k) in ("right", "left", "both") and s.at(k + 1) in BODY:
        return Found(read_raise(s, i))
    return j


def _after_get(s: ParseState, i: int) -> int | Found:
    """ "get the cup"; "get to the kitchen" is a walk, "get going", "get over it" are neither."""
    j = i + 1
    t = s.at(j)
    if t not in GET_IDIOM_NEXT:
        return j
    if t in ("to", "back", "home") or (t == "over" and s.at(j + 1) in TO_WORDS):
        return Found(read_motion(s, i))  # (read_motion hands "get" without a destination back here)
    if t in ("a", "an", "it", "some"):
        return j
    return Found(None)  # "get over it", "get ready", "get lost"


def _after_give(s: ParseState, i: int) -> int | Found:
    """ "give me a high five" is a gesture; "hand over the screwdriver" an object."""
    j = k = i + 1
    if s.at(k) in OBJECT_PRONOUNS and s.at(k) not in ("them", "you", "yourself"):
        k += 1
    elif s.at(k) == "over" and s.toks[i] in ("hand", "pass"):
        j = k = k + 1  # "hand over the screwdriver"
    k2 = k + 1 if s.at(k) in DETERMINERS else k
    g = s.phrase_at(k2, GESTURES_BY_FIRST)
    if g is not None:
        return Found(([(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], skip_gesture_tail(s, k2 + len(g))))
    return j


_PICK_OPENERS: dict[str, Callable[[ParseState, int], int | Found]] = {
    "pick": _after_pick, "lift": _after_lift, "raise": _after_lift, "get": _after_get,
    **dict.fromkeys(("give", "hand", "pass"), _after_give),
}


def _past_recipient(s: ParseState, verb: str, i: int, j: int) -> int | Found:
    """Past who the object is for ("bring me the cup", "bring to me the bottle"); "bring me to
    the kitchen" is being guided there."""
    if verb in ("bring", "carry") and s.at(j) in ("me", "us", "them", "him", "her") and _to_after_ways(s, j + 1):
        return Found(read_guide(s, i))  # "bring me to the kitchen"
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


def _to_after_ways(s: ParseState, k: int) -> bool:
    """Whether "to" comes at ``k``, perhaps after "over" or "back" ("bring us back over to the
    entrance"): someone brought to a place, so led there."""
    while s.at(k) in ("over", "back"):
        k += 1
    return s.at(k) in TO_WORDS
