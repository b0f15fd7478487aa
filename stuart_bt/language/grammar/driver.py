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

import math
from collections.abc import Iterable
from dataclasses import replace
from typing import NamedTuple

from ..intents import FIND, GESTURE, MOVE, NAVIGATE, PICK, STOP, TURN, TURN_AROUND, TaskIntent
from ..numbers import word_value
from .clauses import FAMILY_READERS, called_at, opens_conversation, read_clause, read_connector, read_topic
from .forms import CHECK, SOFTENED, question_tags, retraction_at, takes_back_at
from .lexicon import (
    ALL_VERBS,
    AUX,
    BODY_PARTS,
    BOUNDARY,
    CONDITIONS,
    COPULA,
    CORRECTIONS_BY_FIRST,
    DETERMINERS,
    DIRECTIONS,
    HARD_STOPS,
    LIST_LABELS,
    MODALS,
    NP_STOP,
    PAST,
    PAUSE_SPANS_BY_FIRST,
    PLAIN_STOPS,
    POLITE_BY_FIRST,
    REPEATS_BY_FIRST,
    RETRACTIONS_BY_FIRST,
    ROTATIONS,
    SIGN_OFFS_BY_FIRST,
    STEP_ORDINALS,
    STOP_PHRASES_BY_FIRST,
    SUBJECT_AND_BE,
    SUBJECT_AND_IS,
    SUBJECT_AND_MODAL,
    SUBORDINATORS,
    THANKS_AHEAD_FEELINGS,
    TIME_OPENERS,
    TIMES,
    TRAILING,
    WH,
)
from .motion import UNTIL_VERBS
from .nouns import read_arrival
from .state import Defaults, ParseState, Spec, may_end, skip_rest, starts_a_stop, stop_phrase_end
from .stopping import says_why_at
from .tokens import Tokens, tokenize


class Grammar:
    """Parses command text (what follows the wake phrase) into TaskIntents.

    ``vocatives`` are extra words that end a noun phrase (the robot's name: "go to the kitchen,
    Stuart" must not look for a "kitchen stuart"); ``defaults`` the amounts used when none is
    said."""

    def __init__(self, *, defaults: Defaults | None = None, vocatives: Iterable[str] = ()) -> None:
        self.defaults = defaults or Defaults()
        self.vocatives = frozenset(v.lower() for v in vocatives)
        self.stop_words = NP_STOP | self.vocatives

    def parse(self, text: str) -> list[TaskIntent]:
        """The intents in ``text``, in the order they are to be done; [] when it holds no command."""
        return self.read(text).intents

    def read(self, text: str) -> Reading:
        """The intents in ``text`` and which words they came from (see :class:`Reading`)."""
        tokens = tokenize(text)
        reading = self.read_tokens(text, tokens)
        if not reading.intents and USED not in reading.marks and "." in tokens.toks:
            reading = self.read_tokens(text, tokens.without("."))  # "go. to. the kitchen.": stray periods
        if reading.unread and any(i.action == STOP for i in self.read(reading.unread).intents):
            stop = TaskIntent(STOP, "", 0.0, 0.0, 0.0, "stop")  # a stop wins, however long the utterance
            return Reading([stop], reading.tokens, reading.marks, reading.unread)
        return reading

    def parse_tokens(self, text: str, tokens: Tokens) -> list[TaskIntent]:
        """Like :meth:`parse` on the tokens :func:`tokenize` made of ``text``."""
        return self.read_tokens(text, tokens).intents

    def read_tokens(self, text: str, tokens: Tokens) -> Reading:
        """Like :meth:`read` on the tokens :func:`tokenize` made of ``text``."""
        reader = _CommandReader(self, text, tokens)
        intents = reader.read()
        return Reading(intents, tuple(reader.toks), bytes(reader.marks), tokens.unread())


class Reading(NamedTuple):
    """A command read: its intents, the tokens, what each token was to the reader (``USED``: an
    intent came from it; ``TALK``: part of a question or statement; 0: read by no clause) and the
    text past MAX_TOKENS that was not read at all. The marks are what coverage is made of."""

    intents: list[TaskIntent]
    tokens: tuple[str, ...] = ()
    marks: bytes = b""
    unread: str = ""


