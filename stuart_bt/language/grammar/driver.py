"""The command grammar: the text after the wake phrase -> an ordered list of TaskIntents.

Deterministic and rule-based on purpose: a robot must do the same thing for the same words, a
misheard command must fail visibly rather than be guessed, and a parse must cost microseconds
(the budget is 50 µs at p99, see bench/parse.py). Shape of the grammar::

    command   := clause (connector clause)*
    connector := "," | "and" | "then" | "and then" | "after that" | ";" | "." | "to" (+verb) | ...
    clause    := polite* verb-phrase trailing*  |  ellipsis
    polite    := "please" | "could you" | "would you mind" | "i want you to" | "let's" | ...
    ellipsis  := noun-phrase (same action as the clause before: "go to the kitchen and the bathroom")
               | direction/quantity ("turn left, then right"; "forward two metres")
               | gesture phrase ("high five!")

Each verb family has a small recursive-descent reader (motion, turn, pick, find, gesture,
stop, and the light verbs do/make/give/show/take that lead into the others). Readers consume
tokens from a position and return intents plus the position after them; anything they do not
understand ends the clause.

What is *not* a command: a sentence that opens like a question or a statement ("what can you
pick up?", "do you like the kitchen?", "I went to the kitchen", "the kitchen is nice") is
conversation to its end (the next "." "?" "!" or ";"), even if a command-like clause follows an
"and". Polite questions are commands ("could you go to the kitchen?", "can you wave?"), except
questions about wishes ("would you like to go to the kitchen?"). Negated commands ("don't go to
the kitchen") give nothing, except "don't move", which is a stop.

The grammar reports targets as spoken (lower case, determiners removed): "the charging dock"
-> "charging dock". Mapping them to marker names and object labels is
:mod:`stuart_bt.language.resolve`'s job, so parsing never needs a map.
"""

from __future__ import annotations

from collections.abc import Iterable

from ..intents import FIND, NAVIGATE, PICK, STOP, TaskIntent
from .clauses import opens_conversation, read_clause, read_connector, read_topic
from .lexicon import ALL_VERBS, BOUNDARY, COPULA, CORRECTIONS_BY_FIRST, HARD_STOPS, MODALS, NP_STOP, PAST, SUBORDINATORS
from .nouns import read_arrival
from .state import Defaults, ParseState, may_end, skip_rest
from .tokens import Tokens, tokenize


