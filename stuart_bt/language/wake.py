"""The wake filter: is this utterance addressed to the robot, and what is the command after it?

Speech recognisers spell a name the way it sounds: "Hey Stuart" arrives as "hey stewart",
"a stuart", "hay steward", "hey stu art", "hey swart". So the name is compared by sound, not by
spelling: both sides are reduced to a phonetic key (a short skeleton of sound classes, see
:func:`phonetic_key`) and compared by a weighted edit distance in which losing a vowel sound
costs more than losing a consonant. That is what tells "swart" (the "u" glide kept, a "t" lost:
wakes) from "start" (the "u" lost: does not) although both are one letter away from "stuart".
The tolerance was tuned on tests/data/utterances/wake.jsonl.

Where the name may stand: at the start of the utterance, after optional filler ("um", "oh",
"so") and a greeting ("hey", "hi", "hello", "ok", "okay", ... and what recognisers make of them:
"hay", "a", "o k"). A name with no greeting wakes only when a pause follows it (a comma or other
punctuation, or nothing at all: "Stuart, stop!"), so "Stuart Little is a film" does not wake,
and neither does a name in the middle of a sentence ("I told Stuart to go"). The same holds for
a name after one word that is no known greeting but sounds like "hey": a greeting the recogniser
misheard ("case Stuart, stop"; not "tell Stuart, ...").
"""

from __future__ import annotations

import difflib
import itertools
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

# Greetings the robot answers to, and what recognisers write for them.
GREETINGS: tuple[str, ...] = ("hey", "hi", "hello", "ok", "okay", "yo", "hiya", "howdy", "excuse me", "good morning",
                              "good afternoon", "good evening", "morning", "afternoon", "evening")
GREETING_VARIANTS: dict[str, tuple[str, ...]] = {
    "hey": ("hay", "hei", "heh", "hej", "he", "eh", "a", "ay", "aye", "hay there"),
    "hi": ("hai", "high", "hy"),
    "hello": ("hallo", "hullo", "helo", "hollo"),
    "ok": ("okay", "o k", "oh kay", "okey", "okie", "kay"),
    "okay": ("ok", "o k", "oh kay", "okey", "okie", "kay"),
    "hiya": ("hiyah",),
}
# Words that may come before the greeting (or between it and the name) without changing anything.
FILLERS: frozenset[str] = frozenset({
    "um", "umm", "uh", "uhh", "uhm", "er", "erm", "ehm", "em", "hm", "hmm", "hmmm", "mm", "mmm",
    "ah", "ahh", "oh", "ooh", "so", "well", "yeah", "yes", "right", "alright", "now", "and", "but",
    "there", "dear", "please", "then",
    # exclamations and discourse words before the name ("oh wow, Stuart, ...", "um so like stuart ...")
    "wow", "like", "no", "oops", "yikes", "gosh", "oi", "aw", "aww", "listen",
    "actually", "anyway", "righto", "alrighty", "okey", "dokey",
    # thanks or praise before the name ("Thanks Stuart, you can go back to the dock now")
    "thanks", "cheers", "sorry", "great", "perfect", "brilliant", "excellent", "lovely", "cool", "nice",
})
_TOKEN = re.compile(r"[^\W_]+(?:['’][^\W_]+)*")
_PAUSE = frozenset(",.!?:;…-–—")
# every character that is neither a letter, a digit nor an apostrophe separates words
_SEPARATE = str.maketrans({**{chr(c): " " for c in range(128) if not chr(c).isalnum() and chr(c) != "'"},
                           **dict.fromkeys("’‘", "'"), **dict.fromkeys("…–—‐‑“”„«»•·¿¡", " "), "_": " "})
_STRIP = " \t\r\n,.!?:;…-–—\"'"  # between the wake phrase and the command
_LOOK_AHEAD = 9  # tokens read from an utterance: the wake phrase is always near the start
_LOOK_AHEAD_CHARS = 200

