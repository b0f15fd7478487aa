"""Clauses: polite openers and requests, which verb family reads a verb, verbless clauses
(ellipsis, "about face", "high five!"), connectors between clauses.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from ..intents import FIND, GESTURE, MOVE, NAVIGATE, PICK, STOP, TURN, TURN_AROUND
from ..numbers import ANGLE, UNITS, word_value
from .amounts import MAX_BARE_SIDESTEP_M, NUMBER_STARTS, read_motion_terms, read_move, read_turn_terms
from .finding import read_find, read_find_noun
from .gestures import read_gesture, skip_gesture_tail
from .lexicon import (
    ADDRESS_TERMS,
    ALL_VERBS,
    AUX,
    BACKWARD,
    BOUNDARY,
    CONNECTORS_BY_FIRST,
    COPULA,
    DETERMINERS,
    DIRECTIONS,
    FIND_VERBS,
    FORWARD,
    GESTURE_NOUNS,
    GESTURE_PHRASES,
    GESTURE_VERBS,
    GESTURES_BY_FIRST,
    GUIDE_VERBS,
    HARD_STOPS,
    LEFT,
    LIGHT_VERBS,
    MODALS,
    MOTION_VERBS,
    OBJECT_PRONOUNS,
    PAST,
    PICK_VERBS,
    PLAIN_STOPS,
    POLITE_BY_FIRST,
    REORDER,
    REQUESTS_BY_FIRST,
    RIGHT,
    ROTATIONS,
    SIGN_OFFS_BY_FIRST,
    SPEAKER_OPENERS_BY_FIRST,
    STEP_ORDINALS,
    STOP_PHRASES_BY_FIRST,
    STOP_VERBS,
    SUBJECTS,
    THANKS_AHEAD_FEELINGS,
    THANKS_AHEAD_INTENSIFIERS,
    THANKS_AHEAD_OPENERS_BY_FIRST,
    TO_WORDS,
    TURN_IDIOMS_BY_FIRST,
    TURN_VERBS,
    WANTS,
    WANTS_OBJECT,
    WH,
    WISH_QUESTIONS_BY_FIRST,
    by_first,
)
from .light_verbs import read_do
from .motion import VISIT_VERBS, read_guide, read_motion, read_turn, read_visit_by
from .nouns import numbered_place, read_noun_phrase, read_object, read_place
from .picking import read_pick
from .state import ParseState, Reader, Result, may_end, numbers_a_step
from .stopping import read_stop


def _family(verb: str) -> Callable[[ParseState, int], Result] | None:
    return _DISPATCH.get(verb)

_DISPATCH: dict[str, Callable[[ParseState, int], Result]] = {}

for _verbs, _reader in ((MOTION_VERBS, read_motion), (TURN_VERBS, read_turn), (PICK_VERBS, read_pick),
                        (FIND_VERBS, read_find), (STOP_VERBS, read_stop), (GESTURE_VERBS, read_gesture),
                        (LIGHT_VERBS, read_do)):
    _DISPATCH.update(dict.fromkeys(_verbs, _reader))

# Each family by name, for a verb one family reads as another's (ParseState.read_as): wired here,
# above every family module, so that no family imports one that imports it.
FAMILY_READERS: dict[str, Reader] = {
    "motion": read_motion, "turn": read_turn, "pick": read_pick, "find": read_find, "stop": read_stop,
    "gesture": read_gesture, "light_verbs": read_do,
}

_DISPATCH["get"] = read_motion  # "get to the kitchen" / "get me a cup" (it hands over to read_pick)

_DISPATCH["take"] = _take = read_do  # "take me to", "take a step", "take a left", else pick

_DISPATCH["make"] = read_do

_DISPATCH["give"] = read_do

_DISPATCH["raise"] = read_gesture

_DISPATCH["lift"] = read_pick

_DISPATCH.update(dict.fromkeys(GUIDE_VERBS, read_guide))

_DISPATCH["have"] = read_find_noun  # "have a look for ..." (and nothing else: "have a seat")


def _polite(s: ParseState, i: int) -> int:
    """Index after polite openers ("could you please", "would you mind", "I want you to",
    "let's", "you", "please") that come before the verb."""
    toks, n = s.toks, s.n
    for _ in range(8):
        if i >= n:
            break
        t = toks[i]
        if t in s.vocatives:
            i += 1  # "actually Stuart, stop": the name said again before the verb
            continue
        if t in THANKS_AHEAD_OPENERS_BY_FIRST and (after := _thanks_ahead(s, i)):
            i = after  # "I'd be ever so grateful if you could ..."
            continue
        p = s.phrase_at(i, POLITE_BY_FIRST) if t in POLITE_BY_FIRST else None
        if p is None:
            if t in MODALS and i + 1 < n and toks[i + 1] == "you":
                i += 2
                continue
            if i > 0 and (called := called_at(s, i)) and s.at(i + called) in ALL_VERBS:
                i += called  # "alright buddy head over to the charging dock": the robot called after an opener
                continue
            if t == "you" and i + 1 < n and toks[i + 1] in ALL_VERBS and toks[i + 1] not in ("look", "do", "stand",
                                                                                             "back", "hold") and (
                    not compares(s, i)):  # ("you pick up bottles faster than our interns": a comparison)
                i += 1
                continue
            break
        if p == ("right",) and (i + 1 >= n or toks[i + 1] in BOUNDARY or toks[i + 1] in NUMBER_STARTS or toks[
                i + 1][:1].isdigit() or toks[i + 1] in ("by", "about", "turn")):
            break  # "right" is a direction here
        if p in (("start",), ("begin",), ("keep",)) and not (i + 1 < n and toks[i + 1] in ALL_VERBS):
            break
        after = i + len(p) + (1 if p in _OPENERS_BEFORE_A_PAUSE and s.at(i + len(p)) == "," else 0)
        if p in _BEFORE_A_VERB_ONLY and not _verb_at(s, after) and not (
                p == ("like",) and s.at(i + 1) in MODALS and s.at(i + 2) == "you"):
            break  # "like" is a filler only before a verb ("could you like go there") or a request ("like could you")
        i += len(p)
        if (p[0] == "if" or p in _OPENERS_BEFORE_A_PAUSE) and s.at(i) == ",":
            i += 1  # "if you don't mind, turn around", "come on, go to the bathroom"
    return i


def _verb_at(s: ParseState, k: int) -> bool:
    """Whether a verb is said at ``k``, perhaps after "just" ("you know, just go ...")."""
    return s.at(k + (s.at(k) == "just")) in ALL_VERBS


def called_at(s: ParseState, i: int) -> int:
    """How many words at ``i`` call the robot a name before a command with no pause ("mate pick
    up the apple", "my friend, wave"): one or two, else 0."""
    k = i + 1 if s.toks[i] in _FOND and s.at(i + 1) in _CALLED else i
    return k + 1 - i if s.toks[k] in _CALLED and (s.at(k + 1) in ALL_VERBS or s.at(k + 1) == ",") else 0


# terms of address for the robot alone (not "guys", "everyone": those call others) and the
# words said before one ("my friend", "old pal")
_CALLED = ADDRESS_TERMS - {"everyone", "everybody", "guys", "folks", "lads", "kid", "son"}
_FOND = frozenset({"my", "old", "little", "big", "good", "dear"})


def _thanks_ahead(s: ParseState, i: int) -> int:
    """Index after thanks said ahead of a request at ``i`` ("I'd be ever so grateful if you
    could", "it would be great if you would"), or 0."""
    opener = s.phrase_at(i, THANKS_AHEAD_OPENERS_BY_FIRST)
    if opener is None:
        return 0
    j = i + len(opener)
    while s.at(j) in THANKS_AHEAD_INTENSIFIERS:
        j += 1
    if s.at(j) in THANKS_AHEAD_FEELINGS and s.at(j + 1) == "if" and s.at(j + 2) == "you":
        if s.at(j + 3) in ("could", "would", "can"):
            return j + 4
        if s.at(j + 3) in PAST:  # "it would be awesome if you gave me a high five"
            s.toks[j + 3] = PAST[s.toks[j + 3]]
            return j + 3
    return 0


# polite openers only when a verb follows: "could you like go", "help me find", "mind getting"
_BEFORE_A_VERB_ONLY = frozenset({("next",), ("like",), ("help", "me"), ("help", "us"), ("please", "to"), ("mind",),
                                 ("you", "mind"), ("awfully",), ("terribly",), ("ever", "so"), ("again",),
                                 ("maybe", "try"), ("come", "on"), ("you", "know", "what"), ("you", "know"),
                                 ("first",), ("firstly",),  # ("so first go to the kitchen": after an opener)
                                 *((subject, verb) for subject in ("i", "we")
                                   for verb in ("guess", "suppose", "reckon"))})


# openers a pause may follow before the verb ("come on, go to the bathroom")
_OPENERS_BEFORE_A_PAUSE = frozenset({("come", "on"), ("you", "know", "what"), ("you", "know")})


def _request(s: ParseState, i: int) -> Result:
    """ "can I have a hug" / "could we get the bottle" (gesture or pick_up) and "I want a high
    five" / "I'd love a hug" (gestures only: "I want the kitchen clean" is no command)."""
    p = s.phrase_at(i, REQUESTS_BY_FIRST)
    if p is None:
        return None
    j = i + len(p)
    k = j + 1 if s.at(j) in DETERMINERS else j
    g = s.phrase_at(k, GESTURES_BY_FIRST)
    if g is not None and (len(g) > 1 or g[0] != "five"):
        return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], skip_gesture_tail(s, k + len(g))
    if s.at(j) in ("to", "some", "help", "a") and s.at(j + 1) in ("help", "hand", "minute", "word"):
        return None
    if p in WANTS and not (p in WANTS_OBJECT and s.at(j) in ("the", "a", "an", "that", "this", "my")):
        return None
    words, e = read_noun_phrase(s, j)
    if p in WANTS and (not may_end(s, e) or any(len(w) > 4 and w.endswith("ed") for w in words[1:])):
        return None  # "I'd like the kitchen cleaned": no object handed over
    target = read_object(s, words)
    return ([(PICK, target, 0.0, 0.0, 0.0)], e) if target else None

