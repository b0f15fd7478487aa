"""Whisper with a command-only grammar engine as a second opinion (engine ``whisper+grammar``).

Whisper hears anything, so it hears talk as talk, but it sometimes hears a command as something
near it ("Hey Stuart, then turn around" as "hey Stuart, and enter around"; the wake phrase as
"head to it"). The grammar engine (:mod:`.sphinx`) hears only commands, so it hears those right,
and hears talk as some command too. Each covers the other's blind side this way:

1. whisper hears the utterance; when it heard someone else addressed ("hey Steve, ...",
   :func:`.wake_repair.said_to_someone_else`), nothing corrects it; when its opening sounds like
   the wake phrase and may be it ("face to earth, go to ..."), the reading with the wake phrase
   put back is scored as in step 3 and taken within :data:`REPAIR_MARGIN` (:mod:`.wake_repair`);
   when one of its readings is a sentence of the command grammar
   (:func:`.command_grammar.matcher`), the two engines could not disagree about its form and
   whisper's transcript is used as it is;
2. otherwise the grammar engine hears it, and its words are put into whisper's reading where
   the two differ (:func:`splice`: whisper's spelling, case and punctuation are kept);
3. whisper scores that corrected sentence against the same sound (forced decoding with the same
   prompt, :meth:`~.recognisers.WhisperRecogniser.score`), and its own best reading too: the
   difference puts the correction on the scale of whisper's readings;
4. a correction that trails whisper's best by at most :data:`CORRECTION_MARGIN` is the reading
   heard (first, whisper's readings after it, whisper's belief in its words as the confidence);
   one that trails by more is kept as the last reading, where nothing acts on it.

Which reading is acted on, and whether to ask, is then decided where it always is
(:mod:`stuart_bt.language.readings`, the confidence floor), so a correction whisper itself finds
much less likely than what it heard is never taken: talk, which the grammar engine turns into a
command, is heard by whisper as talk, and the forced command scores far below it (measured:
docs/hearing.md).
"""

from __future__ import annotations

import difflib
import itertools
import math
import re
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from .command_grammar import as_digits, matcher, normalise, spoken
from .pipeline import is_speech
from .recognisers import WINDOW_S, Transcript, WhisperRecogniser
from .sphinx import GrammarRecogniser
from .vocabulary import Vocabulary
from .wake_repair import names_the_robot, said_to_someone_else, wake_repaired

if TYPE_CHECKING:
    import numpy as np

# How much less likely per token (average log probability) than whisper's own best reading a
# grammar engine's correction may be and still be the reading heard. Measured on the hearing
# benchmark (docs/hearing.md): corrections of misheard commands trailed by 0.05-0.53 clean and
# mostly under 1 at 10 dB SNR; the commands the grammar engine made of talk trailed by 3.3 or
# more clean and 1.5 or more in noise. A correction that trails by more stays a reading, last.
CORRECTION_MARGIN = 0.75
# The same for a reading with the wake phrase put back (:mod:`.wake_repair`): its other words are
# whisper's own, so it must come closer. Measured at 10 dB SNR (docs/hearing.md): the wake phrase
# put back where it was said trailed by 0.03-0.6; "hey Stephen, ..." and "hey Steve, ..." said
# to someone else, were they not ruled out before, trailed by 0.37-0.74.
REPAIR_MARGIN = 0.5
# Most places where whisper and the grammar engine differ whose every choice is tried (2^5 - 1
# splices at most, of which only the sentences of the command grammar are scored)
MOST_PLACES = 5
# How far behind the reading heard another may be and still be acted on: the language stage's
# READING_MARGIN (stuart_bt.language.readings; hearing comes before language and imports none of it)
COMMAND_MARGIN = 0.15