class _CommandReader:
    """One command read left to right: clauses between connectors, with what the words between
    them ask for (a correction, a reordering, a clause held until the next one is in)."""

    __slots__ = ("after_subordinate", "clause_end", "conditional", "correct_at", "dead", "held", "hold", "i", "marks",
                 "out", "reorder_at", "retract_at", "s", "sentence_at", "tagged", "taken_back", "text", "tokens",
                 "toks")

    def __init__(self, grammar: Grammar, text: str, tokens: Tokens) -> None:
        self.text, self.tokens = text, tokens
        self.toks = list(tokens.toks)  # a past verb after "once you've" may be replaced by its base form
        self.s = ParseState(self.toks, len(self.toks), grammar.defaults, grammar.stop_words, read_clause,
                            FAMILY_READERS, contracted=tokens.contracted, vocatives=grammar.vocatives)
        self.out: list[TaskIntent] = []
        self.i = 0
        self.dead = False  # the sentence opened as a question or statement
        self.reorder_at: int | None = None  # "X but first Y": Y's intents go before X's
        self.correct_at: int | None = None  # "X, no, Y": Y's intents replace X's
        self.clause_end = -1  # where the last clause ended: "X after you Y" has no connector between
        self.hold = False  # "before you Y, X": Y's intents wait ...
        self.held: list[TaskIntent] = []  # ... here until X's are in
        self.marks = bytearray(len(self.toks))  # per token: USED, TALK, or 0 (read by no clause)
        self.tagged = question_tags(self.toks, tokens.gerunds)  # sentences ending in a question tag (None: no tag)
        self.retract_at: int | None = None  # "go to the kitchen, no.": a correction nothing replaced takes back
        self.conditional = False  # an "if" clause came before a command: the robot cannot check it
        self.after_subordinate = False  # the clause before was "when you get there": a stop after it is a step
        self.taken_back = False  # everything asked was just taken back: "..., never mind, forget it" says it again
        self.sentence_at = 0  # where this sentence's intents begin: "X and Y, but first Z" puts Z before both

    def read(self) -> list[TaskIntent]:
        """The intents, in order; ``marks`` then says which tokens they came from."""
        n = self.s.n
        tagged = self.tagged
        while self.i < n:
            if tagged is not None and tagged[self.i]:
                self.marks[self.i] = ASKED if tagged[self.i] == CHECK else USED if tagged[self.i] == SOFTENED else TALK
                self.i += 1
                continue
            if self._between_clauses() or self._in_conversation():
                continue
            opening = self._subordinate_opening()
            if opening is None:
                break
            self._clause(*opening)
        if self.retract_at is not None:
            del self.out[self.retract_at:]
        return _dedupe_stops(self.out + self.held)

    def _between_clauses(self) -> bool:
        """A sentence end, a correction ("no, ..."), or a connector at ``i``: consumed."""
        s, toks, t = self.s, self.toks, self.toks[self.i]
        if t in HARD_STOPS:
            self.dead = self.conditional = False
            self.i += 1
            self.sentence_at = len(self.out)
            return True
        if self._called_again():
            return True
        if t in INTERJECTIONS and (self.out or self.held) and not self.dead and self._before_a_correction():
            return True
        if t == "no" and s.at(self.i + 1) in STOP_PHRASES_BY_FIRST and (
                s.phrase_at(self.i + 1, STOP_PHRASES_BY_FIRST) is not None):
            self._mark(self.i, self.i + 1, USED)  # "no no no freeze": said before a stop, not a negation
            self.i += 1
            return True
        if t in LIST_LABELS and word_value(s.at(self.i + 1)) is not None and s.at(self.i + 2) == ",":
            self._mark(self.i, self.i + 3, USED)  # "item two, locate the cup": a label, not a second place
            self.i += 3
            return True
        signed = s.phrase_at(self.i, SIGN_OFFS_BY_FIRST) if t in SIGN_OFFS_BY_FIRST and self.out else None
        if signed and may_end(s, self.i + len(signed)):  # "move forward, come on": said, not asked
            self._mark(self.i, self.i + len(signed), USED)
            self.i += len(signed)
            return True
        taken_back = retraction_at(s, self.i) if t in RETRACTIONS_BY_FIRST and (
            self.out or self.held or self.taken_back) and not self.dead else 0
        if taken_back:  # "go to the kitchen, just kidding": nothing asked before it stands
            return self._take_back(taken_back)
        c = s.phrase_at(self.i, CORRECTIONS_BY_FIRST) if self.out and not self.dead else None
        if c:
            self.correct_at = len(self.out) - _last_clause_len(self.out)  # "go to the kitchen, no, the bathroom"
            self._mark(self.i, self.i + len(c), USED)
            self.i += len(c)
            if c in RETRACTING and (self.i >= s.n or toks[self.i] in BOUNDARY):
                self.retract_at = self.correct_at  # "no." alone: unless a clause replaces it, it takes back
            return True
        con = read_connector(s, self.i)
        if con is None:
            return False
        kind, end = con
        self._mark(self.i, end if toks[self.i] in STEP_ORDINALS else self.i, USED)  # ("second pick it up")
        self.i = end
        if kind == "or":  # "the kitchen or the bathroom": a choice is not a plan
            offered = self.i
            while self.i < s.n and toks[self.i] not in HARD_STOPS:
                self.i += 1
            if self.out:  # "turn left, or maybe right": which one is meant? every word of the choice is unsure
                self._mark(offered, self.i, CHOICE)
        elif kind == "reorder" and self.out:
            self.reorder_at = min(self.sentence_at, len(self.out))  # "go there and wave, but first turn around"
        return True

    def _called_again(self) -> bool:
        """The robot called at ``i`` by its name again ("..., actually Stuart stop right there") or,
        opening a sentence, by a term of address ("Stuart mate pick up the apple"): consumed."""
        if self.dead:
            return False
        s, i = self.s, self.i
        called = 1 if self.toks[i] in s.vocatives else called_at(s, i) if self._opens_sentence(i) else 0
        self._mark(i, i + called, USED)
        self.i += called
        return called > 0

    def _corrects_after(self, i: int) -> bool:
        """A correction or a retraction at ``i``, after a comma or more interjections there
        ("actually, don't worry", "oh wait, forget it")."""
        s = self.s
        while s.at(i) == "," or s.at(i) in INTERJECTIONS:
            i += 1
        return i < s.n and bool(retraction_at(s, i) or s.phrase_at(i, CORRECTIONS_BY_FIRST))

    def _before_a_correction(self) -> bool:
        """An interjection at ``i`` before a correction ("actually, scratch that") or before the
        thing or place said instead ("go to the kitchen? oh, actually, the bathroom", "wait, not
        the bottle, the cup"): consumed, and the last clause marked to be replaced."""
        if self._corrects_after(self.i + 1):
            self._mark(self.i, self.i + 1, USED)
            self.i += 1
            return True
        instead = self._said_instead(self.i)
        if not instead:
            return False
        self.correct_at = len(self.out) - _last_clause_len(self.out)
        self._mark(self.i, instead, USED)
        self.i = instead
        return True

    def _said_instead(self, i: int) -> int:
        """Where a thing or place said instead of the last one starts, after interjections at ``i``
        and perhaps "not" and the one meant not ("oh, actually, the bathroom", "wait, not the
        bottle, the cup"): a phrase with no verb to the end of its sentence; 0 when none is."""
        s = self.s
        while s.at(i) == "," or s.at(i) in INTERJECTIONS:
            i += 1
        if s.at(i) == "not":
            k = i + 1
            while k < s.n and s.toks[k] not in BOUNDARY:
                k += 1
            if s.at(k) != ",":
                return 0
            i = k + 1
        if s.at(i) not in DETERMINERS:
            return 0
        k = i + 1
        while k < s.n and s.toks[k] not in HARD_STOPS:
            if s.toks[k] in ALL_VERBS or s.toks[k] in BOUNDARY:
                return 0
            k += 1
        return i if k > i + 1 else 0

    def _take_back(self, length: int) -> bool:
        """The retraction of ``length`` words at ``i`` takes back everything asked before it: consumed."""
        self._forget_all()
        self.taken_back = True
        self._mark(self.i, self.i + length, USED)
        self.i += length
        return True

    def _forget_all(self) -> None:
        self.s.last_action = ""  # nothing for an ellipsis to continue ("..., I'm joking, obviously")
        self.out.clear()
        self.held.clear()
        self.correct_at = self.reorder_at = self.retract_at = None
        self.hold = False

    def _in_conversation(self) -> bool:
        """Inside a question or a statement: skip its words (a word said to the robot after a
        comma ends it: "I lost my keys, can you help me find them?", "that's enough, stop")."""
        if not self.dead:
            return False
        s, i, t = self.s, self.i, self.toks[self.i]
        before = self.toks[i - 1]
        if (before == "," and (t == "please" or (t in MODALS and s.at(i + 1) == "you"))) or _stop_said_at(s, i):
            self.dead = False  # "I know I told you to go there, but stop right now": a stop always wins
            return False
        taken_back = retraction_at(s, i) if t in RETRACTIONS_BY_FIRST and (self.out or self.held) else 0
        if taken_back and may_end(s, i + taken_back):  # "fetch me a cup and a biscuit ha ha only joking":
            return self._take_back(taken_back)  # taken back at the end of the talk that followed the command
        self.marks[i] = TALK
        self.i += 1
        return True

    def _subordinate_opening(self) -> tuple[str, bool] | None:
        """Past "before you", "as soon as you", "when/once/after you('ve)": (the opening word,
        whether a subordinate clause follows); ``None`` when the text ends there."""
        s, toks, n = self.s, self.toks, self.s.n
        t = toks[self.i]
        attached = bool(self.out) and self.i == self.clause_end
        if t == "before" and self.i + 1 < n and (toks[self.i + 1] in ("you", "u") or toks[self.i + 1] in ALL_VERBS):
            self.i += 2 if toks[self.i + 1] in ("you", "u") else 1
            self.hold = not attached  # "before you go, wave": the wave first; "wave before you go": in order
            if self.i >= n:
                return None
        if t == "as" and s.at(self.i + 1) == "soon" and s.at(self.i + 2) == "as" and s.at(self.i + 3) in (
                "you", "youve", "youre", "u"):
            self.i += 2
            t = "once"  # "as soon as you get to the kitchen": like "once you ..."
        if t == "if" and (s.at(self.i + 1) == "you" and s.at(self.i + 2) in MODALS or s.phrase_at(
                self.i, POLITE_BY_FIRST) is not None):
            return t, False  # "if you could go to the kitchen", "if you don't mind, ...": polite, no condition
        if not (t in SUBORDINATORS and self.i + 1 < n and (toks[self.i + 1] in ("you", "youve", "youre", "u") or (
                t == "after" and toks[self.i + 1] in ALL_VERBS))):
            return t, False
        # "when you find it, pick it up": the clause says what happens first; it is kept unless it
        # repeats the intent just before ("look for the bottle and when you find it ...")
        perfect = toks[self.i + 1] == "youve" or t == "once"
        self.i += 2 if toks[self.i + 1] in ("you", "youve", "youre", "u") else 1
        if t in ("after", "when", "once") and attached:  # "go to the kitchen after you wave": the wave first;
            # "turn left once you get to the kitchen", "wave when you arrive": the arrival first
            self.reorder_at = len(self.out) - _last_clause_len(self.out)
        if self.i < n and toks[self.i] == "have" and toks[self.i - 1] == "you":
            self.i += 1  # "once you have picked up ..."
            perfect = True
        if self.i >= n:
            return None
        if perfect and toks[self.i] in PAST:
            toks[self.i] = PAST[toks[self.i]]  # "when you've found it": the verb ("when you went": a story)
        return t, True

    def _clause(self, t: str, subordinate: bool) -> None:
        """Read the clause at ``i`` and put its intents where the words around it say."""
        s, start = self.s, self.i
        if subordinate and t == "if":  # "if you go to the kitchen ...": a condition, never a command itself
            self.conditional = True
            self._no_clause(t, False)
            self._mark(start, self.i, TALK)
            return
        if not subordinate and (start in self.tokens.gerunds or (t, s.at(start + 1)) in TIME_OPENERS) and (
                self._opens_sentence(start)):
            self.dead = True  # "walking to the kitchen takes ages": the ing-form is the subject of a statement
            self._no_clause(t, False)
            self._mark(start, self.i, TALK)
            return
        if not subordinate and t in REPEATS_BY_FIRST and self._repeated(start):
            return
        got = read_arrival(s, start) if subordinate else None
        if got is None:
            s.subordinate = subordinate
            got = read_clause(s, start)
            s.subordinate = False
        if got is None:
            self._no_clause(t, subordinate)
            return
        specs, j = got
        j = max(j, start + 1)
        if not specs:  # "grab the cup and hand it to me": the handing over adds nothing
            self._mark(start, j, USED)
            s.first = False
            self.i = self.clause_end = skip_rest(s, j)
            return
        if self.conditional and not all(sp[0] == STOP for sp in specs):
            self._mark(start, j, TALK)  # "if you see the kids, wave at them": the robot cannot wait for a condition
            self.i = self.clause_end = skip_rest(s, j)  # (a stop needs none: "if you're about to fall, stop")
            s.first = False
            return
        if s.at(j) in COPULA and not subordinate and not (s.at(j) == "were" and j + 1 in self.tokens.gerunds) and not (
                specs[-1][0] == STOP and says_why_at(s, j)):  # ("stop were filming": "we're", as a recogniser writes)
            # "going to the kitchen was fun": a subject, so a statement ("... we're heading home": a remark)
            self.dead, self.correct_at, self.reorder_at, self.hold = True, None, None, False
            self._mark(start, j, TALK)
            self.i = j
            return
        if subordinate and self.out and {(a, tg) for a, tg, *_ in specs} <= {(it.action, it.target) for it in self.out}:
            self._mark(start, j, USED)
            s.first = False
            self.i = skip_rest(s, j)
            return
        if specs[0][0] == STOP and not subordinate and all(sp[0] == STOP for sp in specs) and (
                self._interjected(start) or s.at(start + 1) in PLAIN_STOPS or self.toks[start] in _CHANGE_OF_MIND
                or not _URGENT.isdisjoint(self.toks[start:j]) or says_why_at(s, j)):
            self._forget_all()  # "..., oh no, stop!", "... and stop stop stop": said over a plan, it cancels it
        self.after_subordinate = subordinate
        restated = self._restated(start, j, specs)
        if restated is not None:  # "turn left, ninety degrees": how far, not a second turn
            self.out[-1] = restated
            self._mark(start, j, USED)
            self.i = self.clause_end = skip_rest(s, j)
            return
        if start > 0 and self.toks[start - 1] == "but" and self.out and _first_after(self.toks, j):
            self.reorder_at = min(self.sentence_at, len(self.out))  # "..., but turn around first"
        a, b = self.tokens.span(start, min(j, s.n) - 1)
        self._place([TaskIntent(act, tg, x, y, yaw, self.text[a:b]) for act, tg, x, y, yaw in specs])
        self._mark_read(start, j)
        self._remember(specs)
        # "when you get to station six put your hands up": the main clause follows with no pause
        self.i = self.clause_end = j if subordinate and s.at(j) in ALL_VERBS else skip_rest(s, j)
        self._mark_after(start, j, specs)

    def _mark_read(self, start: int, end: int) -> None:
        """The words of a clause an intent came from are used, except a condition in them ("...
        until the professor arrives") and a gait the robot lacks ("crawl to the entrance"): the
        robot asks about those."""
        self._mark(start, _condition_at(self.toks, start, end), USED)
        if not _GAITS_IT_LACKS.isdisjoint(self.toks[start:end]):
            for k in range(start, end):
                if self.toks[k] in _GAITS_IT_LACKS:
                    self.marks[k] = 0

    def _mark_after(self, start: int, j: int, specs: list[Spec]) -> None:
        """What the words between a clause's end ``j`` and the next clause were: a reason, whom it
        is for, a statement run on, or which thing was meant."""
        s = self.s
        why = _reason_at(self.toks, j, self.i)
        if all(sp[0] in _DONE_FOR_SOMEONE for sp in specs):  # not "look for the cup": its thing
            why = min(why, _for_whom_at(self.toks, start + 1, self.i))
        if why == self.i > j and (self._remark_at(j) or specs[-1][0] == STOP and says_why_at(s, j)):
            self.dead, self.i = True, j  # "pick up the cup the kids want to see it": a statement run on,
            return  # no pause written; talk to the end of its sentence
        if why < self.i:  # "turn around so we can see your back", "... because I said so": said, not asked
            self._mark(why, self.i, TALK)
        elif s.at(j) == "for" and s.at(j + 1) in _WHOM and _only_who(self.toks[j + 2:self.i]):
            self._mark(j, self.i, USED)  # "find the bottle for us old timers": who "us" are
        if specs[-1][1] and s.at(j) in QUALIFIERS and _says_which(self.toks[j:self.i]):
            self._mark(j, self.i, USED)  # "the apple on the counter": which apple, not a new step

    def _repeated(self, start: int) -> bool:
        """ "..., and again", "one more time", "do it again", "do the same to the left": the step
        just asked for once more (a move or turn to the side said, or the other way), placed as a
        clause of its own; False when no repeat is said at ``start`` or there is nothing to repeat."""
        s = self.s
        said = s.phrase_at(start, REPEATS_BY_FIRST)
        done = self.held or self.out
        if said is None or not done:
            return False
        j = start + len(said)
        again, j = _mirrored(s, j, done[-1])
        if again is None or not may_end(s, j):
            return False
        self._mark(start, j, USED)
        self._place([again])
        s.first = False
        self.i = self.clause_end = skip_rest(s, j)
        return True

    def _restated(self, start: int, end: int, specs: list[Spec]) -> TaskIntent | None:
        """ "turn left, ninety degrees", "forward, a couple of metres": an amount alone after a
        pause says how far the move or turn just asked for goes, when that one said no amount.
        The last intent with that amount (its direction kept), else None (a direction said again,
        "then", or an amount said before make it another step: "turn left, then ninety degrees")."""
        if len(specs) != 1 or not self.out:
            return None
        act, _, x, y, yaw = specs[0]
        last = self.out[-1]
        if act == TURN_AROUND == last.action and self.toks[start] == "face":
            return last  # "spin round and face the other way": where the turn ends, not a second turn
        if self.toks[start - 1] != ",":
            return None
        if act != last.action or act not in (MOVE, TURN) or _names_a_way(self.toks[start:end]):
            return None
        if _names_an_amount(tokenize(last.raw_text).toks):
            return None
        if act == TURN:
            return replace(last, yaw=math.copysign(abs(yaw), last.yaw))
        scale = math.hypot(x, y) / (math.hypot(last.x, last.y) or 1.0)
        return replace(last, x=last.x * scale, y=last.y * scale)

    def _remark_at(self, j: int) -> bool:
        """Whether the words at ``j``, right after a command with no connector between, are a
        statement of their own: they open as one (a subject: "the kids", "we", "Jess is") and
        have a verb before the next connector ("the kids want ...", "we are late")."""
        s = self.s
        if (j in self.tokens.contracted or self.toks[j] in SUBJECT_AND_IS or self.toks[j] in SUBJECT_AND_MODAL) and (
                s.at(j + 1) not in BOUNDARY) or (
                self.toks[j] in DETERMINERS and j + 1 in self.tokens.contracted) or (
                self.toks[j] in SUBJECT_AND_BE and j + 1 in self.tokens.gerunds):
            return True  # "find the apple it's my lunch" ("its", as recognisers write it), "your battery's low"
        return self.toks[j] not in _NO_SUBJECT and _statement_after(s, j, _REMARK_VERBS)

    def _opens_sentence(self, i: int) -> bool:
        """Whether ``i`` starts a sentence: the start, after . ! ? ;, or after a comma before any command."""
        before = self.toks[i - 1] if i else "."
        return before in HARD_STOPS or (before == "," and not self.out and not self.held)

    def _interjected(self, i: int) -> bool:
        """Whether the clause at ``i`` interrupts what was asked before it rather than follows it:
        it comes after a pause or a correction, not after "then" or "and", nor after "when you get
        there" (a stop is then where to stop)."""
        if not (self.out or self.held) or self.after_subordinate:
            return False
        before = self.toks[i - 1] if i else ""
        return before not in SEQUENCERS

    def _no_clause(self, t: str, subordinate: bool) -> None:
        """No command at ``i``: skip to the next connector; a question or a statement makes the
        rest of its sentence conversation."""
        s, toks = self.s, self.toks
        self.correct_at = self.reorder_at = None  # "go to the kitchen. no need to hurry": nothing to correct with
        self.hold = False
        if subordinate and t != "if":  # "when you are ready go to the kitchen": a time, no question
            self.i = skip_rest(s, self.i + 1)
            s.first = False
            return
        start = self.i
        opens = opens_conversation(s, start)
        topic = opens and read_topic(s, start)
        if opens and not topic:
            self.dead = True
        self.i += 1
        while self.i < s.n and toks[self.i] not in BOUNDARY and not (
                (_stop_said_at(s, self.i) if self.dead else starts_a_stop(s, self.i)) or takes_back_at(s, self.i)):
            self.i += 1  # "you're late so just stop": the talk ends where a stop is said; "do a dance stop" too
        if self.dead:
            self._mark(start, self.i, TALK)
        elif topic:  # "the kitchen, go there": what "there" will mean
            self._mark(start, self.i, USED)
        s.first = False

    def _mark(self, start: int, end: int, how: int) -> None:
        end = min(end, len(self.marks))
        if end > start:
            self.marks[start:end] = _RUNS[how][:end - start]

    def _place(self, made: list[TaskIntent]) -> None:
        """Held back, replacing a corrected clause, before a reordered one, or at the end."""
        if self.hold:
            self.held, self.hold = made, False
        elif self.correct_at is not None:
            self.out[self.correct_at:] = made
            self.correct_at = None
        elif self.reorder_at is not None:
            self.out[self.reorder_at:self.reorder_at] = made
            self.reorder_at = None
        else:
            self.out.extend(made)
        self.retract_at = None
        self.taken_back = False
        if self.held and made is not self.held:
            self.out.extend(self.held)
            self.held = []

    def _remember(self, specs: list[Spec]) -> None:
        """What "it", "there" and an ellipsis refer to from now on."""
        s = self.s
        for act, tg, *_ in specs:
            if act in (PICK, FIND) and tg not in ("me", "it"):
                s.last_object = tg
            elif act == NAVIGATE:
                s.last_place = tg
        s.last_action = specs[-1][0]
        s.first = False