RECIPROCAL = frozenset({"hug", "shake hand", "high five"})  # gestures made with someone


def _reciprocal(s: ParseState, i: int) -> Result:
    """ "let me shake your hand" / "can I give you a hug": the robot's half of a shared gesture."""
    p = s.phrase_at(i, SPEAKER_OPENERS_BY_FIRST)
    if p is None:
        return None
    j = i + len(p)
    while s.at(j) in ("please", "just"):
        j += 1
    if j >= s.n or (s.toks[j] not in GESTURE_VERBS and s.toks[j] not in LIGHT_VERBS and s.toks[j] != "high"):
        return None
    got = read_clause(s, j)
    if got is None or any(a != GESTURE or tg not in RECIPROCAL for a, tg, *_ in got[0]):
        return None
    return got


def opens_conversation(s: ParseState, i: int) -> bool:
    """Whether the clause at ``i`` opens like a question or statement (so the sentence is
    conversation to its end): wh-words, auxiliaries, subjects, wishes ("would you like")."""
    toks, n = s.toks, s.n
    t = toks[i]
    if t in WH or t in AUX or t in SUBJECTS:
        return True
    if t == "do" and i + 1 < n and toks[i + 1] in ("you", "i", "we", "they", "it", "he", "she", "not"):
        return True
    if t in MODALS and i + 1 < n and toks[i + 1] != "you":
        return True
    if i + 1 < n and (toks[i + 1] in AUX or toks[i + 1] in _REPORTED) and t not in ALL_VERBS and t not in BOUNDARY:
        return True  # "..., Jess is filming", "Ana said you'd go ...": a name and its verb, a statement
    if names_a_doer(s, i) or _names_and_is(s, i):
        return True
    if t in WISH_QUESTIONS_BY_FIRST and s.phrase_at(i, WISH_QUESTIONS_BY_FIRST) is not None:
        return True
    if s.contracted and any(k in s.contracted and k + 1 < n and toks[k + 1] not in BOUNDARY and _no_verb_before(s, i, k)
                            for k in range(i, min(i + 3, n))):
        return True  # "your battery's low", "the coffee's ready": a noun and "is", a statement
    return t == "you" and (not (i + 1 < n and toks[i + 1] in ALL_VERBS) or compares(s, i))


