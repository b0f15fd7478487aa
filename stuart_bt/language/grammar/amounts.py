"""Amounts of motion: distances, directions and angles ("two metres forward", "left 90",
"a quarter turn"), with the defaults when none is said.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..intents import MOVE, TURN, TURN_AROUND
from ..numbers import ANGLE, LENGTH, SOUNDS_LIKE, STEP_M, UNITS, Quantity, read_number, read_quantity
from .lexicon import (
    AROUND,
    BACKWARD,
    BOUNDARY,
    DIRECTIONS,
    FORWARD,
    LEFT,
    MOVE_FILLER,
    RIGHT,
    ROTATIONS,
    TURN_FILLER,
    VAGUE_BY_FIRST,
)
from .state import ParseState, Result


def read_motion_terms(s: ParseState, i: int) -> tuple[tuple[int, int] | None, float | None, str, bool, int]:
    """Direction and amount after a motion or turn verb, in any order ("forward two metres",
    "2 m to the left", "a little to the right", "90 degrees clockwise"): (direction, amount,
    its dimension, vague?, end). A rotation word (clockwise) counts as LEFT/RIGHT."""
    toks, n = s.toks, s.n
    direction: tuple[int, int] | None = None
    amount: float | None = None
    dim = ""
    vague = False
    j = i
    for _ in range(12):
        if j >= n:
            break
        t = toks[j]
        if t in DIRECTIONS:
            d = DIRECTIONS[t]
            if direction is not None and d != direction:
                break  # "forward and left" is two moves; "forward left" is not understood
            direction = d
            j += 1
            continue
        if t in ("clockwise", "cw", "anticlockwise", "counterclockwise", "ccw"):
            direction = LEFT if ROTATIONS[t] > 0 else RIGHT
            j += 1
            continue
        if t in ("anti", "counter") and j + 1 < n and toks[j + 1] == "clockwise":
            direction = LEFT
            j += 2
            continue
        if amount is None:
            v = s.phrase_at(j, VAGUE_BY_FIRST)
            if v is not None:
                vague = True
                j += len(v)
                continue
            if t in ("a", "an") and j + 1 < n and toks[j + 1] in ("few", "couple", "full", "quarter", "half"):
                pass
            q = read_quantity(toks, j) if (t[0].isdigit() or t in NUMBER_STARTS or (
                (t in SOUNDS_LIKE or t == "another") and j + 1 < n and toks[j + 1] in UNITS)) else None
            if q is not None:
                amount, dim = q.value, q.dimension
                j = q.end
                continue
        if t in MOVE_FILLER or t in TURN_FILLER:
            if t in ("the", "to", "your", "my") and j + 1 < n and (toks[j + 1] in DIRECTIONS or toks[j + 1] in (
                    "the", "your", "my", "left", "right") or toks[j + 1] in ROTATIONS):
                j += 1
                continue
            if t in ("a", "an", "the", "your", "my", "its", "of", "some", "way", "place", "side", "spot",
                     "direction") or (j + 1 < n and toks[j + 1] not in BOUNDARY):
                if t in ("a", "an") and not (j + 1 < n and (toks[j + 1] in UNITS or toks[j + 1] in NUMBER_STARTS)):
                    break
                j += 1
                continue
        break
    return direction, amount, dim, vague, j

NUMBER_STARTS = frozenset({
    "a", "an", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven", "twelve",
    "thirteen", "fourteen", "fifteen", "sixteen", "seventeen", "eighteen", "nineteen", "twenty", "thirty",
    "forty", "fourty", "fifty", "sixty", "seventy", "eighty", "ninety", "hundred", "half", "quarter", "quarters",
    "couple", "few", "several", "zero", "nought", "full", "complete", "whole", "pair", "pi", "point",
})

MAX_BARE_SIDESTEP_M = 10.0  # "left 90" with no unit: more than the lab is wide, so an angle

STEP_WORDS = frozenset(w for w, (dim, factor) in UNITS.items() if dim == LENGTH and factor == STEP_M)

_FRACTION_STARTS = frozenset({"a", "an", "half", "quarter", "quarters", "one", "three", "two"})  # "three quarters"


def read_move(s: ParseState, i: int, verb: str, default_back: bool = False) -> Result:
    """move_relative from the direction/amount after a motion verb; ``None`` if neither was said
    or the amount is an angle."""
    direction, amount, dim, vague, j = read_motion_terms(s, i)
    if direction is None and amount is None and not vague and not default_back:
        return None
    if dim == ANGLE:
        return None
    d = s.defaults
    if amount is None:
        amount = d.vague_move_m if vague else (d.step_m if verb in ("step", "sidestep") else d.move_m)
    elif dim == "" and verb in ("step", "sidestep"):
        amount *= d.step_m  # "step back two": two steps
    if direction is None:
        direction = BACKWARD if default_back else FORWARD
    return [(MOVE, "", amount * direction[0], amount * direction[1], 0.0)], j


@dataclass
class _Turn:
    """What a turn's words said so far."""

    verb: str
    j: int
    around: bool = False
    sign: int = 0
    angle: float | None = None
    vague: bool = False
    times: int = 1