# prepositions that start a phrase saying which thing or place is meant ("the cup on the table",
# "a bottle of water", "the kitchen by the door"), when they follow a target
QUALIFIERS = frozenset({"on", "in", "at", "of", "from", "near", "by", "with", "under", "beside", "behind", "next",
                        "inside", "over", "underneath", "above", "below", "opposite"})

def _stop_said_at(s: ParseState, i: int) -> bool:
    """Whether a stop is said to the robot at ``i`` in the middle of talk: a stop whose clause
    ends after it, after a pause, "but" or "so", perhaps with softening words between ("..., but
    stop right now", "you're late so just stop", "..., actually freeze a moment", "..., but please
    stop moving for now", "..., but hold it right there")."""
    if i == 0:
        return False
    if s.toks[i] in PLAIN_STOPS and (s.toks[i - 1] == "no" or s.at(i + 1) == s.toks[i]) or (
            s.toks[i] == "no" and s.at(i + 1) in PLAIN_STOPS):
        return True  # "... and then maybe the reading room no stop stop there's a kid in front of you"
    b = i - 1
    while b > 0 and s.toks[b] in _BEFORE_A_STOP and s.toks[b] != "so":
        b -= 1  # ("..., but first stop because ...": the words between were read as a new clause's)
    if s.toks[b] not in (",", "but", "so") and not _asked_to_stop(s, b):
        return _stop_ends_talk(s, i)
    k = i
    while k < i + 8:  # "..., but please just stop", "..., actually Stuart stop right there", "... but right now
        if s.at(k) in _BEFORE_A_STOP or s.at(k) in s.vocatives:  # I need you to just freeze where you are"
            k += 1
        elif s.at(k) in POLITE_BY_FIRST and (polite := s.phrase_at(k, POLITE_BY_FIRST)) is not None:
            k += len(polite)
        elif (s.at(k) == "right" and s.at(k + 1) == "now") or (s.at(k) in MODALS and s.at(k + 1) == "you"):
            k += 2  # "... but could you please stop"
        else:
            break
    end = stop_phrase_end(s, k)
    return end > 0 and _stop_ends(s, end)