def compares(s: ParseState, i: int) -> bool:
    """Whether the sentence from ``i`` compares ("you walk faster than my dad"): a statement."""
    for k in range(i, s.n):
        if s.toks[k] in HARD_STOPS:
            return False
        if s.toks[k] == "than":
            return True
    return False


def _names_and_is(s: ParseState, i: int) -> bool:
    """Whether a thing is named at ``i`` and then said to be something ("your battery is almost
    empty", "this floor was wet"): a statement, whatever the noun."""
    if s.toks[i] not in DETERMINERS:
        return False
    for k in (i + 2, i + 3):
        if s.at(k) in AUX:
            return _no_verb_before(s, i, k) and all(s.toks[m] not in BOUNDARY for m in range(i, k))
    return False


def _no_verb_before(s: ParseState, i: int, k: int) -> bool:
    """Whether no verb or gesture is said from ``i`` to ``k``: "hands up everybody's watching" is a
    gesture and then a statement, "your battery's low" a statement from its first word."""
    return all(s.toks[m] not in ALL_VERBS and s.toks[m] not in GESTURES_BY_FIRST for m in range(i, k))


def names_a_doer(s: ParseState, i: int) -> bool:
    """Whether the words at ``i`` are someone named and what they do ("Sam needs you there", "Dr
    Patel wants the cup"): a statement about a third person, however the person is called."""
    k = i + 1 if s.toks[i] in _TITLES else i
    verb = s.at(k + 1)
    return ((verb in _THIRD_PERSON or verb in _PLURAL_LIKING and s.toks[k].endswith("s")) and s.toks[i] not in ALL_VERBS
            and s.toks[i] not in BOUNDARY and s.toks[k] not in DETERMINERS)  # ("..., kids love that")


