"""The stop family: "stop", "halt", "freeze", "stop moving", "that's enough". A stop reads its
verb and the words that only say more about stopping.
"""

from __future__ import annotations

from ..intents import NAVIGATE, STOP
from .lexicon import (
    ALL_VERBS,
    BOUNDARY,
    POLITE_BY_FIRST,
    STOP_VERB_NEEDS,
    STRONG_VERBS,
    SURFACES,
    WH,
)
from .nouns import read_noun_phrase, read_place
from .state import ParseState, Result, skip_rest


def read_stop(s: ParseState, i: int) -> Result:
    """stop / halt / freeze / wait / stay / hold on / never mind ...: stop. Reads to the next
    connector ("stop what you are doing and turn around")."""
    toks, n = s.toks, s.n
    verb = toks[i]
    j = i + 1
    nxt = s.at(j)
    if verb == "stop" and i > 0 and toks[i - 1] in _ORDINALS and nxt not in BOUNDARY and nxt not in _NO_PLACE_NEXT:
        return _next_stop(s, j)  # "next stop: the electronics bench": where to, not a stop
    needs = STOP_VERB_NEEDS.get(verb)
    if needs is not None and nxt not in needs:
        return None  # "stand in line", "never again", "cut the cake": not a stop
    if verb in ("stop", "halt") and nxt in ("me", "us", "him", "her", "them", "everyone", "everybody", "people"):
        return None  # "stop me if you've heard this one": someone else is stopped
    if verb in ("wait", "stand") and nxt in ("at", "by", "in", "near", "inside", "beside") and s.at(
            j + 1) in ("the", "your", "my", "our", "station"):
        words, e = read_noun_phrase(s, j + 1)  # "wait at the entrance": go there, then stay ("stay by the
        # charging dock": stay where it is, by the dock)
        place = read_place(s, words)
        if place is not None and words[-1] not in SURFACES:
            return [(NAVIGATE, place, 0.0, 0.0, 0.0), (STOP, "", 0.0, 0.0, 0.0)], skip_rest(s, e)
    if verb == "stand" and nxt not in ("still", "there", "by", "put", "here", "fast", "your", "right"):
        return None  # "stand in line"
    while j < n and toks[j] not in BOUNDARY and not says_why_at(s, j):
        if j > i + 1 and toks[j] in STRONG_VERBS and toks[j] not in ("move", "go", "stop", "turn", "walk"):
            break
        if (toks[j] == "dont" and s.at(j + 1) in ALL_VERBS) or (
                toks[j] == "do" and s.at(j + 1) == "not" and s.at(j + 2) in ALL_VERBS):
            break  # "no stop don't pick up that cup": a negated command of its own, never the pick
        j += 1
    return [(STOP, "", 0.0, 0.0, 0.0)], j


def says_why_at(s: ParseState, j: int) -> bool:
    """Whether a statement of its own starts at ``j``, right after a stop with no pause: a new
    subject ("stop you're going to hit the table", "stop I need to reset the map before you go
    ..."), not a request ("stop I want you to ...") nor the stop's own words ("stop what you're
    doing")."""
    t = s.at(j)
    return t in _NEW_SPEAKER_SUBJECTS and s.toks[j - 1] not in WH and (
        t not in POLITE_BY_FIRST or s.phrase_at(j, POLITE_BY_FIRST) is None)


# subjects that open a statement when said straight after a stop (not "it" nor "there": "stop
# it", "stop there" are the stop's own words)
_NEW_SPEAKER_SUBJECTS = frozenset({"i", "im", "ive", "id", "we", "were", "weve", "wed", "he", "hes", "she", "shes",
                                   "they", "theyre", "theyve", "youre", "youve", "theres", "thats", "its"})


# words before "stop" that make it a place on a route ("next stop, the kitchen")
_ORDINALS = frozenset({"next", "first", "last", "final", "second", "third"})
# words after "first stop" that say it is the verb ("..., but first stop because your arm is noisy")
_NO_PLACE_NEXT = frozenset({"because", "cause", "cos", "while", "until", "till", "please", "now", "right", "for",
                            "moving", "everything"})


def _next_stop(s: ParseState, j: int) -> Result:
    """The place named after "next stop" ("next stop: the drone cage", "next stop is the
    kitchen"), or None when no place is named (then it is no command)."""
    if s.at(j) in ("is", "will", "be"):
        j += 2 if s.at(j) == "will" else 1
    words, e = read_noun_phrase(s, j)
    place = read_place(s, words) if words else None
    return ([(NAVIGATE, place, 0.0, 0.0, 0.0)], skip_rest(s, e)) if place else None