def _asked_to_stop(s: ParseState, b: int) -> bool:
    """Whether the words up to ``b``, just before a stop, ask the robot for it with no pause
    before ("... towards the bathroom could you please stop there"), not ask why ("why would you
    stop")."""
    return s.toks[b] == "you" and b > 0 and s.toks[b - 1] in MODALS and (b < 2 or s.toks[b - 2] not in WH)


def _stop_ends(s: ParseState, j: int) -> bool:
    """Whether a stop verb's clause ends at ``j``, perhaps after saying where or how long ("..., so
    stop for a second", "..., but freeze a moment", "..., just halt right there for a second"):
    then it is a stop, not a word in the talk."""
    j = _after_pause_spans(s, j)
    while s.at(j) in ("now", "please"):  # ("... but stop now please the floor is wet")
        j += 1
    # "... just stop for a second while I fix your arm", "... but first stop because ...", "... stop for a second so
    # the group can ...", "... but stop you're way too close to the table"
    return (s.at(j) in CONDITIONS or s.at(j) in _REASONS or s.at(j) in _NEW_SUBJECT or may_end(s, j)
            or _statement_after(s, j))


def _statement_after(s: ParseState, j: int, verbs: frozenset[str] = COPULA) -> bool:
    """Whether a statement of its own starts at ``j`` (after a stop's words: "... but stop now
    please the floor is wet"; after a command: "... the kids want to see it"): it opens as one,
    and an auxiliary, a modal or one of ``verbs`` comes before the next connector."""
    if not (j < s.n and opens_conversation(s, j)):
        return False
    k = j + 1
    while k < s.n and s.toks[k] not in BOUNDARY:
        if s.toks[k] in AUX or s.toks[k] in MODALS or s.toks[k] in verbs:
            return True
        k += 1
    return False


