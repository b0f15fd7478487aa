"""The wake phrase heard as words that sound like it: a repaired reading for whisper to judge.

Under noise, a small recogniser loses the wake phrase first: the breathy "h" and the "st" of
"Hey Stuart" sit where white noise is loudest, and what is left is heard as common words with
the same vowels and rhythm: "face to it", "case you", "taste you at", "face to earth". The rest
of the command is often heard right ("face to earth, go to the workbench and give me a hug").
On the hearing benchmark at 10 dB SNR most commands lost this way (docs/hearing.md).

The repair offers the reading with the wake phrase put back ("hey Stuart, go to the workbench
and give me a hug") when all of these hold:

1. nothing in the reading is the robot's name already (the wake filter reads names itself);
2. the opening words are not a greeting heard as one ("hey Steve, ..."): when the greeting was
   heard right, the name after it was most likely heard right too, and it is someone else's;
3. no opening word is written with a capital: whisper writes a name it heard as a name
   ("Stacey, go to the kitchen" is said to Stacey);
4. the opening (one to :data:`MOST_HEAD_WORDS` words, never past the first pause) sounds like
   the wake phrase or the bare name: a weighted distance between their phones (the grammar
   engine's pronouncing dictionary) of at most :data:`SOUND_TOLERANCE` per phone of the phrase.

Whether it is believed is whisper's call, as for the grammar engine's corrections
(:mod:`.second_opinion`): whisper scores the repaired reading against the same sound, and it
is taken only when it trails whisper's own by at most ``REPAIR_MARGIN`` there. The sound test
alone does not tell "hey Stephen" from "hey Stuart" (measured: both within 0.4 per token), which
is why rules 2 and 3 come first.
"""

from __future__ import annotations

from collections.abc import Callable

from .command_grammar import GREETINGS, spoken

Pronounce = Callable[[str], "list[str]"]  # a word -> its pronunciations (ARPAbet, space separated), or none

MOST_HEAD_WORDS = 3  # "face to earth," / "taste you at,": the wake phrase is heard as at most three words
# Largest distance per phone of the wake phrase at which an opening still sounds like it.
# Measured (docs/hearing.md): the openings heard for "hey Stuart" at 10 dB SNR were 0.21-0.57
# from it ("case to it" 0.21, "face to" 0.36, "thanks to it" 0.5); everyday openings are
# further ("okay team" 0.79, "in case you" 0.86, "listen everyone" 1.36).
SOUND_TOLERANCE = 0.5
# a name heard within this distance a phone of the robot's is the robot's: "stewart" (0), "steward"
# (0.1); "Steve" (0.5) and "Stan" are not
SAME_NAME_TOLERANCE = 0.2
MOST_SAYINGS = 8  # pronunciations of one phrase compared (the dictionary gives up to three a word)
_PAUSES = ",.;:!?"

# ARPAbet phones in classes that are confused with each other: a phone for another of its
# class costs half a substitution
_PHONE_CLASSES = (
    "AA AE AH AO AW AY EH ER EY IH IY OW OY UH UW",  # vowels
    "P B T D K G",  # stops
    "F V TH DH S Z SH ZH HH",  # fricatives
    "CH JH",  # affricates
    "M N NG",  # nasals
    "L R W Y",  # liquids and glides
)
_CLASS_OF = {phone: n for n, phones in enumerate(_PHONE_CLASSES) for phone in phones.split()}
# A breathy "h" is the first sound noise takes: in, out or heard as another sound it costs half
# ("hey" heard as "face", "case", "taste")
_WEAK = frozenset({"HH"})


def phone_distance(a: list[str], b: list[str]) -> float:
    """Weighted edit distance between two phone sequences: a phone in or out costs 1, one for
    another of its class 0.5 ("T" for "D", "IH" for "ER"), any other 1; an "h" half of that."""
    def indel(phone: str) -> float:
        return 0.5 if phone in _WEAK else 1.0

    def swap(pa: str, pb: str) -> float:
        if pa == pb:
            return 0.0
        return 0.5 if pa in _WEAK or pb in _WEAK or _CLASS_OF.get(pa, -1) == _CLASS_OF.get(pb, -2) else 1.0

    previous = [0.0]
    for phone in b:
        previous.append(previous[-1] + indel(phone))
    for pa in a:
        row = [previous[0] + indel(pa)]
        for j, pb in enumerate(b, 1):
            row.append(min(previous[j] + indel(pa), row[j - 1] + indel(pb), previous[j - 1] + swap(pa, pb)))
        previous = row
    return previous[-1]


