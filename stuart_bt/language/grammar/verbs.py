"""The readers of each verb family (motion, turn, pick, find, stop, gesture, and the light verbs
do/make/give/take that lead into the others). Each reads from a position and returns the
intents it found and the position after them; what it does not understand ends the clause.
"""

from __future__ import annotations

import math

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
    GESTURES_BY_FIRST,
    HOME,
    NP_BLOCK,
    OBJECT_PRONOUNS,
    ROTATIONS,
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
    toks, n = s.toks, s.n
    verb = toks[i]
    j = i + 1
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
    t = s.at(j)
    if verb == "back" and t in ("up", "off", "away", "out"):
        j += 1
        t = s.at(j)
    elif verb == "back" and not s.first and may_end(s, j):
        return None  # "go to the bathroom and back": a return the grammar cannot place
    if t == "straight" and s.at(j + 1) in TO_WORDS | HOME | {"back"}:
        j += 1
        t = s.at(j)
    back = False
    if t == "back" and (s.at(j + 1) in TO_WORDS | HOME or (verb in ("come", "go", "get", "head") and s.at(j + 1) in (
            "over", "down", "up") and s.at(j + 2) in TO_WORDS)):
        back = True
        j += 1
        t = s.at(j)
    if t in ("over", "up", "down", "across", "round", "around", "through", "out") and s.at(j + 1) in TO_WORDS:
        j += 1
        t = s.at(j)
    if verb == "make":
        return read_do(s, i)
    if verb == "get" and t not in TO_WORDS and t not in HOME and t != "back":
        return read_pick(s, i)
    if t in ("2", "two", "too") and s.at(j + 1) in ("the", "your", "my", "our", "station"):
        t = "to"  # "go two the kitchen": a recogniser's "to" (a number needs a unit or a direction)
    if t == "for" and (q := read_quantity(s.toks, j + 1)) is not None and q.dimension == LENGTH:
        return read_move(s, j, verb)  # "go straight for two metres": how far, not where
    if s.at(j + 1) in ("the", "your", "my", "our") and (t == "in" and verb in ("go", "come", "head", "move") or (
            t == "until" and verb in ("go", "come", "walk", "run", "head", "move", "drive"))):
        t = "to"  # "go in the kitchen", "walk until the entrance": said for "into", "up to"
    if t in TO_WORDS and t != "for" or (t == "for" and verb in ("head", "make", "go")):
        k = j + 1
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
    if t in HOME:
        return [(NAVIGATE, t, 0.0, 0.0, 0.0)], j + 1
    if t == "there" and (s.last_place or s.topic) and verb not in ("move", "step", "back"):
        return [(NAVIGATE, s.last_place or s.topic, 0.0, 0.0, 0.0)], j + 1  # "... and then go there again"
    if back or (verb == "come" and t in ("back", "here", "closer", "over", "")):
        return None  # "come back", "come here": towards the speaker, whom the grammar cannot place
    if verb in ("visit", "approach", "reach", "enter", "navigate", "goto"):
        words, e = read_noun_phrase(s, j)
        return read_go(s, read_place(s, words), e)
    if t in ALL_VERBS and t not in DIRECTIONS and verb in ("go", "come", "run", "hurry", "rush") and t not in (
            "stand", "back"):
        return s.read_clause(s, j)  # "go get the bottle", "come wave"
    if t == "and" and s.at(j + 1) in ALL_VERBS and verb in ("go", "come"):
        return s.read_clause(s, j + 1)  # "go and get the bottle"
    if verb == "face":
        return read_turn_terms(s, j, verb)
    if verb == "go" and t in ("ahead", "on", "forth") and may_end(s, j + 1):
        return None  # "go ahead", "go on": permission, not a direction
    if t in ("a", "an", "one", "two") and s.at(j + 1) in ("step", "steps") and verb == "take":
        pass
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
    toks, n = s.toks, s.n
    verb = toks[i]
    j = i + 1
    if verb == "pick":
        if s.at(j) in ("up", "out"):
            j += 1
        elif "up" not in s.toks[j:j + 8]:
            words, _ = read_noun_phrase(s, j)
            if not words or words[-1] in CHOICES:
                return None  # "pick a card": choosing, not lifting
    elif verb in ("lift", "raise"):
        k = j + 1 if s.at(j) in ("your", "both", "the", "my") else j
        if s.at(k) in BODY or s.at(k) in ("right", "left", "both") and s.at(k + 1) in BODY:
            return _raise(s, i)
    elif verb == "get":
        t = s.at(j)
        if t in ("going", "go", "moving", "move", "up", "down", "out", "ready", "closer", "away", "lost", "along",
                 "on", "off", "in", "inside", "started", "here", "over", "there", "a", "an", "rid", "it", "real",
                 "better", "well", "some", "started", "dressed", "to", "back", "home"):
            if t in ("to", "back", "home") or (t == "over" and s.at(j + 1) in TO_WORDS):
                return read_motion(s, i)  # (read_motion hands "get" without a destination back here)
            if t == "over":
                return None  # "get over it"
            if t not in ("a", "an", "it", "some"):
                return None
    elif verb in ("give", "hand", "pass"):
        k = j
        if s.at(k) in OBJECT_PRONOUNS and s.at(k) not in ("them", "you", "yourself"):
            k += 1
        elif s.at(k) == "over" and verb in ("hand", "pass"):
            j = k = k + 1  # "hand over the screwdriver"
        k2 = k + 1 if s.at(k) in DETERMINERS else k
        g = s.phrase_at(k2, GESTURES_BY_FIRST)
        if g is not None:
            return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], skip_gesture_tail(s, k2 + len(g))
    if verb in ("bring", "carry") and s.at(j) in ("me", "us", "them", "him", "her") and s.at(j + 1) in TO_WORDS:
        return read_guide(s, i)  # "bring me to the kitchen"
    if verb in ("bring", "get", "fetch", "grab", "hand", "pass", "give", "find", "buy", "pour") and s.at(j) in (
            "me", "us", "him", "her") and j + 1 < n and toks[j + 1] not in BOUNDARY and toks[j + 1] not in (
            "to", "here", "over", "back"):
        j += 1
    elif s.at(j) in ("to", "for") and s.at(j + 1) in ("me", "us") and s.at(j + 2) in DETERMINERS:
        j += 2  # "bring to me the bottle": who it is for, said first
    words, e = read_noun_phrase(s, j)
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
    k = e
    while k < n and toks[k] in ("for", "me", "us", "please", "over", "here", "back", "and", "bring", "it", "up"):
        if toks[k] == "and" and not (s.at(k + 1) in ("bring", "carry", "take") and s.at(k + 2) in ("it", "them")):
            break
        k += 1
    if s.at(k) == "from" or (s.at(k) in ("off", "out") and s.at(k + 1) in ("of", "the")):
        k2 = k + 1 + (1 if s.at(k + 1) == "of" else 0)
        src_words, e2 = read_noun_phrase(s, k2)
        src = read_place(s, src_words)
        if src is not None and src_words[-1] in SURFACES:
            src, e = None, e2  # "from the table": where the object lies, not where to go
        if src is not None and verb in ("bring", "get", "fetch", "grab", "take", "retrieve", "collect", "pick",
                                        "carry", "pass", "hand", "give"):
            out.append((NAVIGATE, src, 0.0, 0.0, 0.0))
            e = e2
            k = e2
    if not (words[0] in ("it", "them", "that", "this") and s.last_action == PICK and target == s.last_object):
        out += [(PICK, t, 0.0, 0.0, 0.0) for t in targets]  # "grab the apple and bring it to ...": picked already
    if s.at(k) in ("to", "into", "over", "towards", "toward") and verb in ("bring", "take", "carry", "deliver",
                                                                           "fetch", "get", "move"):
        k2 = k + 1 + (1 if s.at(k) == "over" and s.at(k + 1) == "to" else 0)
        dest_words, e2 = read_noun_phrase(s, k2)
        dest = " ".join(dest_words)
        if dest_words and dest not in OBJECT_PRONOUNS and dest not in ("here", "me", "us", "the user"):
            place = read_place(s, dest_words)
            if place is not None:
                out.append((NAVIGATE, place, 0.0, 0.0, 0.0))
        e = e2
    return out, e


