"""One parse's state (tokens, what came before, settings) and the small helpers every reader uses."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import NamedTuple

from ..numbers import STEP_M
from .lexicon import (
    ALL_VERBS,
    BOUNDARY,
    CONDITIONS,
    CORRECTIONS_BY_FIRST,
    DETERMINERS,
    INSTEAD,
    PLAIN_STOPS,
    RETRACTIONS_BY_FIRST,
    SIGN_OFFS_BY_FIRST,
    STEP_ORDINALS,
    STRONG_VERBS,
    SUBJECT_AND_BE,
    TRAILING,
    VERB_PARTICLES,
)

Spec = tuple[str, str, float, float, float]  # (action, target, x, y, yaw): an intent without raw_text

Result = tuple[list[Spec], int] | None
Reader = Callable[["ParseState", int], Result]  # reads from a position: what it found, and where it stopped


class Found(NamedTuple):
    """A reader's opening words already made the whole reading (or showed it is none: ``None``),
    as opposed to a position to read on from."""

    result: Result


@dataclass(frozen=True)
class Defaults:
    """Amounts used when the speaker gives none. Why these: a metre is the smallest distance
    the G1 walks cleanly (its controller ignores speeds below ~0.3 m/s, so shorter moves are
    mostly start and stop); a step of the G1 is about half a metre; "turn left" means a right
    angle; "a bit" is deliberately small."""

    move_m: float = 1.0
    vague_move_m: float = 0.5  # "a bit", "a little", "slightly"
    step_m: float = STEP_M  # "take a step back" (numbers.STEP_M: "two steps" is a length)
    turn_deg: float = 90.0
    vague_turn_deg: float = 30.0


@dataclass(slots=True)
class ParseState:
    """One parse: the tokens, what came before (for "it", "there" and ellipsis) and settings."""

    toks: list[str]
    n: int
    defaults: Defaults
    stop_words: frozenset[str]
    read_clause: Reader  # for a verb that leads into another ("go and get ...")
    readers: Mapping[str, Reader] = field(default_factory=dict)  # verb family -> its reader, see read_as
    contracted: frozenset[int] = frozenset()  # tokens written with "'s" ("battery's"): Tokens.contracted
    last_action: str = ""
    last_object: str = ""
    last_place: str = ""
    topic: str = ""  # a bare noun phrase said before the command ("the kitchen, go there")
    first: bool = True
    subordinate: bool = False  # reading "when you ...": "you" is the subject, so no ellipsis
    vocatives: frozenset[str] = frozenset()  # the robot's name, said again inside the command

    def read_as(self, family: str, i: int) -> Result:
        """Read the verb at ``i`` as another family's ("get the cup" is a pick, "make a U-turn" a
        light verb). The families are wired together here, by the clause reader, so that a
        family's module need not import a family that imports it."""
        return self.readers[family](self, i)

    def at(self, i: int) -> str:
        return self.toks[i] if i < self.n else ""

    def phrase_at(self, i: int, table: dict[str, tuple[tuple[str, ...], ...]]) -> tuple[str, ...] | None:
        """The longest entry of ``table`` (by first word) that the tokens at ``i`` spell."""
        forms = table.get(self.toks[i]) if i < self.n else None
        if forms:
            toks = self.toks
            for f in forms:
                k = len(f)
                if k == 1 or tuple(toks[i:i + k]) == f:
                    return f
        return None


def may_end(s: ParseState, j: int) -> bool:
    """Whether the clause may end at ``j``: end of text, a connector, or trailing words only."""
    toks, n = s.toks, s.n
    while j < n:
        t = toks[j]
        if t in BOUNDARY:
            return True
        if t not in TRAILING and t not in s.stop_words:
            return False
        j += 1
    return True


_RECEIVERS = frozenset({"me", "us", "them", "him", "her", "everyone", "everybody", "people", "the"})