def _asks_a_wish(s: ParseState, i: int) -> bool:
    """A question about wishes, plans or opinions at ``i`` ("do you think the kitchen is
    clean?"), unless it opens a longer polite request ("do you think you could go ...")."""
    wish = s.phrase_at(i, WISH_QUESTIONS_BY_FIRST)
    if wish is None:
        return False
    polite = s.phrase_at(i, POLITE_BY_FIRST) if s.toks[i] in POLITE_BY_FIRST else None
    if polite == wish and polite in _BEFORE_A_VERB_ONLY:  # "you know, just go to the kitchen": a filler
        return not _verb_at(s, i + len(polite) + (s.at(i + len(polite)) == ","))
    return polite is None or len(polite) <= len(wish)


# verbs that tell what someone said or thought ("Ana said you'd go to the kitchen"): a report
_REPORTED = frozenset({"said", "says", "told", "tells", "asked", "asks", "thinks", "thought", "wants", "wanted",
                       "reckons", "mentioned", "promised", "suggested"})

# words that say whom a gesture is for ("put your hands together for our speaker")
_TO_SOMEONE = frozenset({"for", "to", "at", "with"})

# how people are called before their name ("Dr Patel needs you")
_TITLES = frozenset({"dr", "doctor", "mr", "mrs", "ms", "miss", "professor", "prof", "mister", "uncle", "aunt",
                     "auntie", "nurse", "captain", "coach"})

# a third person's verbs that open a statement about them ("Sam needs you there", "mum loves it")
_THIRD_PERSON = _REPORTED | frozenset({"needs", "likes", "loves", "hates", "knows", "has", "wishes", "prefers",
                                       "expects", "sends", "says", "waits", "is", "was"})