# -- the phonetic key --------------------------------------------------------------------------------
_DIGRAPHS: tuple[tuple[str, str], ...] = (
    ("tch", "ch"), ("sch", "sk"), ("ph", "f"), ("ck", "k"), ("gh", ""), ("kn", "n"), ("wr", "r"),
    ("wh", "w"), ("qu", "kw"), ("sh", "ʃ"), ("ch", "ʧ"), ("th", "t"),
    ("ew", "u"), ("oo", "u"), ("ou", "u"), ("eu", "u"),
    ("ce", "se"), ("ci", "si"), ("cy", "sy"),
)
_CLASSES = str.maketrans({
    **dict.fromkeys("aeioy", "A"), **dict.fromkeys("uw", "U"),
    **dict.fromkeys("bp", "P"), **dict.fromkeys("dt", "T"), **dict.fromkeys("cgkq", "K"),
    **dict.fromkeys("sz", "S"), **dict.fromkeys("fv", "F"), "x": "KS", "j": "J", "ʧ": "J",
    "ʃ": "C", "l": "L", "r": "R", "m": "M", "n": "N", "h": None, "'": None, "’": None,
})
_RUNS = re.compile(r"(.)\1+")
VOWELS = frozenset("AU")
VOWEL_INDEL, CONSONANT_INDEL, SUBSTITUTION = 1.0, 0.75, 1.0
DEFAULT_TOLERANCE = 0.8  # one consonant sound lost or added; tuned on wake.jsonl
SHORT_NAME_SPELLING = 0.7  # difflib ratio a heard word needs to a short name's spelling
# A word no greeting list holds may stand for "hey" before the name when it sounds like it: one
# consonant sound or two, the "ay" vowel (spelled a, ey or ei), and perhaps the s or t of the name
# glued on ("pay", "they", "case", "hate", "face": what a recogniser made of "hey Stuart" under
# noise or over the robot's voice); a pause must follow the name, as after a bare name.
# "tell Stuart, ...", "poor Stuart, ...", "is Stuart, ..." do not sound like "hey".
MISHEARD_GREETING_KEY = re.compile(r"[^AU]{0,2}A(?:[ST]A?)?")
MISHEARD_GREETING_VOWEL = re.compile(r"a|e[yi]")
MISHEARD_GREETING_COST = 0.5


def phonetic_key(word: str) -> str:
    """A sound skeleton of ``word``: vowels fold into two classes (A, and U for the rounded
    "oo"/"w" sounds), similar consonants into one letter, doubled sounds collapse.
    "stuart", "stewart", "steward", "stuert" and "stu art" all give ``STUART``."""
    w = word.lower()
    for a, b in _DIGRAPHS:
        if a in w:
            w = w.replace(a, b)
    return _RUNS.sub(r"\1", w.translate(_CLASSES))


def key_distance(a: str, b: str, cutoff: float = float("inf")) -> float:
    """Weighted edit distance between two phonetic keys: substitutions 1, a vowel sound in or
    out 1, a consonant sound in or out 0.75. Once every entry of a row exceeds ``cutoff`` the
    answer can only be larger, and that row's minimum is returned (a lower bound)."""
    if a == b:
        return 0.0
    prev = [0.0]
    for ch in b:
        prev.append(prev[-1] + (VOWEL_INDEL if ch in VOWELS else CONSONANT_INDEL))
    for ca in a:
        cost_a = VOWEL_INDEL if ca in VOWELS else CONSONANT_INDEL
        cur = [prev[0] + cost_a]
        for j, cb in enumerate(b, 1):
            cur.append(min(
                prev[j] + cost_a,
                cur[j - 1] + (VOWEL_INDEL if cb in VOWELS else CONSONANT_INDEL),
                prev[j - 1] + (0.0 if ca == cb else SUBSTITUTION),
            ))
        prev = cur
        low = min(cur)
        if low > cutoff:
            return low
    return prev[-1]


def default_tolerance(key: str) -> float:
    """How far a heard name may be from the name's key: one lost consonant for names of five or
    more sounds, an exact key below that (short names have too many neighbours; their spelling
    must also be close, see ``SHORT_NAME_SPELLING``)."""
    return DEFAULT_TOLERANCE if len(key) >= 5 else 0.0


# -- the filter --------------------------------------------------------------------------------------
@dataclass(slots=True)
class WakeMatch:
    """What the filter found. ``command`` is the text after the wake phrase as written (the
    punctuation and spaces between them removed, a final "?" kept); ``phrase`` is the wake phrase
    as written. (Not frozen: it is made once per utterance and a frozen dataclass costs a
    microsecond more to build.)"""

    woke: bool
    command: str = ""
    phrase: str = ""
    heard_name: str = ""
    distance: float = 0.0
    # the name alone, with no pause after it ("stuart go to the kitchen", as recognisers write
    # it): ``woke`` is False and ``command`` the rest; whether that rest is said to the robot is
    # for the grammar to judge (:meth:`stuart_bt.language.parse.Parser.wake_match`)
    unpaused: bool = False