def stop_phrase_end(s: ParseState, k: int) -> int:
    """Where a stop said at ``k`` ends: after "stop", "freeze", "halt" (and "moving", "it",
    "everything" after them) or "hold it" / "hold on" / "hold still"; 0 when none is said there."""
    if s.at(k) in PLAIN_STOPS:
        return k + 2 if s.at(k + 1) in ("move", "moving", "it", "everything") else k + 1  # "moving" reads as "move"
    if s.at(k) in ("hold", "hang") and s.at(k + 1) in ("it", "on", "still", "up"):
        return k + 2
    return 0


def starts_a_stop(s: ParseState, j: int) -> bool:
    """Whether a stop is said at ``j`` among words that only say more about a command ("... wave
    at the visitors stop", "... and wave freeze", "... actually hold it"): the words that only
    colour a command end there, so the stop is read (and wins)."""
    return stop_phrase_end(s, j) > 0


def said_instead_at(s: ParseState, j: int) -> bool:
    """Whether a thing said instead of the one before starts at ``j``, with no pause ("pick up the
    apple hmm actually the book")."""
    return s.toks[j] in INSTEAD and s.at(j + 1) in DETERMINERS


def verb_and_it(s: ParseState, j: int) -> bool:
    """Whether a verb and "it" or "them" start a new command at ``j`` ("... take it to the reading
    room", "... bring them here"): a verb with a pronoun for its object is never part of a name."""
    return (s.toks[j] in ALL_VERBS and s.at(j + 1) in ("it", "them") and j > 0
            and s.toks[j - 1] not in DETERMINERS and s.toks[j - 1] != "to")


def numbers_a_step(s: ParseState, j: int) -> bool:
    """Whether an ordinal at ``j`` numbers the next step of a plan ("... second pick it up"): one
    before a verb ("for a second", "the second station" are none)."""
    return s.toks[j] in STEP_ORDINALS and s.at(j + 1) in ALL_VERBS


def skip_rest(s: ParseState, j: int) -> int:
    """After a clause: skip words the grammar does not use ("at the door", "quickly") up to the
    next connector, a purpose "to <verb>", or a new verb that starts a command."""
    toks, n = s.toks, s.n
    condition = False  # after "until", "unless", "if", "while": a verb is part of the condition
    while j < n:
        t = toks[j]
        if t in BOUNDARY and not (condition and t in ("when", "once", "after", "before")):
            break
        if t in CONDITIONS:
            condition = True
        elif not condition:
            if t == "as" and s.at(j + 1) == "soon" and s.at(j + 2) == "as" and s.at(j + 3) in ("you", "youre", "youve"):
                break  # "pick up the cup as soon as you get to the kitchen": a subordinate clause next
            if t in CORRECTIONS_BY_FIRST and s.phrase_at(j, CORRECTIONS_BY_FIRST) is not None:
                break  # "go to the kitchen no the bathroom"
            if t in RETRACTIONS_BY_FIRST and s.phrase_at(j, RETRACTIONS_BY_FIRST) is not None:
                break  # "turn left just kidding": the driver decides whether it takes the turn back
            if t == "to" and j + 1 < n and toks[j + 1] in ALL_VERBS and toks[j + 1] not in ("back", "hand", "face"):
                break
            if t in STRONG_VERBS and toks[j - 1] not in DETERMINERS and toks[j - 1] != "to" and (
                    toks[j - 1] not in SUBJECT_AND_BE) or starts_a_stop(s, j):
                break  # (not "... we're heading home": a statement, no command)
            if verb_and_it(s, j) or said_instead_at(s, j) or numbers_a_step(s, j):
                break  # "pick up the book take it to ...": the next command; "... actually the book": a correction;
                # "... second pick it up": the next step, numbered
            if t in ("do", "give") and (s.at(j + 1) in DETERMINERS or s.at(j + 1) in _RECEIVERS):
                break  # "... the corner do a high five", "... give everyone a wave": the next command
            if t in SIGN_OFFS_BY_FIRST and (off := s.phrase_at(j, SIGN_OFFS_BY_FIRST)) and may_end(s, j + len(off)):
                break  # "find the screwdriver you know": said, not asked (the driver reads it)
            if (t, s.at(j + 1)) in VERB_PARTICLES and toks[j - 1] not in DETERMINERS and toks[j - 1] != "to":
                break
        j += 1
    return j