class SecondOpinion:
    """``whisper+grammar``: :class:`~.recognisers.WhisperRecogniser` with
    :class:`~.sphinx.GrammarRecogniser` as a second opinion (module docstring)."""

    name = "whisper+grammar"

    def __init__(self, **whisper_options: Any) -> None:
        self.whisper = WhisperRecogniser(**whisper_options)
        self.grammar = GrammarRecogniser()
        self._matchers: dict[Vocabulary, re.Pattern[str]] = {}

    def transcribe(self, samples: np.ndarray, vocabulary: Vocabulary | None = None) -> Transcript:
        heard = self.whisper.transcribe(samples, vocabulary)
        if (vocabulary is None or not is_speech(heard) or heard.audio_s > WINDOW_S
                or said_to_someone_else(heard.text, vocabulary.name, self.grammar.pronunciations)):
            return replace(heard, engine=self.name)
        own = heard.avg_logprob  # whisper's belief in its own best reading: every correction is held to it
        heard = self._wake_repaired(heard, vocabulary)
        if self._in_grammar(heard, vocabulary):
            return replace(heard, engine=self.name)
        command = self.grammar.hear(samples, vocabulary)
        heard_already = {text for text, _ in heard.readings()}
        corrections = [c for c in self._corrections(heard.text, command, vocabulary) if c not in heard_already]
        if not corrections:
            return replace(heard, engine=self.name, seconds=heard.seconds + self.grammar.seconds)
        score, corrected = max(zip(self._scores(heard, corrections, vocabulary), corrections, strict=True))
        seconds = heard.seconds + self.grammar.seconds + self.whisper.last_score_s
        if own - score > self._margin(heard.text, corrected, vocabulary):  # far less likely: kept, never first
            ranked = sorted([*heard.alternatives, (corrected, score)], key=lambda r: -r[1])
            return replace(heard, engine=self.name, alternatives=tuple(ranked), seconds=seconds)
        return replace(_heard_as(heard, corrected, score, seconds), engine=self.name)

    def _wake_repaired(self, heard: Transcript, vocabulary: Vocabulary) -> Transcript:
        """``heard`` with the wake phrase put back (:mod:`.wake_repair`) when whisper finds that
        reading at most :data:`REPAIR_MARGIN` less likely than its own; else ``heard`` (with
        the time the scoring took)."""
        repaired = wake_repaired(heard.text, vocabulary.name, self.grammar.pronunciations)
        if repaired is None:
            return heard
        score = self._score(heard, repaired, vocabulary)
        seconds = heard.seconds + self.whisper.last_score_s
        if heard.avg_logprob - score > REPAIR_MARGIN:
            return replace(heard, seconds=seconds)
        return _heard_as(heard, repaired, score, seconds)

    def _corrections(self, heard: str, command: list[str], vocabulary: Vocabulary) -> list[str]:
        """The sentences of the command grammar made of whisper's ``heard`` with some or all of
        the grammar engine's words put in (:func:`splices`), the whole correction last in any case."""
        if not command:
            return []
        pattern = self._matcher(vocabulary)
        whole = splice(heard, command, vocabulary)
        return [*(c for c in splices(heard, command, vocabulary) if c != whole and pattern.fullmatch(normalise(c))),
                whole]

    def _score(self, heard: Transcript, text: str, vocabulary: Vocabulary) -> float:
        """Whisper's average log probability of ``text`` against the sound it heard as
        ``heard``, on the scale of ``heard``'s own readings (forced decoding of both)."""
        return self._scores(heard, [text], vocabulary)[0]

    def _scores(self, heard: Transcript, texts: list[str], vocabulary: Vocabulary) -> list[float]:
        """:meth:`_score` of each of ``texts``, ``heard`` forced once for all."""
        *ours, theirs = self.whisper.score([*texts, heard.text], vocabulary)
        return [round(heard.avg_logprob + score - theirs, 4) for score in ours]

    def _margin(self, heard: str, corrected: str, vocabulary: Vocabulary) -> float:
        """How far behind whisper's own reading ``corrected`` may be and still be heard: a
        correction that names the robot where whisper heard no name of it puts the wake phrase
        back, and is held to the wake repair's :data:`REPAIR_MARGIN` ("Hey Stan, go to the
        station 3", heard as "face 10, ...", was "hey Stuart, ..." to the grammar engine, 0.55
        behind); any other to :data:`CORRECTION_MARGIN`."""
        sounds = self.grammar.pronunciations
        if names_the_robot(corrected, vocabulary.name, sounds) and not names_the_robot(heard, vocabulary.name, sounds):
            return REPAIR_MARGIN
        return CORRECTION_MARGIN

    def _matcher(self, vocabulary: Vocabulary) -> re.Pattern[str]:
        pattern = self._matchers.get(vocabulary)
        if pattern is None:
            pattern = self._matchers[vocabulary] = matcher(vocabulary)
        return pattern

    def _in_grammar(self, heard: Transcript, vocabulary: Vocabulary, margin: float = math.inf) -> bool:
        """Whether a reading at most ``margin`` behind the one heard is a sentence of the command grammar."""
        pattern = self._matcher(vocabulary)
        least = heard.avg_logprob - margin
        return any(score >= least and pattern.fullmatch(normalise(text)) for text, score in heard.readings())

    def heard_as_command(self, heard: Transcript, vocabulary: Vocabulary) -> bool:
        """Whether a reading the robot may act on is a sentence of the command grammar: the one
        heard, or one within :data:`COMMAND_MARGIN` of it (a correction kept last, far behind,
        is none). :func:`~.pipeline.transcribe` hears an utterance again when this is False."""
        return self._in_grammar(heard, vocabulary, COMMAND_MARGIN)


