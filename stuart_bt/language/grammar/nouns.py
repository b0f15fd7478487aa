"""Noun phrases: objects, places ("the charging dock", "station 3", "there"), lists of them."""

from __future__ import annotations

from ..intents import NAVIGATE
from ..numbers import word_value
from .lexicon import (
    ADDRESS_TERMS,
    ALL_VERBS,
    BODY,
    BOUNDARY,
    CORRECTIONS_BY_FIRST,
    DETERMINERS,
    GENERIC,
    GESTURES_BY_FIRST,
    HOME,
    NP_BLOCK,
    NP_LEADERS,
    NP_STOP,
    OBJECT_PRONOUNS,
    PRONOUNS,
    RETRACTIONS_BY_FIRST,
    STRONG_VERBS,
    SUBJECT_AND_IS,
    SURFACES,
    TO_WORDS,
    TRAILING,
    VERB_PARTICLES,
    WH,
)
from .state import ParseState, Result, numbers_a_step, said_instead_at, starts_a_stop, verb_and_it


def read_noun_phrase(s: ParseState, i: int) -> tuple[list[str], int]:
    """A noun phrase from ``i`` to the next connector, preposition or trailing word; leading
    determiners removed ("the red cup" -> ["red", "cup"]). Returns (words, end)."""
    toks, n, stop = s.toks, s.n, s.stop_words
    if s.at(i) == "like" and s.at(i + 1) in DETERMINERS:
        i += 1  # "go to like the kitchen": a filler before the phrase
    j = i
    while j < n:
        t = toks[j]
        if t == "like" and j > i and toks[j - 1] in DETERMINERS:
            j += 2 if s.at(j + 1) == "," else 1  # "go to the like reading room": a filler
            if s.at(j) in DETERMINERS and j - 2 >= i and toks[j - 2] in DETERMINERS:
                j += 1  # "go to the like the humanoid corner": the phrase said again
            continue
        if t in stop:
            if j == i and t in ("that", "this", "there", "here", "right"):
                j += 1  # "pick that up", "go there": the caller reads a pronoun
                if t != "that" or j >= n or toks[j] in stop:
                    break
                continue
            if t == "next" and j + 1 < n and toks[j + 1] not in ("to",):
                j += 1  # "the next station"
                continue
            if t == "right" and j > i and (j + 1 >= n or toks[j + 1] in BOUNDARY or toks[j + 1] in NP_STOP):
                break
            if t == "right" and j + 1 < n and toks[j + 1] not in ("now", "there", "here", "away"):
                j += 1  # "the right cup", "right kiss" read by other rules first
                continue
            break
        if j > i and _something_else_at(s, i, j):
            break
        j += 1
    words = toks[i:j]
    while len(words) > 1 and (words[0] in DETERMINERS or words[0] in NP_LEADERS or words[0] in ("like", ",")):
        words = words[1:]  # ("the, like, reading room": a filler after the determiner)
    if j >= n or toks[j] in BOUNDARY:
        while len(words) > 1 and (words[-1] in ADDRESS_TERMS or words[-1] in _THANKS_WORDS):
            words = words[:-1]  # "go find the apple buddy", "grab the bottle mate cheers": no part of the thing
    return words, j