def read_find(s: ParseState, i: int, verb: str = "") -> Result:
    """find / locate / look for / search for / check for ...: find; "search the kitchen for the
    cup" goes to the kitchen first. ``None`` for "look left", "find out ...". ``verb`` overrides
    the word at ``i`` (a noun read as a verb: "have a peek for ...")."""
    toks, n = s.toks, s.n
    verb = verb or toks[i]
    j = i + 1
    area: str | None = None
    if verb in ("look", "hunt", "scan", "search", "seek", "track", "check"):
        while s.at(j) in ("around", "about", "out", "everywhere", "all", "over", "round"):
            j += 1
        if s.at(j) == "for":
            j += 1
        elif verb in ("search", "scan", "check"):
            if s.at(j) in ("in", "inside", "through", "of"):
                j += 1  # "search in the kitchen for ...", "have a search of the kitchen for ..."
            words, e = read_noun_phrase(s, j)
            area = read_place(s, words)
            if area is None:
                return None
            if s.at(e) != "for":  # "search the kitchen": a place to search; "check the kitchen": vague
                return ([(FIND, area, 0.0, 0.0, 0.0)], e) if verb != "check" else None
            j = e + 1
        elif verb in ("track", "hunt") and s.at(j) == "down":
            j += 1
        elif verb in ("look", "hunt", "seek", "check"):
            return None
    elif verb == "find":
        if s.at(j) == "out":
            return None
        if s.at(j) == "your" and s.at(j + 1) == "way":
            return read_way_to(s, j + 2)
        if s.at(j) in ("me", "us") and j + 1 < n and toks[j + 1] not in BOUNDARY and toks[j + 1] not in TRAILING:
            j += 1
        elif s.at(j) in ("to", "for") and s.at(j + 1) in ("me", "us") and s.at(j + 2) in DETERMINERS:
            j += 2  # "find for me the cup"
    elif verb in ("locate", "spot", "detect"):
        pass
    words, e = read_noun_phrase(s, j)
    if not words and s.at(e) == "and" and s.at(e + 1) in ALL_VERBS:
        after = s.read_clause(s, e + 1)  # "locate and pick up the bottle": both verbs have the bottle
        if after is not None and after[0] and after[0][-1][1]:
            return [(FIND, after[0][-1][1], 0.0, 0.0, 0.0), *after[0]], after[1]
        return None
    if verb == "find" and words == ["me"]:
        target: str | None = "me"
    else:
        target = read_object(s, words)
    if target is None:
        return None
    out: list[Spec] = []
    if area is not None:
        out.append((NAVIGATE, area, 0.0, 0.0, 0.0))
    out.append((FIND, target, 0.0, 0.0, 0.0))
    return out, e


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
    if verb == "stand" and nxt not in ("still", "there", "by", "put", "here", "fast", "your", "right", "at", "in",
                                       "near", "beside", "inside"):
        return None
    if verb == "never" and nxt != "mind":
        return None
    if verb in ("stop", "halt") and nxt in ("me", "us", "him", "her", "them", "everyone", "everybody", "people"):
        return None  # "stop me if you've heard this one": someone else is stopped
    if verb == "forget" and nxt not in ("it", "that", "about", "everything", "this"):
        return None
    if verb == "cut" and nxt not in ("it", "that", "out"):
        return None
    if verb in ("hang", "hold") and nxt not in ("on", "it", "up", "still", "your", "position", "tight", "off",
                                                 "everything", "there"):
        return None
    if verb in ("end", "terminate", "kill", "interrupt") and nxt not in ("it", "that", "the", "this", "everything",
                                                                          "mission", "task", "now", "all"):
        return None
    if verb == "break" and nxt not in ("off",):
        return None
    if verb == "chill" and nxt not in ("out", ""):
        return None
    if verb == "e" and nxt != "stop":
        return None
    if verb == "emergency" and nxt not in ("stop", "halt", "brake", ""):
        return None
    if verb == "quit" and nxt not in ("it", "that", "moving", "move", "now", "", "please"):
        return None
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
    toks = s.toks
    verb = toks[i]
    j = i + 1
    nxt = s.at(j)
    if verb == "wave":
        if nxt in ("goodbye", "bye") or s.at(j + 1) in ("bye",):
            pass
        if nxt in ("the", "a") and s.at(j + 1) in ("flag", "wand", "banner", "sign"):
            return None
        return [(GESTURE, "wave", 0.0, 0.0, 0.0)], skip_gesture_tail(s, j)
    if verb in ("clap", "applaud"):
        return [(GESTURE, "clap", 0.0, 0.0, 0.0)], skip_gesture_tail(s, j)
    if verb in ("hug", "cuddle", "embrace"):
        return [(GESTURE, "hug", 0.0, 0.0, 0.0)], skip_gesture_tail(s, j)
    if verb == "say":  # "say hello with a wave"; saying alone is speech, not a gesture
        for k in range(j, min(j + 5, s.n)):
            if toks[k] == "with":
                m = k + 1 + (1 if s.at(k + 1) in DETERMINERS else 0)
                g = s.phrase_at(m, GESTURES_BY_FIRST)
                if g is not None:
                    return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], skip_gesture_tail(s, m + len(g))
            if toks[k] in BOUNDARY:
                break
        return None
    if verb == "greet":
        return [(GESTURE, "wave", 0.0, 0.0, 0.0)], skip_gesture_tail(s, j)
    if verb == "reject":
        return [(GESTURE, "reject", 0.0, 0.0, 0.0)], skip_gesture_tail(s, j)
    if verb == "shake":
        for k in range(j, min(j + 4, s.n)):
            if toks[k] in ("hand", "hands"):
                return [(GESTURE, "shake hand", 0.0, 0.0, 0.0)], skip_gesture_tail(s, k + 1)
            if toks[k] in BOUNDARY:
                break
        return None
    if verb in ("kiss", "blow"):
        k = j
        while k < s.n and toks[k] in ("me", "us", "a", "an", "the", "everyone", "them", "him", "her", "some", "big"):
            k += 1
        if verb == "kiss" or s.at(k) in ("kiss", "kisses"):
            name = "two hand kiss"
            tail = skip_gesture_tail(s, k + (1 if verb == "blow" else 0))
            words = toks[k:tail]
            if "left" in words:
                name = "left kiss"
            elif "right" in words:
                name = "right kiss"
            return [(GESTURE, name, 0.0, 0.0, 0.0)], tail
        return None
    if verb in ("raise", "put", "lift"):
        return _raise(s, i)
    if verb in ("lower", "drop", "relax", "release", "rest"):
        k = j + 1 if nxt in ("your", "both", "the", "my") else j
        if s.at(k) in BODY or (s.at(k) == "arm" or (s.at(k) in ("both",) and s.at(k + 1) in BODY)):
            return [(GESTURE, "release arm", 0.0, 0.0, 0.0)], skip_gesture_tail(s, k + 1)
        return None
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