# what a group feels or thinks, said of them ("wave, kids love that")
_PLURAL_LIKING = frozenset({"love", "like", "want", "need", "think", "know", "say", "hate", "enjoy", "prefer",
                            "adore"})

# personal pronouns: after a verb they open a new sentence rather than make the verb a noun
_PERSONAL = frozenset({"you", "we", "i", "they", "he", "she", "it", "everyone", "everybody"})


def read_clause(s: ParseState, i: int) -> Result:
    """One clause at ``i`` (after a connector): polite openers, then a verb phrase, or one of the
    verbless forms (stop phrases, "about face", a gesture name, an elliptic direction or noun
    phrase continuing the clause before)."""
    toks, n = s.toks, s.n
    if toks[i] in REQUESTS_BY_FIRST and (got := _request(s, i)) is not None:
        return got
    if toks[i] in _WANTED_BY_FIRST and (got := _wanted_at(s, i)) is not None:
        return got
    if toks[i] in SPEAKER_OPENERS_BY_FIRST and (got := _reciprocal(s, i)) is not None:
        return got
    if toks[i] in WISH_QUESTIONS_BY_FIRST and _asks_a_wish(s, i):
        return None
    i = _polite(s, i)
    if i >= n:
        return None
    t = toks[i]
    if (s.at(i + 1) in COPULA or (s.at(i + 2) in COPULA and s.at(i + 1) not in BOUNDARY and s.at(
            i + 1) not in _PERSONAL)) and not (t in PLAIN_STOPS and "were" in (s.at(i + 1), s.at(i + 2))):
        # ("stop you are about to hit the wall": a new sentence, no pause written; "stop were filming": "we're")
        return None  # "stop signs are red", "turn left is wrong": the verb is a noun here
    if t in VISIT_VERBS and s.at(i + 1) == "by" and (got := read_visit_by(s, i)) is not None:
        return got
    sp = s.phrase_at(i, STOP_PHRASES_BY_FIRST) if t in STOP_PHRASES_BY_FIRST else None
    if sp is not None and (len(sp) > 1 or t in ("stop", "halt", "freeze", "enough", "whoa", "woah")):
        return _stop_phrase(s, i, sp)
    if t in ("dont", "never") or (t == "do" and s.at(i + 1) == "not") or t == "not":
        return None  # a negated command is no command
    if t in GESTURES_BY_FIRST and (g := s.phrase_at(i, GESTURES_BY_FIRST)) is not None and len(g) > 1 and (
            may_end(s, i + len(g)) or opens_conversation(s, i + len(g)) or s.at(i + len(g)) in _TO_SOMEONE):
        # ("hands up everybody's watching", "put your hands together for our speaker")
        return _idiom_or_gesture(s, i)  # "face wave": a gesture's whole name, though it opens with a verb
    handler = _DISPATCH.get(t)
    if handler is not None:
        got = handler(s, i)
        if got is not None:
            return got
        if t not in DIRECTIONS and t not in ("back",):
            return None
    if names_a_doer(s, i):
        return None  # "..., Dr Patel needs you there": said about someone, no place
    return _verbless(s, i)


def _stop_phrase(s: ParseState, i: int, phrase: tuple[str, ...]) -> Result:
    """A stop said as a phrase ("hold on", "that's enough", "don't move"), to the next connector."""
    t = s.toks[i]
    if t in PLAIN_STOPS:
        return read_stop(s, i)
    j = i + len(phrase)
    if t in ("easy", "steady", "enough") and not may_end(s, j):
        return None
    if phrase[0] in ("dont", "do") and (s.at(j) in TO_WORDS or s.at(j) in ("near", "over", "across", "through")):
        return None  # "don't walk into the bathroom": a negated command, not "don't move"
    while j < s.n and s.toks[j] not in BOUNDARY:
        j += 1
    return [(STOP, "", 0.0, 0.0, 0.0)], j