def _something_else_at(s: ParseState, i: int, j: int) -> bool:
    """Whether the noun phrase begun at ``i`` ends before ``j`` because something else starts
    there: a verb, another phrase, a stop, a statement, a retraction or a correction."""
    toks, n, t = s.toks, s.n, s.toks[j]
    if t in STRONG_VERBS or _another_phrase_at(toks, i, j) or starts_a_stop(s, j) or verb_and_it(s, j):
        return True  # ("go to the kitchen hold it": the stop is read, and wins)
    if t in ALL_VERBS and j + 1 < n and (t, toks[j + 1]) in VERB_PARTICLES:
        return True
    if said_instead_at(s, j):
        return True  # "pick up the apple hmm actually the book"
    if t in GESTURES_BY_FIRST and t in ALL_VERBS and len(s.phrase_at(j, GESTURES_BY_FIRST) or ()) > 1 or (
            t in ("raise", "put", "lift") and (s.at(j + 2) in BODY or s.at(j + 3) in BODY)) or (
            numbers_a_step(s, j)):  # ("find the apple second pick it up")
        return True  # "when you get to the humanoid corner put your hands up": a gesture, said with no pause
    if t in SUBJECT_AND_IS and s.at(j + 1) not in BOUNDARY or t in DETERMINERS and j + 1 in s.contracted:
        return True  # "find the apple its my lunch", "go to the dock your battery's low": a statement follows
    if t in RETRACTIONS_BY_FIRST and s.phrase_at(j, RETRACTIONS_BY_FIRST) is not None:
        return True  # "go to the kitchen just kidding": what follows takes the request back
    if t in CORRECTIONS_BY_FIRST and len(s.phrase_at(j, CORRECTIONS_BY_FIRST) or ()) > 1:
        return True  # "go to the bathroom scratch that", "the kitchen I mean the bathroom": a correction
    return t == "back" and toks[j - 1] not in DETERMINERS and (
        j + 1 >= n or toks[j + 1] in TO_WORDS or toks[j + 1] in BOUNDARY or toks[j + 1] in HOME
        or toks[j + 1] in ("here", "there", "over"))  # "bring the book back to the entrance", "put it back"


# thanks said after a command's thing ("grab the bottle mate cheers"), never part of it
_THANKS_WORDS = frozenset({"thanks", "thank", "cheers", "ta", "thx", "ty"})

# determiners and subject pronouns, which after a noun open another noun phrase or a clause ("the
# cup the kids want", "the man a bottle", "the kitchen we are late"); a determiner not after "of"
# ("a bottle of the water")
_OPENS_ANOTHER = frozenset({"the", "a", "an", "i", "im", "ive", "we", "weve", "he", "hes", "she", "shes", "they",
                            "theyre", "theyve", "youre", "youve"})


def _another_phrase_at(toks: list[str], i: int, j: int) -> bool:
    """Whether ``toks[j]``, inside a noun phrase that began at ``i``, starts something else: a
    verb after a number ("when you get to station six put your hands up"), or a determiner or a
    subject after a noun ("pick up the cup the kids want to see it"; not after "of")."""
    t, before = toks[j], toks[j - 1]
    if j > i + 1 and t in ALL_VERBS and word_value(before) is not None:
        return True
    return t in _OPENS_ANOTHER and before not in DETERMINERS and before != "of"


def _no_noun(words: list[str]) -> bool:
    """A cut-off phrase with no noun: a lone determiner ("go to the"), or a verb and its
    indirect object ("give me give me")."""
    return (len(words) == 1 and words[0] in DETERMINERS) or (
        len(words) == 2 and words[0] in ALL_VERBS and words[1] in OBJECT_PRONOUNS)


def not_a_target(words: list[str]) -> bool:
    """Words that cannot name a thing or a place, whatever they follow: a clause ("whatever Dave
    left"), a verb and its pronoun ("juggle it"), only filler ("mate", "buddy"), or a way of
    moving ("the bathroom backwards"). Leftover words never become targets."""
    return words[0] in WH or words[-1] in ("it", "them") or words[-1] in MANNER or TRAILING.issuperset(words)


MANNER = frozenset({"backwards", "backward", "forwards", "sideways", "slowly", "quickly", "carefully"})


def read_object(s: ParseState, words: list[str]) -> str | None:
    """The spoken object of a pick or find, with "it"/"them"/"that one" meaning the last object
    named in this command; ``None`` when nothing usable was said."""
    if not words:
        return None
    text = " ".join(words)
    if text in PRONOUNS:
        return s.last_object or s.topic or None  # "pick it up" with nothing named before: no command
    if words[0] in ("it", "them", "him", "her", "me", "us") or _no_noun(words):
        return None  # "take it easy", "bring it on"
    if text in GENERIC or text in NP_BLOCK or text in OBJECT_PRONOUNS or words[0] in ("not", "no"):
        return None
    if all(word_value(w) is not None for w in words):
        return None  # "take five": a number is no object
    return None if not_a_target(words) else text