def read_turn_terms(s: ParseState, i: int, verb: str) -> Result:
    """turn_by_angle / turn_around from what follows a turn verb (or stands alone: "left 90")."""
    r = _Turn(verb, i)
    for _ in range(12):
        if r.j >= s.n:
            break
        t = s.toks[r.j]
        if _turn_direction(s, r, t) or _turn_count(s, r, t):
            continue
        if r.angle is None and not r.vague and (vague := s.phrase_at(r.j, VAGUE_BY_FIRST)) is not None:
            r.vague = True
            r.j += len(vague)
        elif r.angle is None and (t[0].isdigit() or t in NUMBER_STARTS or (
                t in SOUNDS_LIKE and s.at(r.j + 1) in UNITS)) and (q := read_quantity(s.toks, r.j)) is not None:
            if q.dimension == LENGTH:
                return None
            if _half_way_round(s, q, t):
                return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], q.end + 2
            r.angle, r.j = _turn_angle(q, t), q.end
        elif t in TURN_FILLER and r.j + 1 < s.n and s.toks[r.j + 1] not in BOUNDARY:
            r.j += 1
        elif t in ("turn",) and r.verb in ("turn", "make", "do", "take") and r.angle is not None:
            r.j += 1  # "make a quarter turn"
        else:
            break
    return _turn_result(s, r)


def _turn_direction(s: ParseState, r: _Turn, t: str) -> bool:
    """Which way: "around", "the other way", "to face away", "left", "anticlockwise"."""
    if t in AROUND or t in ("back", "backward", "backwards", "behind") and r.verb in ("turn", "face", "spin"):
        r.around, r.j = True, r.j + 1
    elif t == "other" and s.at(r.j + 1) in ("way", "direction", "side"):
        r.around, r.j = True, r.j + 2
    elif t == "face" and r.verb != "face":  # "turn to face the other way"
        r.verb, r.j = "face", r.j + 1
    elif t == "away" and r.verb == "face":
        r.around, r.j = True, r.j + 1
    elif t in ROTATIONS and r.sign == 0:
        r.sign, r.j = ROTATIONS[t], r.j + 1
    elif t in ("anti", "counter") and s.at(r.j + 1) == "clockwise":
        r.sign, r.j = 1, r.j + 2
    else:
        return False
    return True


def _turn_count(s: ParseState, r: _Turn, t: str) -> bool:
    """How many times: "twice", "three times"."""
    if t == "twice":
        r.times, r.j = 2, r.j + 1
    elif t in ("three", "four", "3", "4", "two", "2") and s.at(r.j + 1) == "times":
        count = read_number(s.toks, r.j)
        r.times, r.j = int(count[0]) if count else 1, r.j + 2
    else:
        return False
    return True


def _half_way_round(s: ParseState, q: Quantity, t: str) -> bool:
    """ "half way round", "a half turn around": a turn around, however it was said."""
    return (q.dimension != ANGLE and q.value < 1 and t in _FRACTION_STARTS and q.value * 2 * math.pi == math.pi
            and s.at(q.end) in ("way", "turn") and s.at(q.end + 1) in AROUND)


def _turn_angle(q: Quantity, t: str) -> float:
    """Radians from an amount: an angle as said; a fraction of a full turn ("a quarter", "half
    way"); a bare number is degrees."""
    if q.dimension == ANGLE:
        return q.value
    if q.value < 1 and t in _FRACTION_STARTS:
        return q.value * 2 * math.pi  # "turn a quarter to the right", "turn half way round"
    return math.radians(q.value)


def _turn_result(s: ParseState, r: _Turn) -> Result:
    d = s.defaults
    if r.angle is not None:
        return [(TURN, "", 0.0, 0.0, (r.sign or 1) * r.angle * r.times)], r.j
    if r.around and (r.sign or r.times > 1):
        # "around" says how far, the side which way: "turn around to the left" is half a turn
        # leftwards; said more than once, "spin around" is whole spins, "turn around" half turns
        per = 2 * math.pi if r.verb == "spin" and r.times > 1 else math.pi
        return [(TURN, "", 0.0, 0.0, (r.sign or 1) * per * r.times)], r.j
    if r.verb == "spin" and r.times > 1:  # "spin left three times", "spin three times": whole spins
        return [(TURN, "", 0.0, 0.0, (r.sign or 1) * 2 * math.pi * r.times)], r.j
    if r.sign:
        deg = d.vague_turn_deg if r.vague else d.turn_deg
        return [(TURN, "", 0.0, 0.0, r.sign * math.radians(deg) * r.times)], r.j
    if r.around:
        return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], r.j
    return None