def read_do(s: ParseState, i: int) -> Result:
    """do / make / perform / give / show / take / throw: a gesture ("do a high five", "show me a
    heart"), a turn ("make a u-turn", "do a 180", "take a left", "make a quarter turn"), a way
    ("make your way to the kitchen", "show me the way to the kitchen"), or for give/take/show the
    pick and navigation readings."""
    toks, n = s.toks, s.n
    verb = toks[i]
    j = i + 1
    if verb in FIND_NOUN_LEADS and (got := read_find_noun(s, i)) is not None:
        return got
    if verb == "take" and s.at(j) in ("me", "us", "him", "her", "them") and s.at(j + 1) in TO_WORDS:
        words, e = read_noun_phrase(s, j + 2)
        target = read_place(s, words)
        return ([(NAVIGATE, target, 0.0, 0.0, 0.0)], e) if target else None
    if verb == "show" and s.at(j) in ("me", "us", "them", "him", "her", "everyone"):
        k = j + 1
        if s.at(k) in TO_WORDS:
            return read_guide(s, i)  # "show me to the bathroom"
        if s.at(k) == "the" and s.at(k + 1) == "way" and s.at(k + 2) in TO_WORDS:
            words, e = read_noun_phrase(s, k + 3)
            target = read_place(s, words)
            return ([(NAVIGATE, target, 0.0, 0.0, 0.0)], e) if target else None
        if s.at(k) == "where" and k + 1 < n:
            words, e = read_noun_phrase(s, k + 1 + (1 if s.at(k + 1) in ("the",) else 0))
            if s.at(e) == "is" or s.at(e) == "are":
                target = read_place(s, words)
                return ([(NAVIGATE, target, 0.0, 0.0, 0.0)], e + 1) if target else None
            return None
    if s.at(j) in ("me", "us", "him", "her", "them", "everyone", "everybody", "the", "our", "you"):
        if s.at(j) in ("the", "our") and s.at(j + 1) in ("guests", "visitors", "kids", "children", "audience",
                                                         "crowd", "people", "group", "class", "team"):
            j += 2
        elif s.at(j) not in ("the", "our"):
            j += 1
    k = j
    while k < n and toks[k] in ("a", "an", "the", "your", "some", "another", "that", "this", "my", "nice", "little",
                                "quick", "cool", "famous", "special", "full", "lovely", "big"):
        if toks[k] in ("full",) or (toks[k] in ("big", "little") and s.at(k + 1) in GESTURE_NOUNS):
            break
        k += 1
    g = s.phrase_at(k, GESTURES_BY_FIRST)
    if g is not None and not (toks[k] in ("five",) and verb not in ("give",)):
        if toks[k] in ("hand",) and len(g) == 2 and verb != "give":
            pass
        return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], skip_gesture_tail(s, k + len(g))
    if verb in ("do", "make", "perform", "take", "try", "pull", "execute", "throw"):
        t = s.at(k)
        if t in ("u", "you") and s.at(k + 1) in ("turn", "turnaround"):
            return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + 2
        if t == "about" and s.at(k + 1) in ("face", "turn"):
            return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + 2
        if t in ("turnaround", "one80"):
            return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + 1
        if verb != "take" and (t == "180" or (t == "one" and s.at(k + 1) == "eighty")) and s.at(
                k + (1 if t == "180" else 2)) not in UNITS:
            return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + (1 if t == "180" else 2)
        if t in ("left", "right") and (s.at(k + 1) in ("turn", "") or s.at(k + 1) in BOUNDARY or s.at(
                k + 1) in TRAILING):
            return [(TURN, "", 0.0, 0.0, ROTATIONS[t] * math.radians(s.defaults.turn_deg))], k + (
                2 if s.at(k + 1) == "turn" else 1)
        if verb in ("make", "do") and (t == "way" or (t == "your" and s.at(k + 1) == "way")):
            return read_way_to(s, k + (1 if t == "way" else 2))
        if verb in ("take", "make", "do") and (t in STEP_WORDS or s.at(k + 1) in STEP_WORDS or s.at(
                k + 2) in STEP_WORDS):
            got = read_move(s, j, "step")
            at = next(m for m in range(k, k + 3) if toks[m] in STEP_WORDS)
            if got is None and toks[at] in ("step", "pace"):  # "take a small step to the left": one step that way
                got = read_move(s, at + 1, "step")
                if got is None and may_end(s, at + 1):  # "take a small step": forward, like "take a step"
                    got = [(MOVE, "", s.defaults.step_m, 0.0, 0.0)], at + 1
            return got
        # "make a quarter turn to the left", "do a full turn", "do a 360"
        k0 = j
        while k0 < n and toks[k0] in ("a", "an", "the"):
            if s.at(k0 + 1) in NUMBER_STARTS or s.at(k0 + 1)[:1].isdigit() or s.at(k0 + 1) in ("full", "complete",
                                                                                                  "whole", "turn"):
                break
            k0 += 1
        got = read_turn_terms(s, k0, verb)
        if got is not None and verb == "take" and not any(w in ROTATIONS or w in UNITS for w in toks[k0:got[1]]):
            got = None  # "take five": a break; "take a left", "take a quarter turn" say how they turn
        if got is not None and (got[0][0][0] != TURN_AROUND or s.at(k0) in AROUND):
            return got
        if verb in ("do", "make") and s.at(k) == "spin":
            return [(TURN, "", 0.0, 0.0, 2 * math.pi)], k + 1
        return read_pick(s, i) if verb == "take" else None
    if verb in ("give", "show"):
        if verb == "give" and s.at(i + 1) in ("me", "us") or verb == "give" and s.at(i + 1) in DETERMINERS:
            return read_pick(s, i)
        return None
    return None