def _verbless(s: ParseState, i: int) -> Result:
    """Clauses with no verb: "about face", "high five!", "forward two metres", "left 90",
    and ellipsis after a connector ("... and the bathroom", "... then right")."""
    t = s.toks[i]
    got = _idiom_or_gesture(s, i)
    if got is not None:
        return got
    if s.first and (got := _bare_order(s, i)) is not None:
        return got
    last = s.last_action
    if last == NAVIGATE and t in _ON_TO and s.at(i + 1) == "to":
        i, t = i + 1, "to"  # "... then over to the robot arms"
    if last == NAVIGATE and t in TO_WORDS and t != "for" and i + 1 < s.n:  # "... then to the kitchen"
        k = i + 1
        while k < s.n and s.toks[k] in ("the", "your", "my"):
            k += 1
        if s.at(k) not in DIRECTIONS:
            return _another_place(s, i + 1)
    if last == NAVIGATE and word_value(t) is not None and (num := numbered_place(s.last_place)) and may_end(s, i + 1):
        return [(NAVIGATE, f"{num[0]} {t}", 0.0, 0.0, 0.0)], i + 1  # "go to station 1, then 2"
    if t in _ABOUT and last in (MOVE, TURN) and (s.at(i + 1)[:1].isdigit() or s.at(i + 1) in NUMBER_STARTS):
        return _another_amount(s, i + 1)  # "turn left, like ninety degrees": said roughly
    if t in DIRECTIONS or t in ROTATIONS or t in ("anti", "counter") or t[0].isdigit() or t in NUMBER_STARTS or (
            t in ("to", "by") and s.at(i + 1) in ("the", "your", "left", "right")):
        return _another_amount(s, i) if s.first or last in (MOVE, TURN, TURN_AROUND) else None
    if last in (NAVIGATE, PICK, FIND) and t not in WH and t not in AUX and (t not in SUBJECTS or t in DETERMINERS) and (
            not s.subordinate):  # "... and when you're ready, wave": "ready" is no second place
        return _another_target(s, i, last)
    return None


_ORDER_WORDS = by_first(sorted({("now",), ("go",), ("please",), ("quick",), ("quickly",), ("asap",), ("pronto",),
                                 ("if", "you", "please"), ("if", "you", "would"), ("if", "you", "dont", "mind"),
                                 ("you", "go"), ("off", "you", "go"), ("right", "now"), ("chop", "chop"),
                                 ("with", "you"), ("we", "go")},
                                key=lambda p: (-len(p), p)))


# words before "to" in a verbless order ("off to the kitchen with you", "on to station five", "over
# to the workbench"): they say "go", as "to" alone does
_ON_TO = frozenset({"off", "on", "onwards", "onward", "over", "across", "along", "straight"})

_FIRST = frozenset({"first", "firstly"})

_ORDER_LEADS = frozenset({"to"}) | _FIRST  # "to the kitchen!", "first the workbench, then ..."

_ORDER_ENDS = HARD_STOPS | {"and", "then"}  # "to the kitchen!", "to the kitchen and then wave"


def _bare_order(s: ParseState, i: int) -> Result:
    """A place said as an order with no verb, first in the command: "kitchen, now", "station
    four, go", "to the workbench you go", "to the 3D printers!". Alone, a noun is no order
    ("kitchen?" asks about it); "to" and a place must end the sentence ("off to the kitchen with
    you", "on to station five now"), and "first" and a place be followed by "then" ("first the
    workbench, then the entrance")."""
    j = i + 2 if s.toks[i] in _ON_TO and s.at(i + 1) == "to" else i + 1 if s.toks[i] in _ORDER_LEADS else i
    if j >= s.n or s.toks[j] in ALL_VERBS or s.toks[j] in SUBJECTS and s.toks[j] not in DETERMINERS:
        return None  # "to be honest, ...", "to me it looks fine"
    words, e = read_noun_phrase(s, j)
    if any(w in DIRECTIONS or w in UNITS for w in words):
        return None  # "three metres forward please": an amount, read as a move
    k = e + 1 if s.at(e) == "," else e
    order = s.phrase_at(k, _ORDER_WORDS) if k < s.n else None
    end = k + len(order) if order else e
    planned = s.at(k) == "then" and (s.toks[i] in _FIRST or (i > 0 and s.toks[i - 1] in _FIRST))  # "first the
    # workbench, then the entrance"
    signed = s.phrase_at(k, SIGN_OFFS_BY_FIRST) if j > i and k > e and s.at(k) in SIGN_OFFS_BY_FIRST else None
    if not words or not may_end(s, end) or not (order or planned or (signed and may_end(s, k + len(signed))) or (
            j > i and (e >= s.n or s.toks[e] in _ORDER_ENDS))):  # ("off to the drone cage, my friend")
        return None
    place = read_place(s, words)
    return ([(NAVIGATE, place, 0.0, 0.0, 0.0)], end) if place is not None else None