def wake_repaired(text: str, name: str, pronounce: Pronounce) -> str | None:
    """``text`` with its opening words replaced by "hey <name>," when they sound like the wake
    phrase and may be it (the module docstring's rules 1-4), else None."""
    words = text.split()
    keys = [" ".join(spoken(w)) for w in words]
    if name.lower() in keys or not keys or keys[0] in GREETINGS:
        return None
    targets = [*_phones(f"hey {name}", pronounce), *_phones(name, pronounce)]
    best: tuple[float, int] | None = None
    for k in range(1, min(MOST_HEAD_WORDS, len(words) - 1) + 1):
        word = words[k - 1]
        if any(c.isupper() for c in word):
            break
        heard = _phones(" ".join(words[:k]), pronounce)
        if heard and targets:
            d = min(phone_distance(h, t) / len(t) for h in heard for t in targets)
            if d <= SOUND_TOLERANCE and (best is None or d < best[0]):
                best = (d, k)
        if word.endswith(tuple(_PAUSES)):
            break
    if best is None:
        return None
    rest = " ".join(words[best[1]:]).lstrip(_PAUSES + " ")
    return f"hey {name}, {rest}" if rest else None


def said_to_someone_else(text: str, name: str, pronounce: Pronounce) -> bool:
    """Did whisper hear someone other than the robot addressed: a greeting and a name written
    as a name ("hey Steve, ...", "Hi Sarah ..."), or a name alone before a pause ("Stacey, go to
    the kitchen")? Then no engine's correction may make it the robot's name: the prompt and the
    grammar engine both lean to "Stuart", and "hey Steve" trailed "hey Stuart" by only 0.74 per
    token in whisper's own score (docs/hearing.md). The robot's name spelled another way
    ("Stewart", "Steward") is the robot's."""
    words = text.split()
    keys = [" ".join(spoken(w)) for w in words[:2]]
    at = 1 if keys and keys[0] in GREETINGS else 0
    if at >= len(words) or not words[at][:1].isupper() or not (at == 1 or words[at].endswith(tuple(_PAUSES))):
        return False
    return keys[at] not in _OPENING_WORDS and not _sounds_like(keys[at], name, pronounce)


def names_the_robot(text: str, name: str, pronounce: Pronounce) -> bool:
    """Whether a word of ``text`` is the robot's ``name``, however spelled ("Stewart", "steward")."""
    keys = (" ".join(spoken(word)) for word in text.split())
    return any(_sounds_like(key, name, pronounce) for key in keys if key)


# words a sentence often opens with before a pause, written with a capital for that alone
_OPENING_WORDS = frozenset({"sorry", "right", "please", "yes", "yeah", "no", "well", "so", "now", "wait", "thanks",
                            "alright", "listen", "look", "actually", "oh", "um", "uh", "great", "good", "cool", "sure",
                            "first", "then", "next", "and", "but", "also", "again", "quick", "quickly"})


def _sounds_like(word: str, name: str, pronounce: Pronounce) -> bool:
    """Whether ``word`` is ``name`` by its phones, within :data:`SAME_NAME_TOLERANCE` a phone."""
    if word == name.lower():
        return True
    heard, meant = _phones(word, pronounce), _phones(name, pronounce)
    return any(phone_distance(h, m) <= SAME_NAME_TOLERANCE * len(m) for h in heard for m in meant)


def _phones(phrase: str, pronounce: Pronounce) -> list[list[str]]:
    """Every way of saying ``phrase`` (each word in each of its pronunciations, at most
    :data:`MOST_SAYINGS`: "stuart" is S T UW ER T, S T Y UW ER T or S T AO R T); none when a word
    has no pronunciation."""
    sayings: list[list[str]] = [[]]
    for word in spoken(phrase):
        ways = pronounce(word)
        if not ways:
            return []
        sayings = [s + way.split() for s in sayings for way in ways][:MOST_SAYINGS]
    return sayings