def _after_pause_spans(s: ParseState, j: int) -> int:
    """``j`` past the words saying where or how long to stay stopped ("right there for a second")."""
    for _ in range(3):
        k = j + 1 if s.at(j) == "for" else j
        span = s.phrase_at(k, PAUSE_SPANS_BY_FIRST)
        if not span:
            break
        j = k + len(span)
    return j


def _stop_ends_talk(s: ParseState, i: int) -> bool:
    """Whether a stop said at ``i`` with no pause before it is the last thing said in a sentence
    of talk ("you're going way too far you were only meant to do half a metre halt"): an order
    tacked on to the talk, never the word inside it ("I told him to stop", "the bus stop", "why
    did you stop", "don't stop")."""
    if s.toks[i - 1] in _NO_ORDER_BEFORE and not (i > 1 and s.toks[i - 1] in _OBJECT_FORMS
                                                  and s.toks[i - 2] in _PREPOSITIONS):
        return False  # (but "... with all the printers on it stop": "it" is the printers, not who stops)
    end = stop_phrase_end(s, i)
    if not end:
        return False
    j = _after_pause_spans(s, end)
    while j < s.n and s.toks[j] not in HARD_STOPS and (s.toks[j] in TRAILING or s.toks[j] in s.stop_words):
        j += 1
    return j >= s.n or s.toks[j] in HARD_STOPS


