"""Spoken numbers and quantities: "two", "forty five", "one and a half", "1.5 m", "half a metre".

Speech recognisers write numbers either way ("two metres", "2 metres", "2m"), and people say
fractions the way they learned them ("a metre and a half", "three quarters of a metre"), so the
grammar never looks at a number itself: it asks this module to read one at a token position.

Everything works on lists of lower-case tokens (see :func:`stuart_bt.language.grammar.tokenize`)
and returns the index after what it read, so the grammar can go on from there. Results are in SI
units: metres and radians (REP-103).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

ONES: dict[str, int] = {
    "zero": 0, "nought": 0, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6,
    "seven": 7, "eight": 8, "nine": 9, "ten": 10, "eleven": 11, "twelve": 12, "thirteen": 13,
    "fourteen": 14, "fifteen": 15, "sixteen": 16, "seventeen": 17, "eighteen": 18, "nineteen": 19,
}
TENS: dict[str, int] = {
    "twenty": 20, "thirty": 30, "forty": 40, "fourty": 40, "fifty": 50, "sixty": 60,
    "seventy": 70, "eighty": 80, "ninety": 90,
}
FRACTIONS: dict[str, float] = {
    "half": 0.5, "halves": 0.5, "quarter": 0.25, "quarters": 0.25, "third": 1 / 3, "thirds": 1 / 3,
}
ORDINALS: dict[str, int] = {
    "first": 1, "second": 2, "third": 3, "fourth": 4, "fifth": 5, "sixth": 6, "seventh": 7,
    "eighth": 8, "ninth": 9, "tenth": 10,
}
# Words recognisers write for a number; only read as one right before a plural unit.
SOUNDS_LIKE: dict[str, float] = {"to": 2.0, "too": 2.0, "for": 4.0, "won": 1.0, "ate": 8.0}
VAGUE: dict[str, float] = {"couple": 2.0, "few": 3.0, "pair": 2.0, "several": 3.0}

STEP_M = 0.5  # one step of the G1 as a distance ("take two steps back")

# unit word -> (dimension, factor to SI)
LENGTH, ANGLE = "length", "angle"
DEG = math.pi / 180.0
UNITS: dict[str, tuple[str, float]] = {
    **{w: (LENGTH, 1.0) for w in ("m", "metre", "metres", "meter", "meters", "mtr", "mtrs", "mt", "meta", "metres's")},
    **{w: (LENGTH, 0.01) for w in ("cm", "cms", "centimetre", "centimetres", "centimeter", "centimeters",
                                   "centi", "centis")},
    **{w: (LENGTH, 0.001) for w in ("mm", "millimetre", "millimetres", "millimeter", "millimeters")},
    **{w: (LENGTH, 0.3048) for w in ("foot", "feet", "ft")},
    **{w: (LENGTH, 0.0254) for w in ("inch", "inches")},
    **{w: (LENGTH, 0.9144) for w in ("yard", "yards", "yd", "yds")},
    **{w: (LENGTH, STEP_M) for w in ("step", "steps", "pace", "paces")},
    **{w: (ANGLE, DEG) for w in ("degree", "degrees", "deg", "degs", "°", "degre", "degress")},
    **{w: (ANGLE, 1.0) for w in ("radian", "radians", "rad", "rads")},
    **{w: (ANGLE, 2 * math.pi) for w in ("turn", "turns", "revolution", "revolutions", "rotation",
                                         "rotations", "circle", "circles", "spin")},
}
WHOLE = frozenset({"full", "complete", "whole", "entire"})  # "a full turn" = one turn


@dataclass(frozen=True)
class Quantity:
    """A number with its dimension: ``value`` in metres or radians, or a bare number (``unit`` "")
    whose unit the caller decides (metres after "move", degrees after "turn")."""

    value: float
    dimension: str  # LENGTH, ANGLE or "" for a bare number
    end: int  # index of the first token after the quantity


def _digits(tok: str) -> float | None:
    c = tok[0]
    if not ("0" <= c <= "9") and not (c == "." and len(tok) > 1):
        return None
    try:
        return float(tok.replace(",", "."))
    except ValueError:
        return None


def word_value(tok: str) -> float | None:
    """The value of one number token ("7", "1.5", "seven", "forty"), or ``None``."""
    if not tok:
        return None  # past the end of the tokens
    v = _digits(tok)
    if v is not None:
        return v
    if tok in ONES:
        return float(ONES[tok])
    if tok in TENS:
        return float(TENS[tok])
    return None


def _fraction_after_and(toks: Sequence[str], i: int) -> tuple[float, int] | None:
    """ "and a half", "and a quarter", "and three quarters" starting at ``toks[i] == "and"``."""
    n = len(toks)
    if i + 1 >= n or toks[i] != "and":
        return None
    t = toks[i + 1]
    if t in ("a", "an", "one") and i + 2 < n and toks[i + 2] in FRACTIONS:
        return FRACTIONS[toks[i + 2]], i + 3
    if t in ONES and i + 2 < n and toks[i + 2] in FRACTIONS:  # "and three quarters"
        return ONES[t] * FRACTIONS[toks[i + 2]], i + 3
    if t in FRACTIONS and t not in ("third", "thirds"):  # "and half"
        return FRACTIONS[t], i + 2
    return None


def _words(toks: Sequence[str], i: int) -> tuple[float, int] | None:
    """An integer in words: "seven", "forty five", "one hundred and eighty", "a hundred",
    and the way people say angles and lengths: "one eighty" (180), "two seventy", "one fifty"."""
    n = len(toks)
    total, current, j = 0, 0, i
    last = ""  # kind of the previous word: ones, teen, tens, hundred, and
    if j + 1 < n and toks[j] in ("a", "an") and toks[j + 1] in ("hundred", "thousand"):
        current, j, last = 1, j + 1, "ones"
    while j < n:
        t = toks[j]
        if t == "thousand" and last and last != "and":
            total += current * 1000
            current, last = 0, "hundred"
        elif t == "and" and last == "hundred" and j + 1 < n and (toks[j + 1] in ONES or toks[j + 1] in TENS):
            last = "and"  # "one hundred and eighty"
        else:
            step = _next_word(t, last, current, second=j == i + 1)
            if step is None:
                break
            current, last = step
        j += 1
    if not last:
        return None
    return float(total + current), j


def _next_word(t: str, last: str, current: int, second: bool) -> tuple[int, str] | None:
    """``current`` with the number word ``t`` added after a word of kind ``last`` (``second``:
    ``t`` is the number's second word): (the new value, the kind of ``t``), or ``None`` when
    ``t`` does not carry the number on."""
    if t == "hundred":
        return (current * 100, "hundred") if last in ("ones", "teen") and current < 100 else None
    if t in ONES:
        value = ONES[t]
        kind = "ones" if value < 10 else "teen"
        follows = (kind == "ones" and last == "tens")  # "forty five"
    elif t in TENS:
        value, kind, follows = TENS[t], "tens", False
    else:
        return None
    if not last:
        return value, kind
    if follows or last in ("hundred", "and"):  # "a hundred five", "one hundred and fifteen"
        return current + value, kind
    if last == "ones" and second and current > 0 and kind != "ones":
        return current * 100 + value, kind  # "one fifteen", "one eighty"
    return None


def _after_point(toks: Sequence[str], k: int) -> tuple[float, int] | None:
    """The decimals spoken after "point", one digit per word or as digits ("point seven five",
    "point 5"): (the fraction, next index), or ``None``."""
    n = len(toks)
    if k < n and toks[k].isdigit():
        return float("0." + toks[k]), k + 1
    digits = []
    while k < n and toks[k] in ONES and ONES[toks[k]] < 10:
        digits.append(str(ONES[toks[k]]))
        k += 1
    return (float("0." + "".join(digits)), k) if digits else None


def read_number(toks: Sequence[str], i: int) -> tuple[float, int] | None:
    """A number at ``toks[i]``: digits ("1.5"), words ("one point five", "point five", "twenty five"),
    fractions ("half", "a half", "three quarters", "two and a half"), vague amounts ("a couple
    of", "a few"). Returns (value, next index) or ``None``. A lone "a"/"an" is not a number here:
    "a metre" is read by :func:`read_quantity`, which knows a unit follows."""
    if i >= len(toks):
        return None
    got = _leading_number(toks, i)
    if got is None:
        return None
    value, j = got
    n = len(toks)
    if j < n and toks[j] in FRACTIONS and value == int(value) and value >= 1 and toks[i] not in ("a", "an"):
        value, j = value * FRACTIONS[toks[j]], j + 1  # "three quarters", "two thirds"
    frac = _fraction_after_and(toks, j)
    if frac is not None and not (j < n and toks[j] == "and" and value != int(value)):
        value, j = value + frac[0], frac[1]  # "one and a half", "2 and a half"
    return value, j


def _leading_number(toks: Sequence[str], i: int) -> tuple[float, int] | None:
    """The number that starts at ``toks[i]``, before any fraction that may follow it."""
    t = toks[i]
    d = _digits(t)
    if d is not None:
        return d, i + 1
    if t in ("a", "an"):
        return _after_article(toks, i)
    if t in VAGUE:
        return VAGUE[t], _skip_of(toks, i + 1)
    if t in FRACTIONS and t not in ("third", "thirds"):  # "half", "quarter" ("third" is an ordinal)
        return FRACTIONS[t], i + 1
    if t == "point":  # "point five": the "zero" before the point is often not said
        return _after_point(toks, i + 1)
    got = _words(toks, i)
    if got is None:
        return None
    value, j = got
    after = _after_point(toks, j + 1) if j + 1 < len(toks) and toks[j] == "point" else None
    if after is not None:  # "one point five", "zero point seven five"
        return int(value) + after[0], after[1]
    return value, j


def _after_article(toks: Sequence[str], i: int) -> tuple[float, int] | None:
    """ "a half", "a couple of", "a few", "a hundred": a number that starts with "a"/"an"."""
    if i + 1 >= len(toks):
        return None
    nxt = toks[i + 1]
    if nxt in FRACTIONS:  # "a half", "a quarter"
        return FRACTIONS[nxt], i + 2
    if nxt in VAGUE:  # "a couple of", "a few"
        return VAGUE[nxt], _skip_of(toks, i + 2)
    if nxt in ("hundred", "thousand"):
        return _words(toks, i)
    return None


def _skip_of(toks: Sequence[str], j: int) -> int:
    """Past an "of" at ``j`` ("a couple of metres")."""
    return j + 1 if j < len(toks) and toks[j] == "of" else j


def _pi(toks: Sequence[str], i: int, number: tuple[float, int] | None) -> tuple[float, int] | None:
    """Angles in radians said with pi: "pi", "two pi", "pi over two", "pi by 4", "half pi".
    ``number`` is what :func:`read_number` read at ``i`` (read once: quantities are most of a
    command's parsing time)."""
    n = len(toks)
    factor, j = 1.0, i
    if j < n and toks[j] != "pi":
        if number is None or number[1] >= n or toks[number[1]] != "pi":
            return None
        factor, j = number
    if j >= n or toks[j] != "pi":
        return None
    j += 1
    if j + 1 < n and toks[j] in ("over", "by", "divided") :
        k = j + 2 if toks[j] == "divided" and toks[j + 1] == "by" else j + 1
        d = read_number(toks, k)
        if d is not None and d[0]:
            factor /= d[0]
            j = d[1]
    if j < n and toks[j] in ("radians", "radian", "rad", "rads"):
        j += 1
    return factor * math.pi, j


def _centimetres_after(toks: Sequence[str], j: int, metres: float) -> tuple[float, int]:
    """After "N metre(s)" at ``j``: centimetres said as a second number ("one metre fifty", "a
    metre and 20 centimetres"): (metres in all, next index); unchanged when none follows."""
    n = len(toks)
    if j >= n:
        return metres, j
    rest = read_number(toks, j + 1 if toks[j] == "and" else j)
    if rest is not None and 1 <= rest[0] < 100 and rest[0] == int(rest[0]):
        k = rest[1]
        if k < n and toks[k] in UNITS and UNITS[toks[k]] == (LENGTH, 0.01):
            return metres + rest[0] * 0.01, k + 1
        if (k >= n or toks[k] not in UNITS) and toks[j] != "and":
            return metres + rest[0] * 0.01, k
    return metres, j


def read_quantity(toks: Sequence[str], i: int) -> Quantity | None:
    """A number with an optional unit: "2 m", "two metres", "a metre and a half", "half a metre",
    "a quarter of a metre", "fifty centimetres", "ninety degrees", "a quarter turn", "a full turn",
    "a couple of metres", "one metre fifty". Value in SI (metres, radians); a bare number keeps its
    value and an empty dimension for the caller to interpret."""
    n = len(toks)
    if i >= n:
        return None
    t = toks[i]
    j = i
    value: float
    got = read_number(toks, i)
    pi = _pi(toks, i, got)
    if pi is not None:
        return Quantity(pi[0], ANGLE, pi[1])
    if got is None and t in SOUNDS_LIKE and i + 1 < n and toks[i + 1] in UNITS and toks[i + 1].endswith("s"):
        got = SOUNDS_LIKE[t], i + 1  # "move forward to meters": a recogniser's "two"
    if got is None:
        # "a metre", "an inch", "a full turn", "one full turn" (no number word: one of the unit)
        k = i + 1 if t in ("a", "an", "another") else i  # "another metre": one more
        if k < n and toks[k] in WHOLE:
            k += 1
        if k < n and toks[k] in UNITS and (k > i):
            dim, factor = UNITS[toks[k]]
            value, j = factor, k + 1
            frac = _fraction_after_and(toks, j)  # "a metre and a half"
            if frac is not None:
                value, j = factor * (1 + frac[0]), frac[1]
            elif dim == LENGTH and factor == 1.0:
                value, j = _centimetres_after(toks, j, value)  # "a metre fifty"
            return Quantity(value, dim, j)
        return None
    value, j = got
    j = _to_the_unit(toks, j)
    if j < n and toks[j] in UNITS:
        dim, factor = UNITS[toks[j]]
        j += 1
        total = value * factor
        frac = _fraction_after_and(toks, j)  # "two metres and a half"
        if frac is not None and value == int(value):
            total, j = (value + frac[0]) * factor, frac[1]
        elif dim == LENGTH and factor == 1.0:
            total, j = _centimetres_after(toks, j, total)  # "one metre fifty (centimetres)"
        return Quantity(total, dim, j)
    return Quantity(value, "", got[1])  # a bare number: the caller knows its unit


def _to_the_unit(toks: Sequence[str], j: int) -> int:
    """Past the words between a number and its unit: "one *more* metre", "half *of a* metre",
    "three quarters *of a* turn", "one *full* turn"."""
    n = len(toks)
    if j + 1 < n and toks[j] in ("more", "extra") and toks[j + 1] in UNITS:
        j += 1  # "one more metre", "two extra metres": how far still, not another amount
    if j < n and toks[j] == "of":
        j += 1
    if j < n and toks[j] in ("a", "an") and j + 1 < n and (toks[j + 1] in UNITS or toks[j + 1] in WHOLE):
        j += 1
    if j < n and toks[j] in WHOLE:
        j += 1
    return j


def ordinal(tok: str) -> int | None:
    """ "third" -> 3, "3rd" -> 3, otherwise ``None`` (for "the third station")."""
    if tok in ORDINALS:
        return ORDINALS[tok]
    if len(tok) > 2 and tok[-2:] in ("st", "nd", "rd", "th") and tok[:-2].isdigit():
        return int(tok[:-2])
    return None


def digits_for_words(words: Sequence[str]) -> list[str]:
    """Replace number words by digits ("station three" -> "station 3"): how targets are compared
    with marker names, never how the grammar reports them."""
    out: list[str] = []
    i, n = 0, len(words)
    while i < n:
        got = _words(words, i) if words[i] not in ("a", "an") else None
        if got is not None:
            value, j = got
            out.append(str(int(value)))
            i = j
            continue
        o = ordinal(words[i])
        out.append(str(o) if o is not None else words[i])
        i += 1
    return out