def _heard_as(heard: Transcript, text: str, score: float, seconds: float) -> Transcript:
    """``heard`` with ``text`` (scored ``score``) as the reading heard, whisper's own readings
    after it, and whisper's belief in those words as the confidence."""
    return replace(heard, text=text, avg_logprob=score, confidence=math.exp(score) * (1.0 - heard.no_speech),
                   alternatives=((heard.text, round(heard.avg_logprob, 4)), *heard.alternatives), seconds=seconds)


def splice(heard: str, command: list[str], vocabulary: Vocabulary) -> str:
    """``heard`` (a general recogniser's text) with the words of ``command`` (the grammar
    engine's tokens) where the two differ: words both heard keep ``heard``'s spelling, case and
    punctuation, amounts are written in digits as in ``heard``, the robot's name and the lab's
    words as the vocabulary writes them ("Stuart", "3D"), with a comma after the name (the wake
    filter reads a bare name as a vocative only so); "hey Stuart, and enter around." with "hey
    stuart and then turn around" -> "hey Stuart, and then turn around.". With ``heard`` empty,
    the command as the grammar engine writes it."""
    surface = heard.split()
    keys = [" ".join(spoken(s)) for s in surface]
    ours = as_digits(command)
    return _spliced(surface, ours, _differences(keys, ours), vocabulary)


def splices(heard: str, command: list[str], vocabulary: Vocabulary) -> list[str]:
    """:func:`splice` with each choice of the places where the two differ, one or more: the
    grammar engine hears only commands, so in noise it may hear more than was said ("... the
    charging dock and give me a hand" as "... and give me a heart and halt") and be right in one
    place only. A place where the two name different things ("bottle" and "book", "90" and
    "19") is in every choice: whisper's word there is never kept against the other's, so the
    correction is whole there or not at all. Words put for as many words are a place each ("face
    user go" for "hey stuart come": the wake phrase may be the grammar engine's and the verb
    whisper's). At most :data:`MOST_PLACES` places (else the whole splice alone)."""
    surface = heard.split()
    keys = [" ".join(spoken(s)) for s in surface]
    ours = as_digits(command)
    opcodes = _word_by_word(_differences(keys, ours))
    places = [k for k, op in enumerate(opcodes) if op[0] != "equal"]
    if len(places) > MOST_PLACES:
        return [_spliced(surface, ours, opcodes, vocabulary)]
    naming = _naming_words(vocabulary)
    must = {k for k in places if opcodes[k][0] == "replace" and any(  # where the two name different things
        w in naming or w[:1].isdigit() for w in ours[opcodes[k][3]:opcodes[k][4]])}
    out: dict[str, None] = {}
    for size in range(1, len(places) + 1):
        for chosen in itertools.combinations(places, size):
            if not must.issubset(chosen):
                continue
            kept = [op if k in chosen or op[0] == "equal" else ("equal", op[1], op[2], op[1], op[1])
                    for k, op in enumerate(opcodes)]
            out[_spliced(surface, ours, kept, vocabulary)] = None
    return list(out)