# words before a stop verb that make it no order to the robot: its subject ("why did you stop",
# "made it stop"), "to", a negation, a modal or a determiner or adjective of the noun ("the bus stop",
# "came to a halt", "our last stop")
_NO_ORDER_BEFORE = frozenset({
    "to", "not", "dont", "never", "cant", "cannot", "wont", "didnt", "doesnt", "shouldnt", "wouldnt", "couldnt",
    "i", "you", "we", "they", "he", "she", "it", "me", "us", "them", "him", "ill", "youll", "well", "theyll",
    "will", "would", "could", "can", "should", "might", "must", "may", "shall", "did", "does", "do", "doing",
    "the", "a", "an", "this", "that", "my", "your", "our", "their", "his", "her", "its", "no",
    "bus", "pit", "last", "next", "final", "first", "full", "quick", "one", "every", "each", "deep", "ever", "always",
    "often", "sometimes", "usually"})

# the people a command is done for, as said at its end ("... for us old timers")
_WHOM = frozenset({"me", "us", "them", "him", "her"})
# pronouns that, after a preposition, are no subject of the stop after them ("... on it stop")
_OBJECT_FORMS = _WHOM | {"it"}
_PREPOSITIONS = frozenset({"on", "in", "at", "with", "to", "for", "from", "into", "onto", "near", "behind", "by",
                           "under", "over", "past", "towards", "toward", "about", "around", "beside", "of"})