class Grammar:
    """Parses command text (what follows the wake phrase) into TaskIntents.

    ``vocatives`` are extra words that end a noun phrase (the robot's name: "go to the kitchen,
    Stuart" must not look for a "kitchen stuart"); ``defaults`` the amounts used when none is
    said."""

    def __init__(self, *, defaults: Defaults | None = None, vocatives: Iterable[str] = ()) -> None:
        self.defaults = defaults or Defaults()
        self.stop_words = NP_STOP | frozenset(v.lower() for v in vocatives)

    def parse(self, text: str) -> list[TaskIntent]:
        """The intents in ``text``, in the order they are to be done; [] when it holds no command."""
        tokens = tokenize(text)
        out = self.parse_tokens(text, tokens)
        if not out and "." in tokens.toks:  # "go. to. the kitchen.": a recogniser's stray periods
            out = self.parse_tokens(text, tokens.without("."))
        return out

    def parse_tokens(self, text: str, tokens: Tokens) -> list[TaskIntent]:
        """Like :meth:`parse` on the tokens :func:`tokenize` made of ``text``."""
        toks = list(tokens.toks)  # a past verb after "once you've" may be replaced by its base form
        s = ParseState(toks, len(toks), self.defaults, self.stop_words, read_clause)
        n = s.n
        out: list[TaskIntent] = []
        i = 0
        dead = False  # the sentence opened as a question or statement
        reorder_at: int | None = None  # "X but first Y": Y's intents go before X's
        correct_at: int | None = None  # "X, no, Y": Y's intents replace X's
        clause_end = -1  # where the last clause ended: "X after you Y" has no connector between
        hold = False  # "before you Y, X": Y's intents wait ...
        held: list[TaskIntent] = []  # ... here until X's are in
        while i < n:
            t = toks[i]
            if t in HARD_STOPS:
                dead = False
                i += 1
                continue
            if out and not dead and t in CORRECTIONS_BY_FIRST and (c := s.phrase_at(i, CORRECTIONS_BY_FIRST)):
                correct_at = len(out) - _last_clause_len(out)  # "go to the kitchen, no, the bathroom"
                i += len(c)
                continue
            con = read_connector(s, i)
            if con is not None:
                kind, i = con
                if kind == "or":  # "the kitchen or the bathroom": a choice is not a plan
                    while i < n and toks[i] not in HARD_STOPS:
                        i += 1
                elif kind == "reorder" and out:
                    reorder_at = len(out) - _last_clause_len(out)
                continue
            if dead and toks[i - 1] == "," and (t == "please" or (t in MODALS and s.at(i + 1) == "you") or (
                    t in ("stop", "halt", "freeze") and may_end(s, i + 1))):
                dead = False  # "I lost my keys, can you help me find them?", "is enough, stop": said to the robot
            if dead:
                i += 1
                continue
            subordinate = False
            attached = bool(out) and i == clause_end
            if t == "before" and i + 1 < n and (toks[i + 1] in ("you", "u") or toks[i + 1] in ALL_VERBS):
                i += 2 if toks[i + 1] in ("you", "u") else 1
                hold = not attached  # "before you go, wave": the wave first; "wave before you go": in order
                if i >= n:
                    break
            if t == "as" and s.at(i + 1) == "soon" and s.at(i + 2) == "as" and s.at(i + 3) in (
                    "you", "youve", "youre", "u"):
                i += 2
                t = "once"  # "as soon as you get to the kitchen": like "once you ..."
            if t in SUBORDINATORS and i + 1 < n and (toks[i + 1] in ("you", "youve", "youre", "u") or (
                    t == "after" and toks[i + 1] in ALL_VERBS)):
                # "when you find it, pick it up": the clause says what happens first; it is kept
                # unless it repeats the intent just before ("look for the bottle and when you
                # find it ...")
                perfect = toks[i + 1] == "youve" or t == "once"
                i += 2 if toks[i + 1] in ("you", "youve", "youre", "u") else 1
                subordinate = True
                if t == "after" and attached:  # "go to the kitchen after you wave": the wave first
                    reorder_at = len(out) - _last_clause_len(out)
                if i < n and toks[i] == "have" and toks[i - 1] == "you":
                    i += 1  # "once you have picked up ..."
                    perfect = True
                if i >= n:
                    break
                if perfect and toks[i] in PAST:
                    toks[i] = PAST[toks[i]]  # "when you've found it": the verb ("when you went": a story)
            start = i
            got = read_arrival(s, i) if subordinate and t != "if" else None
            if got is None:
                s.subordinate = subordinate
                got = read_clause(s, i)
                s.subordinate = False
            if got is None:
                correct_at = reorder_at = None  # "go to the kitchen. no need to hurry": nothing to correct with
                hold = False
                if subordinate and t != "if":  # "when you are ready go to the kitchen": a time, no question
                    i = skip_rest(s, i + 1)
                    s.first = False
                    continue
                if opens_conversation(s, i) and not read_topic(s, i):
                    dead = True
                i += 1
                while i < n and toks[i] not in BOUNDARY:
                    i += 1
                s.first = False
                continue
            specs, j = got
            j = max(j, i + 1)
            if not specs:  # "grab the cup and hand it to me": the handing over adds nothing
                s.first = False
                i = clause_end = skip_rest(s, j)
                continue
            if s.at(j) in COPULA and not subordinate:  # "going to the kitchen was fun": a subject, so a statement
                dead = True
                correct_at = reorder_at = None
                hold = False
                i = j
                continue
            if subordinate and out and [(it.action, it.target) for it in out[-len(specs):]] == [
                    (a, tg) for a, tg, *_ in specs]:
                s.first = False
                i = skip_rest(s, j)
                continue
            a, b = tokens.span(start, min(j, n) - 1)
            raw = text[a:b]
            made = [TaskIntent(a, tg, x, y, yaw, raw) for a, tg, x, y, yaw in specs]
            if hold:
                held, hold = made, False
            elif correct_at is not None:
                out[correct_at:] = made
                correct_at = None
            elif reorder_at is not None:
                out[reorder_at:reorder_at] = made
                reorder_at = None
            else:
                out.extend(made)
            if held and made is not held:
                out.extend(held)
                held = []
            for act, tg, *_ in specs:
                if act in (PICK, FIND) and tg not in ("me", "it"):
                    s.last_object = tg
                elif act == NAVIGATE:
                    s.last_place = tg
            s.last_action = specs[-1][0]
            s.first = False
            i = clause_end = skip_rest(s, j)
        return _dedupe_stops(out + held)


def _last_clause_len(out: list[TaskIntent]) -> int:
    """How many of the last intents came from the last clause (same raw_text)."""
    if not out:
        return 0
    raw = out[-1].raw_text
    k = 0
    for it in reversed(out):
        if it.raw_text != raw:
            break
        k += 1
    return k


def _dedupe_stops(out: list[TaskIntent]) -> list[TaskIntent]:
    """ "stop, stop, stop!" is one stop."""
    if len(out) < 2:
        return out
    kept = [out[0]]
    for it in out[1:]:
        if it.action == STOP and kept[-1].action == STOP:
            continue
        kept.append(it)
    return kept

_DEFAULT = Grammar()


def parse_command(text: str) -> list[TaskIntent]:
    """The intents in command ``text`` with the default grammar (see :class:`Grammar`)."""
    return _DEFAULT.parse(text)