class WakeFilter:
    """Decides whether an utterance starts with the robot's wake phrase.

    ``name`` is the robot's name; ``greetings`` the words that may open the wake phrase (their
    usual recogniser spellings are added, see ``GREETING_VARIANTS``); ``tolerance`` the largest
    phonetic distance at which a heard word still counts as the name (default:
    :func:`default_tolerance`); ``bare_name`` lets the name alone wake when a pause follows it.
    """

    def __init__(self, name: str = "Stuart", greetings: Iterable[str] = GREETINGS, *,
                 fillers: Iterable[str] = FILLERS, tolerance: float | None = None, bare_name: bool = True) -> None:
        words = [w.lower() for w in _TOKEN.findall(name)]
        if not words:
            raise ValueError(f"robot name {name!r} has no letters")
        self.name = name
        self.key = phonetic_key("".join(words))
        self.tolerance = default_tolerance(self.key) if tolerance is None else float(tolerance)
        self.bare_name = bare_name
        self.fillers = frozenset(f.lower() for f in fillers)
        self._greetings = _greeting_table(greetings)
        self._fused_greetings: dict[str, list[str]] = {}
        for g in sorted({g[0] for forms in self._greetings.values() for g in forms if len(g) == 1 and len(g[0]) >= 2},
                        key=len, reverse=True):
            self._fused_greetings.setdefault(g[0], []).append(g)
        self._max_span = len(words) + 2  # "hey stu art" is one name heard as two words
        self._spelling = "".join(words)
        self._name_chars = len(self._spelling)
        self._cache: dict[str, float] = {}

    def distance(self, heard: str) -> float:
        """Phonetic distance from ``heard`` (one word, or several run together) to the name."""
        d = self._cache.get(heard)
        if d is None:
            if len(self._cache) > 4096:
                self._cache.clear()
            key = phonetic_key(heard)
            # every sound in or out costs at least CONSONANT_INDEL: a length gap alone can rule a
            # word out without the distance table
            gap = abs(len(key) - len(self.key)) * CONSONANT_INDEL
            d = 99.0 if gap > self.tolerance else key_distance(key, self.key, self.tolerance)
            if d <= self.tolerance and len(self.key) < 5 and heard != self._spelling and difflib.SequenceMatcher(
                    None, heard, self._spelling).ratio() < SHORT_NAME_SPELLING:
                d = 99.0  # short keys have many neighbours ("max", "mix"): the spelling must agree too
            self._cache[heard] = d
        return d

    def match(self, utterance: str) -> WakeMatch:
        """The wake phrase at the start of ``utterance`` and the command after it, or the name
        at its end after a pause ("To the kitchen, Stuart!") and the command before it, or a
        match with ``woke`` False."""
        found = self._at_start(utterance)
        if found.woke or found.unpaused:
            return found
        return self._at_end(utterance) or found

    def _at_end(self, utterance: str) -> WakeMatch | None:
        """The name as the last words, after a pause: the whole sentence before it was said to
        the robot ("Would you mind picking up the cup, Stuart?"). Its final "?" is kept."""
        body = utterance.rstrip(_STRIP)
        cut = max(body.rfind(c, max(0, len(body) - _LOOK_AHEAD_CHARS)) for c in _PAUSE)  # the last pause
        words = [w.lower() for w in _TOKEN.findall(body, cut + 1)] if cut > 0 else []
        if not words or len(words) > self._max_span or not _TOKEN.search(body, 0, cut):
            return None
        d = self.distance("".join(words))
        if d > self.tolerance:
            return None
        question = "?" if utterance.rstrip().endswith("?") else ""
        return WakeMatch(True, body[:cut].lstrip(_STRIP).rstrip(_STRIP) + question, body[cut + 1:].strip(),
                         " ".join(words), d)

    def _at_start(self, utterance: str) -> WakeMatch:
        head = utterance[:_LOOK_AHEAD_CHARS]
        low = head.lower()
        if len(low) != len(head):  # lower() changed a length: the slow, exact way
            found = list(itertools.islice(_TOKEN.finditer(head), _LOOK_AHEAD))
            toks = [m.group().lower() for m in found]
            offsets = [m.start() for m in found]
        else:
            spaced = low.translate(_SEPARATE)  # one character for one: offsets stay right
            toks = [t.strip("'") for t in spaced.split()[:_LOOK_AHEAD]]
            offsets = None  # found when needed: most utterances never wake
        if not toks:
            return WakeMatch(False)
        i, greeted = self._skip_openers(toks)
        if i >= len(toks):
            return WakeMatch(False)
        span = self._name_at(toks, i)
        if span is None and not greeted:
            span = self._fused(toks[i])  # "heystuart": greeting and name run together
            greeted = span is not None
        misheard = False
        if span is None and not greeted and _sounds_like_hey(toks[i]):
            span = self._name_at(toks, i + 1)  # "case Stuart, stop": a greeting misheard; a pause must follow
            if span is not None:
                span = (span[0] + 1, span[1] + MISHEARD_GREETING_COST)
                misheard = True
        if span is None:
            return WakeMatch(False)
        k, dist = span
        # "stuart stuart give me a high five": a name said twice is said once (as it was heard
        # the first time: no distance to work out for every other word)
        said, length = toks[i:i + k], k
        while toks[i + k:i + k + length] == said:
            k += length
        if offsets is None:
            offsets, pos = [], 0
            for t in toks[:i + k]:  # where each word starts in the utterance
                pos = spaced.find(t, pos) if t else pos
                offsets.append(pos)
                pos += len(t)
        end = offsets[i + k - 1] + len(toks[i + k - 1])
        rest = utterance[end:]
        if not greeted:
            after = rest.lstrip(" \t")
            term = _ADDRESS.match(after)  # "Stuart mate, ...": a term of address belongs to the name
            if term and term.end() < len(after) and after[term.end()] in _PAUSE:
                rest, after = after[term.end():], after[term.end():]
            if not self.bare_name:
                return WakeMatch(False)
            if after and after[0] not in _PAUSE:
                return WakeMatch(False, rest.lstrip(_STRIP).rstrip(), utterance[offsets[0]:end],
                                 " ".join(toks[i:i + k]), dist, unpaused=not misheard)
        heard = " ".join(toks[i:i + k])
        return WakeMatch(True, rest.lstrip(_STRIP).rstrip(), utterance[offsets[0]:end], heard, dist)

    def _skip_openers(self, toks: Sequence[str]) -> tuple[int, bool]:
        """Index after fillers and greetings ("um", "oh hey there", "ok so hey"), and whether a
        greeting was among them."""
        i, greeted, n = 0, False, len(toks)
        for _ in range(8):
            while i < n and toks[i] in self.fillers:
                i += 1
            if i >= n:
                break
            for g in self._greetings.get(toks[i], ()):
                if len(g) == 1 or tuple(toks[i:i + len(g)]) == g:
                    i += len(g)
                    greeted = True
                    break
            else:
                break
        return i, greeted

    def _fused(self, tok: str) -> tuple[int, float] | None:
        """(1, distance) when ``tok`` is a one-word greeting with the name glued on."""
        for g in self._fused_greetings.get(tok[:1], ()):
            if tok.startswith(g) and len(tok) > len(g) + 2:
                d = self.distance(tok[len(g):])
                if d <= self.tolerance:
                    return 1, d
        return None

    def _name_at(self, toks: Sequence[str], i: int) -> tuple[int, float] | None:
        """(number of tokens, distance) of the best name reading at ``toks[i]``: one word, or up
        to ``len(name words) + 2`` words run together; the fewest words win a tie."""
        best: tuple[int, float] | None = None
        heard = ""
        for k in range(1, self._max_span + 1):
            if i + k > len(toks):
                break
            heard += toks[i + k - 1]
            if len(heard) > 2 * self._name_chars + 2:
                break
            d = self.distance(heard)
            if d <= self.tolerance and (best is None or d < best[1]):
                best = (k, d)
                if d == 0.0:
                    break  # nothing longer can beat an exact sound match
        return best