# words said just before a stop that ends a stretch of talk ("..., actually stop", "..., just stop")
_BEFORE_A_STOP = frozenset({"just", "please", "now", "so", "actually", "oh", "ok", "no", "wait", "then", "honestly",
                            "seriously", "really", "first"})

# words that make a stop urgent, and the stop words of alarm: said after "and then", it still
# calls off the plan, not ends it ("go to station six and find the book and then um stop
# everything right now", "... and then halt"; "... and then stop" is the plan's last step); so
# does a warning said straight after it ("... and then stop you're going to knock over the tripod")
_URGENT = frozenset({"everything", "now", "immediately", "instantly", "emergency", "asap", "halt", "freeze"})

# words that open a stop said as a change of mind, even after "and" ("go to the workbench and um
# actually wait, freeze": the walk is called off)
_CHANGE_OF_MIND = frozenset({"actually", "oh", "no", "hmm", "hold", "hang"})

# words said before a correction or a retraction ("actually, scratch that", "oh no, stop")
INTERJECTIONS = frozenset({"actually", "oh", "ah", "well", "hmm", "ok", "so", "hang", "on", "hold", "wait"})

# words after which a stop is the next step of the plan ("... and then stop"), not an interruption
SEQUENCERS = frozenset({"then", "and", "afterwards", "afterward", "next", "finally", "lastly", "by", "that", "this"})

# corrections that, said alone with nothing to replace what they correct, take it back ("go there, no.")
RETRACTING = frozenset({("no",), ("no", "wait"), ("wait", "no"), ("scratch", "that"), ("not", "that"),
                        ("my", "mistake"), ("my", "bad")})

# what a token was to the reader: words a command came from, words of conversation, words of a
# choice the speaker left open ("..., or maybe right": the robot asks), a tag after a command
# ("go to the kitchen, right?": a question about it, or a check that it was heard? the robot asks)
USED, TALK, CHOICE, ASKED = 1, 2, 3, 4  # ASKED: a tag that puts a command as a question ("..., right?")
_RUNS = {how: bytes((how,)) * 256 for how in (USED, TALK, CHOICE)}  # MAX_TOKENS marks of each, sliced


def _mirrored(s: ParseState, j: int, last: TaskIntent) -> tuple[TaskIntent | None, int]:
    """``last`` again, to the side said at ``j`` ("... to the left", "the other way") for a move
    sideways or a turn, and where those words end; (None, j) when a side is said for a step that
    has none."""
    k = j + 1 if s.at(j) in ("to", "on") else j
    k += 1 if s.at(k) == "the" else 0
    if s.at(k) in ("left", "right"):
        sign, end = (1.0 if s.at(k) == "left" else -1.0), k + 1
    elif s.at(k) == "other" and s.at(k + 1) in ("way", "side", "direction"):
        sign, end = 0.0, k + 2
    else:
        return replace(last), j
    if last.action == TURN:
        return replace(last, yaw=-last.yaw if sign == 0.0 else math.copysign(last.yaw, sign)), end
    if last.action == MOVE and last.y and not last.x:
        return replace(last, y=-last.y if sign == 0.0 else math.copysign(last.y, sign)), end
    return None, j