def read_place(s: ParseState, words: list[str]) -> str | None:
    """The spoken place of a navigation, with "there" meaning the last place named; a plural
    before a number is singular ("stations one, two and three": "station one", ...)."""
    if not words:
        return None
    if len(words) >= 2 and words[-2].endswith("s") and not words[-2].endswith("ss") and word_value(
            words[-1]) is not None:
        words = [*words[:-2], words[-2][:-1], words[-1]]
    text = " ".join(words)
    if text in ("there", "that place", "it", "that"):
        return s.last_place or s.topic or None
    if (text in GENERIC or text in NP_BLOCK or text in OBJECT_PRONOUNS or words[0] in ("not", "no") or text == "here"
            or _no_noun(words) or words[-1] in OBJECT_PRONOUNS):
        return None  # ... and "(sorry) to bother you": a verb and its object, no place
    return None if not_a_target(words) else text


def numbered_place(place: str) -> tuple[str, float] | None:
    """ "station three" -> ("station", 3.0): a place named by a number, or ``None``."""
    head, _, last = place.rpartition(" ")
    value = word_value(last) if head else None
    return (head, value) if value is not None else None


def read_go(s: ParseState, target: str | None, e: int) -> Result:
    """navigate_to_marker ``target`` (ending at ``e``); a numbered range is one per number:
    "visit stations 1 to 3", "station one through three" -> station 1, station 2, station 3."""
    if target is None:
        return None
    num = numbered_place(target) if s.at(e) in ("to", "through", "thru") else None
    last = word_value(s.at(e + 1)) if num else None
    if num and last is not None and num[1] == int(num[1]) and last == int(last) and num[1] < last <= num[1] + 10:
        return [(NAVIGATE, f"{num[0]} {k}", 0.0, 0.0, 0.0) for k in range(int(num[1]), int(last) + 1)], e + 2
    return [(NAVIGATE, target, 0.0, 0.0, 0.0)], e


def read_shared_list(s: ParseState, e: int) -> tuple[list[str], int]:
    """More objects after the first ("the cup and the bottle", "the cup, the book and the
    apple") when a source or destination follows the last one, which then applies to all:
    (the other objects, end). Without one the list is left to the ellipsis rule."""
    more: list[str] = []
    k = e
    while s.at(k) in (",", "and"):
        k += 1
        if s.at(k) == "and":
            k += 1
        if s.at(k) not in DETERMINERS:
            return [], e
        words, k2 = read_noun_phrase(s, k)
        obj = read_object(s, words) if words else None
        if obj is None:
            return [], e
        more.append(obj)
        k = k2
    if more and (s.at(k) == "from" or s.at(k) in ("to", "into") and s.at(k + 1) in DETERMINERS | {"station"}):
        return more, k
    return [], e


def read_way_to(s: ParseState, m: int) -> Result:
    """After "make your way" / "find your way": (over, back, ...) to PLACE."""
    while s.at(m) in ("over", "back", "down", "up", "across", "round", "around", "straight"):
        m += 1
    if s.at(m) not in TO_WORDS:
        return None
    words, e = read_noun_phrase(s, m + 1)
    target = read_place(s, words)
    return ([(NAVIGATE, target, 0.0, 0.0, 0.0)], e) if target else None


def read_arrival(s: ParseState, i: int) -> Result:
    """After "when you" / "once you": being somewhere is getting there ("once you're at the
    workbench, pick up the screwdriver", "when you arrive in the kitchen ..."): navigate_to_marker,
    dropped like any subordinate clause when it repeats the navigation before it. (After "if"
    it is a condition, not a plan.)"""
    if s.at(i) in ("are", "re", "arrive", "arrived", "get", "got"):
        i += 1  # "when you are at ...", "once you arrive at ..."
    if s.at(i) not in ("at", "in", "inside", "by", "near"):
        return None
    words, e = read_noun_phrase(s, i + 1)
    place = read_place(s, words)
    return ([(NAVIGATE, place, 0.0, 0.0, 0.0)], e) if place and words[-1] not in SURFACES else None