Opcode = tuple[str, int, int, int, int]


def _naming_words(vocabulary: Vocabulary) -> frozenset[str]:
    """The words that name a place, object or gesture, as the grammar engine writes them."""
    phrases = (*vocabulary.places, *vocabulary.objects, *vocabulary.gestures)
    return frozenset(w for p in phrases for w in spoken(p)) - _FUNCTION_WORDS


_FUNCTION_WORDS = frozenset({"the", "a", "an", "of", "to", "and", "my", "your", "me", "up"})


def _differences(keys: list[str], ours: list[str]) -> list[Opcode]:
    """Where whisper's words (as spoken keys) and the grammar engine's agree and differ."""
    return [(op, a0, a1, b0, b1) for op, a0, a1, b0, b1 in
            difflib.SequenceMatcher(a=keys, b=ours, autojunk=False).get_opcodes()]


def _word_by_word(opcodes: list[Opcode]) -> list[Opcode]:
    """``opcodes`` with each replacement of n words by n words split into n replacements of one:
    difflib joins neighbouring differences into one, though each may be right on its own."""
    out: list[Opcode] = []
    for op, a0, a1, b0, b1 in opcodes:
        if op == "replace" and a1 - a0 == b1 - b0 > 1:
            out += [("replace", a0 + n, a0 + n + 1, b0 + n, b0 + n + 1) for n in range(a1 - a0)]
        else:
            out.append((op, a0, a1, b0, b1))
    return out


def _spliced(surface: list[str], ours: list[str], opcodes: list[Opcode], vocabulary: Vocabulary) -> str:
    """``surface`` (whisper's words) with ``ours`` put in where ``opcodes`` say they differ."""
    out: list[str] = []
    for op, a0, a1, b0, b1 in opcodes:
        if op == "equal":
            out += surface[a0:a1]
            continue
        words = [_written(w, vocabulary) for w in ours[b0:b1]]
        if words and a1 > a0:
            words[-1] += _trailing(surface[a1 - 1])  # "it," -> "Stuart,"
        elif words and out and a0 == len(surface) and (end := _trailing(out[-1])):
            out[-1], words[-1] = out[-1][:-len(end)], words[-1] + end  # "... screwdriver now."
        out += words
    name = vocabulary.name.lower()
    for n, word in enumerate(out):
        if " ".join(spoken(word)) == name:
            out[n] = word if _trailing(word) else word + ","  # "Stuart, go ...": the name is a vocative
            break
    text = " ".join(out)
    if surface and surface[0][:1].isupper() and text:
        text = text[0].upper() + text[1:]
    return text


def _trailing(token: str) -> str:
    """The punctuation a written word ends with ("it," -> ",")."""
    end = len(token)
    while end > 0 and not token[end - 1].isalnum():
        end -= 1
    return token[end:]


def _written(token: str, vocabulary: Vocabulary) -> str:
    """A grammar token as the vocabulary writes it: the robot's name and words with capitals
    inside or digits ("3D") as given, any other word in lower case."""
    if token == vocabulary.name.lower():
        return vocabulary.name
    for phrase in (*vocabulary.places, *vocabulary.objects, *vocabulary.gestures, *vocabulary.extra):
        for word in phrase.split():
            if word.lower() == token and (word[1:] != word[1:].lower() or any(c.isdigit() for c in word)):
                return word
    return token