def _condition_at(toks: list[str], start: int, end: int) -> int:
    """Where a condition starts inside a clause's words ("stay there until ..."), else ``end``:
    the robot cannot wait for a condition, so its words are never counted as understood."""
    if CONDITIONS.isdisjoint(toks[start + 1:end]):  # the common case, without a Python loop
        return end
    for k in range(start + 1, end):  # not its first word: "if you could ..." is polite
        if toks[k] in CONDITIONS and not (toks[k] == "if" and k + 2 < end and toks[k + 1] == "you" and toks[
                k + 2] in ("could", "would")) and not (  # nor in a polite opener: "I'd be grateful if you could ..."
                toks[k] in ("until", "till") and toks[k - 1] in UNTIL_VERBS and toks[k + 1:k + 2] == ["the"]) and not (
                toks[k] == "if" and toks[k - 1] in THANKS_AHEAD_FEELINGS):  # ("it'd be awesome if you gave me ...")
            return k  # ("go until the entrance": where to, read as "to")
    return end


def _reason_at(toks: list[str], start: int, end: int) -> int:
    """Where a reason or a purpose starts among the words after a command ("because we want to
    see your back", "so that everyone can see", "so we can see your back"), else ``end``: it says
    why, not what, so its words are talk, never unused words that make the robot ask."""
    span = toks[start:end]
    if _REASONS.isdisjoint(span) and "so" not in span:  # the common case, without a Python loop
        return end
    for k in range(start, end):
        t = toks[k]
        if t in _REASONS or (t == "so" and k + 1 < end and toks[k + 1] in _PURPOSE_SUBJECTS):
            return k
    return end


def _for_whom_at(toks: list[str], start: int, end: int) -> int:
    """Where "for" and whom a command is done for start ("turn around for the camera", "wave for
    the kids"), inside the command's words or after them, else ``end``; a time ("for a minute",
    "for the next ten minutes") is not, and an amount ("for two metres") is read as one."""
    if "for" not in toks[start:end]:  # the common case, without a Python loop
        return end
    for k in range(start, end - 1):
        if toks[k] == "for" and toks[k + 1] in _FOR_WHOM and TIMES.isdisjoint(toks[k + 1:end]):
            return k
    return end


# words that open a statement but no subject of one after a command ("pick up a cup", "go to the
# kitchen if ...", "turn left not right")
_NO_SUBJECT = frozenset({"a", "an", "one", "not", "if", "probably", "because", "although", "though", "unless", "said"})

# verbs of a statement said after a command, besides the auxiliaries ("the kids want to see it")
_REMARK_VERBS = frozenset({"want", "wants", "wanna", "need", "needs", "love", "loves", "like", "likes", "think",
                           "thinks", "know", "knows", "got", "get", "gets", "said", "says", "say"})

_REASONS = frozenset({"because", "cause", "cos", "coz", "cuz"})

# words that open a new clause after a stop with no pause ("stop you're way too close"), and "so"
_NEW_SUBJECT = frozenset({"so", "youre", "theres", "its", "im", "theyre", "hes", "shes", "thats", "were"})

# verbs of going in a way a walking humanoid cannot ("crawl to the entrance"): read as going
# there, but the word is not understood, so the robot asks
_GAITS_IT_LACKS = frozenset({"crawl", "slither", "swim", "fly", "hop"})

# actions that "for the camera" says whom they are done for (the others take a thing after "for")
_DONE_FOR_SOMEONE = frozenset({MOVE, TURN, TURN_AROUND, GESTURE, PICK})  # ("pick up the cup for my little girl")

# words that open who or what a command is done for ("for the camera", "for me", "for everyone")
_FOR_WHOM = frozenset({"the", "me", "us", "everyone", "everybody", "them", "him", "her", "our", "my", "all", "those",
                       "these", "this", "that", "your"})

_PURPOSE_SUBJECTS = frozenset({"that", "we", "i", "you", "they", "everyone", "everybody", "people", "he", "she",
                               "the", "our", "my", "visitors", "guests", "kids", "children"})

_NOT_WHICH = TIMES | BODY_PARTS | {"your"}


def _only_who(words: list[str]) -> bool:
    """Whether ``words`` after "for us" can only say who "us" are: no verb, no time, no direction."""
    return all(w not in ALL_VERBS and w not in TIMES and w not in DIRECTIONS for w in words)



def _names_a_way(words: Iterable[str]) -> bool:
    """Whether ``words`` name a direction or a way of turning ("left", "back", "clockwise")."""
    return any(w in DIRECTIONS or w in ROTATIONS for w in words)


def _names_an_amount(words: Iterable[str]) -> bool:
    """Whether ``words`` name an amount: a number, "a bit", "half", "a couple", a step."""
    return any(w[:1].isdigit() or w in _AMOUNT_WORDS or word_value(w) is not None for w in words)


_AMOUNT_WORDS = frozenset({"bit", "little", "tad", "touch", "smidge", "slightly", "half", "quarter", "couple", "few",
                           "step", "steps", "pace", "paces", "full", "whole", "all", "way"})


def _says_which(words: list[str]) -> bool:
    """A phrase after a target that says which thing or place is meant ("on the counter"), not
    when ("in an hour", "at half two", "at three") or how ("with your teeth", "on one leg")."""
    if words[:1] == ["at"] and (words[1:2] == ["half"] or word_value(words[1] if len(words) > 1 else "") is not None):
        return False  # a clock time
    return _NOT_WHICH.isdisjoint(words)


def _first_after(toks: list[str], j: int) -> bool:
    """Whether "first" is said after a clause's words, before the next connector ("turn around
    first", "turn around first please"): the clause goes before the others."""
    for t in toks[j:j + 4]:
        if t == "first":
            return True
        if t in BOUNDARY:
            return False
    return False


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