def _idiom_or_gesture(s: ParseState, i: int) -> Result:
    """ "about face", "u-turn"; or a gesture named alone ("high five!", "a hug")."""
    toks, n = s.toks, s.n
    idiom = s.phrase_at(i, TURN_IDIOMS_BY_FIRST)
    if idiom is not None and may_end(s, i + len(idiom)):
        return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], i + len(idiom)
    k = i + 1 if toks[i] in DETERMINERS and i + 1 < n else i
    g = s.phrase_at(k, GESTURES_BY_FIRST)
    if g is None or (len(g) == 1 and g[0] in ("five", "kiss", "waves", "kisses")):
        return None
    end = k + len(g)
    if s.at(end) in _TO_SOMEONE:
        end = skip_gesture_tail(s, end)  # "... for our speaker", "... to the kids"
    elif not may_end(s, end) and len(g) > 1:
        end = _past_recipient(s, end)  # "high five this young man": given to someone
    if not may_end(s, end) and not (len(g) > 1 and end == k + len(g) and opens_conversation(s, end)):
        return None  # (the whole name and then a statement: "hands up everybody's watching")
    while end < n and toks[end] in GESTURE_NOUNS:
        end += 1
    return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], end


def _past_recipient(s: ParseState, j: int) -> int:
    """Past the person a gesture is given to ("me", "everyone", "this young man", "the kids"):
    a pronoun, or a determiner and up to three words to the end of the clause; ``j`` when none."""
    if s.at(j) in ("me", "us", "him", "her", "them", "everyone", "everybody", "you"):
        return j + 1
    if s.at(j) in ("this", "that", "the", "these", "those", "my", "our"):
        for k in range(j + 2, j + 5):
            if may_end(s, k):
                return k
    return j


def _another_place(s: ParseState, i: int) -> Result:
    """ "... then to the kitchen": a place at ``i``, after a walk."""
    words, j = read_noun_phrase(s, i)
    target = read_place(s, words)
    if target is not None and may_end(s, j) and s.at(j) not in OBJECT_PRONOUNS:  # "(sorry) to bother you"
        return [(NAVIGATE, target, 0.0, 0.0, 0.0)], j
    return None


# words that say an amount is rough, before it ("like ninety degrees", "about two metres")
_ABOUT = frozenset({"like", "about", "around", "roughly", "approximately", "approx", "maybe", "say", "some"})


# "I'd like you over at the charging dock", "I need you at the entrance": wanted somewhere
_WANTED_BY_FIRST = by_first(sorted({(who, "need", "you") for who in ("i", "we")} | {(who, "want", "you") for who in (
    "i", "we")} | {("id", "like", "you"), ("wed", "like", "you"), ("i", "would", "like", "you"), ("id", "love", "you"),
    ("i", "need", "you", "back"), ("we", "need", "you", "back")}, key=lambda p: (-len(p), p)))


