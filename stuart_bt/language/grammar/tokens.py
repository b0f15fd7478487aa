"""Text to tokens: lower case, clause punctuation as tokens, number-unit runs split, hesitations and
repeats dropped, ing-forms of known verbs made plain; and the way back to character spans.
"""

from __future__ import annotations

import re

from ..numbers import UNITS, word_value
from .lexicon import DISFLUENCIES, GERUNDS, HARD_STOPS, HESITANT, INTERRUPTING, PLAIN_STOPS, SPLITS, STOP_VERBS

_NUM_UNIT = re.compile(r"(\d+(?:[.,]\d+)?)([^\W\d_]+|°)$")

MAX_TOKENS = 200  # a spoken command is never longer; the rest of a longer text is not read

_SPECIAL = frozenset(DISFLUENCIES | set(SPLITS) | set(GERUNDS) | INTERRUPTING)
# a dash standing alone before a stop is the speaker breaking off ("... turn left and - freeze!",
# "wave at the - halt"): read as the end of a sentence (one character for one: spans stay right)
_BREAK_BEFORE_A_STOP = re.compile(r"(?<=\s)[-–—](?=\s*(?:stop|halt|freeze|emergency|wait)\b)")
_PAUSES = HARD_STOPS | {","}


class Tokens:
    """The tokens of a text and, computed only when asked (for ``raw_text``), their spans."""

    __slots__ = ("_low", "_offsets", "_raw", "_src", "contracted", "gerunds", "read_to", "toks")

    def __init__(self, toks: list[str], src: list[int], raw: list[str], low: str, read_to: int | None = None,
                 gerunds: frozenset[int] = frozenset(), contracted: frozenset[int] = frozenset()) -> None:
        self.toks = toks
        self.gerunds = gerunds  # tokens that were said as ing-forms ("walking" -> "walk"): a subject, maybe
        # nouns written with "'s" ("battery's"): a possessive or "is", which the dropped apostrophe hides
        self.contracted = contracted
        self.read_to = len(raw) if read_to is None else read_to  # pieces read: fewer when MAX_TOKENS cut the text
        self._src = src  # token index -> index of the whitespace-separated piece it came from
        self._raw = raw
        self._low = low
        self._offsets: list[int] | None = None

    def without(self, token: str) -> Tokens:
        """The same tokens with every ``token`` left out."""
        return self.kept([k for k, t in enumerate(self.toks) if t != token])

    def kept(self, keep: list[int]) -> Tokens:
        """The same tokens with only those at the indices ``keep`` (in order)."""
        gerunds = frozenset(new for new, old in enumerate(keep) if old in self.gerunds)
        contracted = frozenset(new for new, old in enumerate(keep) if old in self.contracted)
        return Tokens([self.toks[k] for k in keep], [self._src[k] for k in keep], self._raw, self._low, self.read_to,
                      gerunds, contracted)

    @property
    def truncated(self) -> bool:
        """Whether the text was longer than MAX_TOKENS and its end was not read."""
        return self.read_to < len(self._raw)

    def unread(self) -> str:
        """The text after the last piece read (empty unless ``truncated``)."""
        return " ".join(self._raw[self.read_to:]) if self.read_to < len(self._raw) else ""

    def span(self, first: int, last: int) -> tuple[int, int]:
        """Character span in the text from token ``first`` to token ``last`` (inclusive)."""
        if self._offsets is None:
            offsets, pos, low = [], 0, self._low
            for piece in self._raw:
                at = low.find(piece, pos)
                offsets.append(at)
                pos = at + len(piece)
            self._offsets = offsets
        a, b = self._src[first], self._src[last]
        return self._offsets[a], self._offsets[b] + len(self._raw[b])

_SEPARATE = str.maketrans({
    **{c: " " for c in "\"()[]{}<>*+=/|~^`@#$%:_-–—‐‑“”„«»…•·\t\n\r"},
    **{c: f" {c} " for c in ".,;!?&°"},
    "’": "'", "‘": "'",
})

# a title's full stop, before the name ("shake hands with Dr. Okafor")
_TITLE_DOT = re.compile(r"\b(dr|mr|mrs|ms|prof|st|mt|capt)\.(?= +[^\W\d_])")

# "write" where only the side can be meant, as recognisers write "right" (same length: offsets hold)
_WRITE_AS_RIGHT = re.compile(r"\b((?:the|your|to|and|then|hard|bear|veer) )write\b")

_DECIMAL = re.compile(r"\d[.,]\d")

_NUMBER_PIECE = re.compile(r"\d+(?:[.,]\d+)?[^\W_]*|[^\W\d_][^\W_]*(?:'[^\W_]+)*|[.;!?,°&]")


