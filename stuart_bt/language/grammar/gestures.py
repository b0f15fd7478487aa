"""The gesture family: "wave", "give a thumbs up", "say hello and wave", "shake hands",
"blow a kiss", "raise your arms", "lower your hands". A gesture verb reads its name and the
words that may trail it (to whom, with which hand).
"""

from __future__ import annotations

from collections.abc import Callable

from ..intents import GESTURE
from .forms import takes_back_at
from .lexicon import (
    BODY,
    BOUNDARY,
    DETERMINERS,
    GESTURE_PHRASES,
    GESTURE_VERB_NAMES,
    GESTURES_BY_FIRST,
    STRONG_VERBS,
)
from .state import ParseState, Result, starts_a_stop


def skip_gesture_tail(s: ParseState, j: int) -> int:
    """Words after a gesture that change nothing: "gesture", "with your hands", "at me", "to
    the camera", "for the visitors", "hello", "goodbye"."""
    toks, n = s.toks, s.n
    while j < n and toks[j] not in BOUNDARY:
        if toks[j] in STRONG_VERBS and toks[j] not in ("wave",) and j + 1 < n and toks[j + 1] not in BOUNDARY:
            break
        if starts_a_stop(s, j):
            break  # "wave at the visitors stop": the stop is read, and wins
        if toks[j] == "with" and _one_hand(s, j + 1):
            break  # "wave with your right hand": a gesture plays as it was made, so the robot asks
        if toks[j] in _WHEN:
            break  # "wave to the visitors at half past two": a time the robot cannot wait for, so it asks
        if takes_back_at(s, j):
            break  # "give us a hug actually forget it": what follows takes it back
        j += 1
    return j


# words that say when, not how long ("wave for a second" is a short wave)
_WHEN = frozenset({"past", "oclock", "pm", "noon", "midnight", "tomorrow", "tonight", "later"})


def _one_hand(s: ParseState, k: int) -> bool:
    """Whether one hand or arm is chosen at ``k`` ("your left hand", "the right arm", "one hand")."""
    if s.at(k) in ("your", "my", "the", "his", "her"):
        k += 1
    return s.at(k) in ("left", "right", "one", "other") and s.at(k + 1) in ("hand", "arm")


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


def read_raise(s: ParseState, i: int) -> Result:
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
    **dict.fromkeys(("raise", "put", "lift"), read_raise),
    **dict.fromkeys(("lower", "drop", "relax", "release", "rest"), _lower_arms),
}
