"""An utterance, start to end: wake filter, then grammar, then one result.

This is the contract the CLI prints and other programs script against::

    {"utterance": str, "wake": bool, "command": str, "intents": [TaskIntent...], "conversational": bool,
     "coverage": {"used": [str], "unused": [str], "talk": [str], "unread": str},
     "doubt": [{"reason": str, "detail": str}]}

- no wake phrase: ``wake`` false, ``command`` "", ``intents`` [], ``conversational`` false (the
  robot was not spoken to, so there is nothing to answer either);
- wake phrase and no command in what follows: ``conversational`` true (the text goes to the
  conversation side: "Hey Stuart, what can you pick up?");
- ``command`` is the text after the wake phrase, as written, less any part said to someone
  else in the room ("..., Anna, can you follow him?", :mod:`.asides`);
- ``coverage``: which words of ``command`` the intents came from, which content words no clause
  used, which were conversation, and any text past the length limit (never read);
- ``doubt``: why the robot should ask before acting on ``intents`` (:mod:`.doubt`); empty for a
  clear command, for a stop, and when there are no intents.

Resolution against the map and the object labels is a separate step
(:mod:`stuart_bt.language.resolve`): a parse never needs a map, and the same parse can be
resolved against whichever map the robot is on.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from ..core.jsonfile import to_json
from .asides import said_to_the_robot, turned_to_the_robot
from .doubt import Doubt, Limits, doubts
from .grammar import Coverage, Defaults, Grammar, coverage
from .grammar.driver import TALK, Reading
from .grammar.lexicon import AUX, MODALS, SUBJECTS, WH
from .intents import STOP, TaskIntent
from .wake import GREETINGS, WakeFilter, WakeMatch


@dataclass
class ParseResult:
    """What one utterance means to the robot."""

    utterance: str
    wake: bool = False
    command: str = ""
    intents: list[TaskIntent] = field(default_factory=list)
    conversational: bool = False
    coverage: Coverage = field(default_factory=Coverage)
    doubt: list[Doubt] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        return {"utterance": self.utterance, "wake": self.wake, "command": self.command,
                "intents": [i.to_dict() for i in self.intents], "conversational": self.conversational,
                "coverage": self.coverage.to_dict(), "doubt": [d.to_dict() for d in self.doubt]}

    def to_json(self) -> str:
        return to_json(self.to_dict(), ensure_ascii=False)


class Parser:
    """Wake filter + grammar with one robot name. ``require_wake=False`` parses every utterance as
    a command (a typed console, where nobody says "Hey Stuart"); ``wake`` is then reported as
    found or not, but does not gate the grammar."""

    def __init__(self, name: str = "Stuart", greetings: Iterable[str] = GREETINGS, *,
                 wake_filter: WakeFilter | None = None, grammar: Grammar | None = None,
                 defaults: Defaults | None = None, require_wake: bool = True, limits: Limits | None = None) -> None:
        self.wake_filter = wake_filter or WakeFilter(name, greetings)
        self.vocatives = [w for w in self.wake_filter.name.lower().split() if w]
        self.grammar = grammar or Grammar(defaults=defaults, vocatives=self.vocatives)
        self.require_wake = require_wake
        self.limits = limits or Limits()
        # the reading that decided an unpaused name's wake, kept for the one read of the same text
        # as the command that follows (one tuple, replaced whole: safe to share between threads)
        self._kept: tuple[str, Reading] | None = None

    def wake_match(self, utterance: str) -> WakeMatch:
        """The wake filter's verdict, with one judgement only the grammar can make: the name
        alone with no pause after it ("stuart go to the kitchen", as a recogniser writes it)
        wakes when what follows is said to the robot: a command that does not open as talk, or a
        question to it ("stuart what can you do"), or a stop anywhere in it ("stuart you're late
        so just stop": stopping is always safe), never a sentence about it ("stuart went to the
        kitchen", "stuart is in the kitchen")."""
        wake = self.wake_filter.match(utterance)
        if wake.unpaused and self._said_to_the_robot(wake.command):
            wake.woke = True
        elif not wake.woke and not wake.unpaused:
            return self._name_last(utterance) or wake
        return wake

    def _name_last(self, utterance: str) -> WakeMatch | None:
        """The name as the last word with no pause before it, after a request to the robot
        ("could you clap for us stuart", as recognisers write it): a wake when the words before
        it are said to the robot (as for the name first with no pause after it), and the word
        just before the name is no preposition ("wave to stuart" is about it)."""
        words = utterance.rstrip(_END).rsplit(maxsplit=2)
        if len(words) < 3 or words[-2].lower() in _ABOUT_IT or not self._is_name(words[-1].lower()):
            return None
        rest = utterance.rstrip(_END)[:-len(words[-1])].rstrip(" ,")
        if not self._said_to_the_robot(rest):
            return None
        return WakeMatch(True, rest + ("?" if utterance.rstrip().endswith("?") else ""), words[-1], words[-1].lower(),
                         self.wake_filter.distance(words[-1].lower()))

    def _said_to_the_robot(self, rest: str) -> bool:
        reading = self.grammar.read(rest)
        self._kept = (rest, reading)
        if reading.intents:  # a command, unless its first word was read as talk; a stop always
            return reading.marks[:1] != bytes((TALK,)) or any(i.action == STOP for i in reading.intents)
        first = reading.tokens[:2]  # or a question put to it: "stuart what ...", "stuart can you ..."
        return bool(first) and (first[0] in WH or (len(first) == 2 and first[1] == "you" and (
            first[0] in MODALS or first[0] in AUX or first[0] in ("do", "have"))))

    def _read(self, text: str) -> Reading:
        kept, self._kept = self._kept, None
        return kept[1] if kept is not None and kept[0] == text else self.grammar.read(text)

    def parse(self, utterance: str) -> ParseResult:
        """The result for one utterance (never raises on text: any string gives a result)."""
        wake = self.wake_match(utterance)
        if not wake.woke:
            turned = turned_to_the_robot(utterance, self._is_name) if "," in utterance else None
            if turned is None:
                turned = self._named_inside(utterance)
            if turned is not None:  # "Sam, grab the extinguisher - Stuart, stop where you are"
                return self._command(utterance, True, turned)
            if not self.require_wake:
                return self._command(utterance, False, utterance.strip())
            return ParseResult(utterance)
        command = wake.command
        if "," in command:  # "go to the reading room. Anna, can you follow him?": Anna's part is not ours
            command = said_to_the_robot(command, self._is_name)
        return self._command(utterance, True, command)

    def _named_inside(self, utterance: str) -> str | None:
        """The text said to the robot when its name is said inside the utterance, neither first
        nor last, and nobody else is addressed: set off by pauses it is a vocative, and the whole
        utterance without it is said to the robot ("Once you've found the cup, Stuart, pick it
        up.", "Sorry to bother you, Stuart. Could you give us a wave?"); with no pause, what
        follows it is, when that is said to the robot and the word before the name does not speak
        of it ("the kids want a story stuart when you get to the reading room find the book", but
        "me and stuart go to the kitchen every day", "I saw stuart go to the kitchen"). Else None."""
        words = list(_WORDS.finditer(utterance))
        name = self.wake_filter.name.lower()
        for k in range(1, len(words) - 1):
            word = words[k].group().lower()  # (spelled as the name starts, about as long: cheap to rule out)
            if word[:2] != name[:2] or abs(len(word) - len(name)) > 2 or "'" in word or not self._is_name(word):
                continue  # ("Stuart's battery is low": spoken of)
            before = utterance[words[k - 1].end():words[k].start()]
            after = utterance[words[k].end():words[k + 1].start()]
            if _PAUSE.search(before) and _PAUSE.search(after):
                said = _without(utterance, words[k].start(), words[k].end())
                return said if self._said_to_the_robot_somewhere(said) else None
            if (k < 2 or words[k - 1].group().lower() in _SPOKEN_OF or words[k + 1].group().lower() in _SUBJECT_VERBS
                    or _PAUSE.search(after)):
                return None  # (the name second: the wake filter's, "haha stuart you walk like a penguin")
            rest = utterance[words[k + 1].start():]
            return rest if self._said_to_the_robot(rest) else None
        return None

    def _said_to_the_robot_somewhere(self, text: str) -> bool:
        """Whether any sentence of ``text`` holds a command (the rest may be talk); the reading is
        kept for the read of the same text that follows, as :meth:`_said_to_the_robot` keeps its."""
        reading = self.grammar.read(text)
        self._kept = (text, reading)
        return bool(reading.intents)

    def _is_name(self, word: str) -> bool:
        """Whether a word (lower case) is the robot's name as the wake filter hears names."""
        return self.wake_filter.distance(word) <= self.wake_filter.tolerance

    def _command(self, utterance: str, woke: bool, command: str) -> ParseResult:
        if not command:
            return ParseResult(utterance, woke, command, [], woke)
        read = self.read_command(command)
        read.utterance, read.wake = utterance, woke
        return read

    def read_command(self, command: str) -> ParseResult:
        """The grammar on command text alone (no wake filter): intents, coverage and doubt."""
        reading = self._read(command)
        covered = coverage(reading, self.vocatives)
        return ParseResult(command, False, command, reading.intents, not reading.intents, covered,
                           doubts(reading.intents, covered, self.limits))


_END = " \t\r\n.!?,;:"  # what a sentence may end with after its last word
# words after which the name is spoken of, not to ("wave to stuart", "a photo with stuart")
_ABOUT_IT = frozenset({"to", "at", "with", "about", "for", "from", "like", "of", "and", "or", "by", "than", "tell",
                       "ask", "meet", "is", "was", "the", "a"})

def _without(text: str, start: int, end: int) -> str:
    """``text`` without the vocative at ``start:end`` and the comma that set it off: "Please,
    Stuart, put your hands up." -> "Please, put your hands up."; "..., Stuart. Could you ..." ->
    "... . Could you ..."."""
    left, right = text[:start].rstrip(), text[end:].lstrip()
    if right.startswith(","):
        right = right[1:].lstrip()
    elif right[:1] in (".", "!", "?", ";", ":") and left.endswith(","):
        left = left[:-1]
    return f"{left} {right}"


# words before the name inside an utterance, with no pause, that speak of the robot ("me and
# stuart go ...", "I saw stuart go ...", "when stuart goes ..."), and words after it that make it
# the subject of a sentence ("stuart should go ...", "stuart is ...")
_SPOKEN_OF = _ABOUT_IT | frozenset({
    "told", "tells", "asked", "asks", "let", "lets", "make", "makes", "made", "saw", "see", "sees", "seen", "watch",
    "watched", "help", "helped", "have", "had", "get", "got", "want", "wants", "wanted", "need", "needs", "did",
    "does", "do", "can", "could", "will", "would", "should", "when", "if", "while", "because", "that", "whether",
    "why", "how", "where", "what", "who", "until", "before", "after", "once", "but", "bet", "think", "thought",
    "said", "says", "hope", "hear", "heard", "love", "loves", "like", "likes", "not", "on", "in", "into"})
_SUBJECT_VERBS = AUX | MODALS | SUBJECTS | frozenset({
    "has", "had", "goes", "went", "walks", "walked", "turns", "turned", "picks", "picked", "finds", "found", "waves",
    "waved", "and", "or"})
_WORDS = re.compile(r"[A-Za-z']+")
_PAUSE = re.compile(r"[,.!?;:\u2013\u2014-]")

_DEFAULT: Parser | None = None


def parse(utterance: str) -> ParseResult:
    """Parse with the default robot name ("Stuart")."""
    global _DEFAULT
    if _DEFAULT is None:
        _DEFAULT = Parser()
    return _DEFAULT.parse(utterance)