def tokenize(text: str) -> Tokens:
    """Lower-case tokens of ``text``. Punctuation that separates clauses (``. , ; ! ? &``) is a
    token, other symbols are spaces; apostrophes are dropped ("let's" -> "lets": recognisers write
    both); number-unit runs are split ("1.5m"); hesitations ("um", "uh"; "mm" unless a number is
    before it: "500 mm") and immediate repeats ("the the") are removed; ing-forms of known verbs
    become the verb ("turning" -> "turn"). At most MAX_TOKENS tokens are read."""
    low = text.lower()
    if len(low) != len(text):  # a few characters change length in lower(): keep offsets right
        low = "".join(c.lower() if len(c.lower()) == 1 else c for c in text)
    if "-" in low or "–" in low or "—" in low:
        low = _BREAK_BEFORE_A_STOP.sub(";", low)
    if "." in low:
        low = _TITLE_DOT.sub(r"\1 ", low)  # "Dr. Okafor": no sentence ends after a title
    if "write" in low:
        low = _WRITE_AS_RIGHT.sub(r"\1right", low)  # "slide to the write": a recogniser's "right"
    if _DECIMAL.search(low):  # "1.5": the period is no separator here (rare: the slow way)
        pieces = _NUMBER_PIECE.findall(low.replace("’", "'").translate(_KEEP_POINTS))
    else:
        pieces = low.translate(_SEPARATE).split()
    toks: list[str] = []
    src: list[int] = []
    gerunds: list[int] = []
    last = ""
    words = pieces  # "pleeease", "stooop": a letter said long is the letter once (spans keep the pieces)
    if _ELONGATED.search(low):
        words = [_ELONGATED.sub(r"\1", p) if p.isalpha() else p for p in pieces]
    special = _SPECIAL
    contracted: list[int] = []
    for k, t in enumerate(words):
        if t in special or t == last or "'" in t or t[0] <= "9":
            out, kind = _special_piece(t, last)
            if not out:
                continue
            if kind:
                (gerunds if kind == _GERUND else contracted).append(len(toks) + len(out) - 1)
            toks += out
            src += (k,) * len(out)
            last = out[-1]
        else:
            toks.append(t)
            src.append(k)
            last = t
        if len(toks) >= MAX_TOKENS:
            return _once(Tokens(toks, src, pieces, low, k + 1, frozenset(gerunds), frozenset(contracted)))
    return _once(Tokens(toks, src, pieces, low, None, frozenset(gerunds), frozenset(contracted)))


_NEVER_FOLDED = _PAUSES | STOP_VERBS  # a stop said again is kept (see _special_piece); a pause ends a phrase


def _once(tokens: Tokens) -> Tokens:
    """``tokens`` with a phrase of two or three words said twice with no pause kept once: "keep
    going keep going a bit more", "go to go to the kitchen" (a speaker restarting, as "the the" is
    for one word). Said with a pause ("turn left, turn left") it is two steps and stays."""
    toks = tokens.toks
    drop: set[int] = set()
    k, end = 2, len(toks)
    while k < end:
        n = _repeat_before(toks, k)
        if n:
            drop.update(range(k, k + n))
            k += n
        else:
            k += 1
    if not drop:
        return tokens
    return tokens.kept([k for k in range(len(toks)) if k not in drop])


def _repeat_before(toks: list[str], k: int) -> int:
    """The length (2 or 3) of a phrase that ends just before ``k`` and is said again from ``k``;
    0 when none is, or when it holds a pause or a stop."""
    for n in (2, 3):
        if k >= n and k + n <= len(toks) and toks[k] == toks[k - n] and toks[k - n:k] == toks[k:k + n] \
                and _NEVER_FOLDED.isdisjoint(toks[k:k + n]):
            return n
    return 0


_GERUND, _CONTRACTED = 1, 2  # what a special piece was, besides its tokens


def _special_piece(t: str, last: str) -> tuple[tuple[str, ...], int]:
    """The tokens a piece that may need care becomes (none for a hesitation, a repeat, a lone
    apostrophe or a comma inside a phrase; a number and its unit; a contraction's words; the
    verb of an ing-form, with a pause before an exclamation), and what it was: ``_GERUND``
    (an ing-form), ``_CONTRACTED`` (a word with "'s" the lexicon does not split), else 0."""
    kind = 0
    if "'" in t:
        kind = _CONTRACTED if t.endswith("'s") else 0
        t = t.replace("'", "")
        if not t:
            return (), 0
    if t in DISFLUENCIES and not (t in UNITS and last and word_value(last) is not None):
        return (), 0  # "um"; but "500 mm" is a unit, not a hum
    if t == last and t not in HARD_STOPS and t != "," and t not in PLAIN_STOPS:
        return (), 0  # a stop said again is kept: over a plan it interrupts it ("... and stop stop stop")
    pause = _pause_at(t, last)
    if pause < 0:
        return (), 0
    before = (",",) if pause else ()
    c = t[0]
    if "0" <= c <= "9":
        um = _NUM_UNIT.match(t)
        if um and um.group(2) in UNITS:
            return (*before, um.group(1), um.group(2)), 0
    elif t in SPLITS:
        return (*before, *SPLITS[t]), 0
    elif t in GERUNDS:
        return (*before, GERUNDS[t]), _GERUND
    return (*before, t), kind



def _pause_at(t: str, last: str) -> int:
    """-1: the comma ``t`` is a hesitation inside a phrase ("go to the, um, bathroom": no phrase
    ends with "the"), dropped; 1: a pause belongs before ``t`` ("turn left oh never mind": the
    speaker broke off, as at a comma); 0: neither."""
    if t == ",":
        return -1 if last in HESITANT else 0
    return 1 if t in INTERRUPTING and last and last not in _PAUSES else 0


_ELONGATED = re.compile(r"([a-z])\1{2,}")  # no English word has a letter three times in a row

_KEEP_POINTS = str.maketrans({c: " " for c in "\"()[]{}<>*+=/|~^`@#$%:_-–—‐‑“”„«»…•·\t\n\r"})
