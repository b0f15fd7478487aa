"""Pronunciations for words a recogniser's dictionary lacks.

A command-only recogniser can only hear words it can pronounce, and the lab's names are not all
in the CMU dictionary: "3D printers", "station 1", "xray", a new marker called "Labrat". A
pronunciation is built from pieces the dictionary does know, in this order:

1. runs of digits are said as numbers ("1" -> "one", "270" -> "two hundred seventy");
2. a word mixing letters and digits is said piece by piece ("3d" -> "three" "d");
3. a word the dictionary lacks is tried as two or three dictionary words run together
   ("xray" -> "x" "ray", "labrat" -> "lab" "rat"), the longest first piece first;
4. a short run of letters with no vowel is spelled ("pcb" -> "p" "c" "b");
5. anything else is read by letter-to-sound rules (:data:`GRAPHEMES`): English spelling is
   irregular, so this is a guess, but a guess close enough for a grammar of a few hundred words
   where the rest of the phrase carries the match.

Phones are the CMU / ARPAbet set of pocketsphinx's en-US model, without stress marks.
"""

from __future__ import annotations

import re
from collections.abc import Callable

Lookup = Callable[[str], "str | None"]  # a word -> its phones (space separated), or None

ONES = ("zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven", "twelve",
        "thirteen", "fourteen", "fifteen", "sixteen", "seventeen", "eighteen", "nineteen")
TENS = ("", "", "twenty", "thirty", "forty", "fifty", "sixty", "seventy", "eighty", "ninety")


def number_words(n: int) -> list[str]:
    """``n`` (0 <= n < 1,000,000) as people say it, in words: 270 -> two hundred seventy."""
    if n < 20:
        return [ONES[n]]
    if n < 100:
        return [TENS[n // 10]] + ([ONES[n % 10]] if n % 10 else [])
    if n < 1000:
        return [ONES[n // 100], "hundred"] + (number_words(n % 100) if n % 100 else [])
    return number_words(n // 1000) + ["thousand"] + (number_words(n % 1000) if n % 1000 else [])


# letter-to-sound: longest grapheme first; a guess for words no dictionary holds
GRAPHEMES: dict[str, str] = {
    "tch": "CH", "sch": "S K", "igh": "AY", "ough": "OW", "augh": "AO", "tion": "SH AH N", "sion": "ZH AH N",
    "ch": "CH", "sh": "SH", "th": "TH", "ph": "F", "wh": "W", "ck": "K", "ng": "NG", "qu": "K W", "gh": "G",
    "kn": "N", "wr": "R", "ee": "IY", "ea": "IY", "oo": "UW", "ou": "AW", "ow": "OW", "oi": "OY", "oy": "OY",
    "ai": "EY", "ay": "EY", "au": "AO", "aw": "AO", "ei": "EY", "ey": "IY", "ie": "IY", "ue": "UW", "ew": "UW",
    "oa": "OW", "ar": "AA R", "er": "ER", "ir": "ER", "ur": "ER", "or": "AO R",
    "a": "AE", "b": "B", "c": "K", "d": "D", "e": "EH", "f": "F", "g": "G", "h": "HH", "i": "IH", "j": "JH",
    "k": "K", "l": "L", "m": "M", "n": "N", "o": "AA", "p": "P", "q": "K", "r": "R", "s": "S", "t": "T",
    "u": "AH", "v": "V", "w": "W", "x": "K S", "y": "IY", "z": "Z",
}
_LONGEST = max(len(g) for g in GRAPHEMES)
_VOWELS = set("aeiouy")


def by_rule(word: str) -> str:
    """Letter-to-sound rules, longest grapheme first (a final silent "e" after a consonant is
    dropped: "labrate" -> L AE B R AE T)."""
    letters = word.lower()
    if len(letters) > 2 and letters.endswith("e") and letters[-2] not in _VOWELS:
        letters = letters[:-1]
    phones: list[str] = []
    i = 0
    while i < len(letters):
        for size in range(min(_LONGEST, len(letters) - i), 0, -1):
            piece = GRAPHEMES.get(letters[i:i + size])
            if piece is not None:
                phones.append(piece)
                i += size
                break
        else:
            i += 1  # not a letter (an apostrophe): silent
    return " ".join(phones)


def pronounce(word: str, lookup: Lookup) -> str | None:
    """Phones for ``word``: the dictionary's, or built as the module docstring says. None for a
    word with no letter the rules know (no letters or digits, or another script)."""
    word = word.lower()
    known = lookup(word)
    if known:
        return known
    phones = " ".join(" ".join(_piece(p, lookup) for p in re.findall(r"[0-9]+|[^\W\d_]+", word)).split())
    return phones or None


def _piece(piece: str, lookup: Lookup) -> str:
    if piece.isdigit():
        return " ".join(_word(w, lookup) for w in number_words(int(piece[:6])))
    known = lookup(piece)
    if known:
        return known
    if len(piece) <= 4 and not _VOWELS & set(piece):
        return " ".join(_word(letter, lookup) for letter in piece)
    split = _compound(piece, lookup, parts=3)
    return " ".join(split) if split else by_rule(piece)


def _compound(word: str, lookup: Lookup, parts: int) -> list[str] | None:
    """``word`` as up to ``parts`` dictionary words run together (each of two letters or more,
    but for a single letter such as the "x" of "xray"), the longest first piece first."""
    for cut in range(len(word) - 1, 0, -1):
        head, tail = word[:cut], word[cut:]
        said = lookup(head) if len(head) > 1 or head in ("x", "u") else None
        if not said:
            continue
        rest = lookup(tail) if len(tail) > 1 else None
        if rest:
            return [said, rest]
        if parts > 2 and (more := _compound(tail, lookup, parts - 1)):
            return [said, *more]
    return None


def _word(word: str, lookup: Lookup) -> str:
    return lookup(word) or by_rule(word)