def _wanted_at(s: ParseState, i: int) -> Result:
    """ "I'd like you over at the charging dock", "I need you at the entrance", "we want you back
    in the kitchen": a walk there (a place after "at", "in", "by" or "to", perhaps after "over",
    "back", "down"); None for anything else ("I need you to ..." is read as politeness)."""
    wanted = s.phrase_at(i, _WANTED_BY_FIRST)
    if wanted is None:
        return None
    k = i + len(wanted)
    if s.at(k) in ("over", "back", "down", "up", "out"):
        k += 1
    if s.at(k) not in ("at", "in", "by", "to", "near", "inside") or s.at(k + 1) in ALL_VERBS:
        return None
    return _another_place(s, k + 1)


def _another_amount(s: ParseState, i: int) -> Result:
    """ "... then right", "forward two metres", "left 90": a move or a turn with no verb, first
    in the command or after a move or a turn (a bare "left 90" is degrees, never 90 m; a side
    with no distance is a turn: "forward two metres then left" turns, as "left" alone first in
    a command would)."""
    t, last = s.toks[i], s.last_action
    direction, amount, dim, vague, _ = read_motion_terms(s, i)
    if direction in (FORWARD, BACKWARD):
        turnish = False  # "... then left then forward one": a move, even after a turn
    elif last in (TURN, TURN_AROUND):
        turnish = True
    else:
        if s.first and amount is None and not vague and direction in (LEFT, RIGHT) and t in ("left", "right"):
            return None  # "right." alone is an acknowledgement as often as a command
        turnish = dim == ANGLE or (direction in (LEFT, RIGHT) and (amount is None or (
            dim == "" and amount > MAX_BARE_SIDESTEP_M)))
    got = read_turn_terms(s, i, "turn") if turnish else read_move(s, i, "move")
    return got if got is not None and may_end(s, got[1]) else None


def _another_target(s: ParseState, i: int, last: str) -> Result:
    """ "go to the kitchen and the bathroom", "pick up the cup and the bottle": a second target
    for the action before."""
    words, j = read_noun_phrase(s, i)
    if not words or not may_end(s, j) or any(w in DETERMINERS for w in words[1:]):
        return None  # "... and close the door": a verb and its object, not a second place
    if s.at(i) in DETERMINERS and s.at(i + 1) in DETERMINERS:
        return None  # "..., it's a bit gloomy": two determiners in a row open a clause, not a noun
    if s.contracted and any(k in s.contracted for k in range(i, j - 1)):
        return None  # "..., your battery's nearly flat": "'s" with words after it is "is", a statement
    target = read_place(s, words) if last == NAVIGATE else read_object(s, words)
    if target is None:
        return None
    return [(last, target, 0.0, 0.0, 0.0)], j


def read_topic(s: ParseState, i: int) -> bool:
    """A first clause, or one opening a sentence, that is only a noun phrase before a comma ("the
    kitchen, please go there"; "where should you go... the entrance, yeah, go to the entrance")
    becomes what "there" and "it" mean; True when it was one."""
    if not (s.first or (i > 0 and s.toks[i - 1] in HARD_STOPS)) or s.toks[i] not in DETERMINERS:
        return False
    words, j = read_noun_phrase(s, i)
    if s.at(j) != "," or not words or words[0] in SUBJECTS or any(w in COPULA or w in AUX for w in words):
        return False
    s.topic = " ".join(words)
    return True


def read_connector(s: ParseState, i: int) -> tuple[str, int] | None:
    """A connector at ``i``: ("next", end), ("reorder", end) for "but first", ("or", end)."""
    t = s.toks[i]
    if t == "to" and i + 1 < s.n and s.toks[i + 1] in ALL_VERBS and i > 0 and s.toks[i - 1] not in HARD_STOPS:
        return "next", i + 1  # "go to the kitchen to get a drink"; "... ? To grab a byte!" opens no command
    if t == "or":
        return "or", i + 1
    if t not in CONNECTORS_BY_FIRST:
        return None
    c = s.phrase_at(i, CONNECTORS_BY_FIRST)
    if c is None or (t in STEP_ORDINALS and not numbers_a_step(s, i)):
        return None  # ("the second station": no step numbered)
    return ("reorder" if c in REORDER else "next"), i + len(c)