# terms of address said right after the name, before the pause ("Stuart mate, ...", "Stuart, buddy")
_ADDRESS = re.compile(r"(?:mate|buddy|pal|my friend|old chap|old friend|my man|dear|bro|dude|sir|man)(?=\W)",
                      re.IGNORECASE)


def _sounds_like_hey(word: str) -> bool:
    """Could a recogniser have written ``word`` for "hey" (with the name's first sound glued on)?"""
    return bool(MISHEARD_GREETING_KEY.fullmatch(phonetic_key(word)) and MISHEARD_GREETING_VOWEL.search(word))


def _greeting_table(greetings: Iterable[str]) -> dict[str, tuple[tuple[str, ...], ...]]:
    """Every greeting and its recogniser variants as token tuples, by first word, longest first."""
    table: set[tuple[str, ...]] = set()
    for g in greetings:
        g = g.lower().strip()
        for form in (g, *GREETING_VARIANTS.get(g, ())):
            words = tuple(w.lower() for w in _TOKEN.findall(form))
            if words:
                table.add(words)
    by_first: dict[str, list[tuple[str, ...]]] = {}
    for words in sorted(table, key=lambda t: (-len(t), t)):
        by_first.setdefault(words[0], []).append(words)
    return {first: tuple(forms) for first, forms in by_first.items()}
