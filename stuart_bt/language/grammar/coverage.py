"""Which words a command was read from, and which it was not: the parse accounts for every word.

A word the grammar did not use is harmless when it is filler (politeness, a connector, an
article, "mate", "right now"); any other unused word might have changed the meaning ("turn right
*at the door*", "go to the kitchen *and make me a sandwich*"), so it is *doubt*, and the robot
asks before it acts (:mod:`stuart_bt.language.doubt`). Words of a question or a statement are
conversation, not unused: nothing was asked of the robot there.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from .driver import ASKED, CHOICE, TALK, TIMES, USED, Reading
from .lexicon import (
    BOUNDARY,
    CONNECTORS,
    DETERMINERS,
    DISFLUENCIES,
    HARD_STOPS,
    NP_STOP,
    OBJECT_PRONOUNS,
    POLITE,
    PRONOUNS,
    TRAILING,
)

# said to frame what follows, never part of what is asked ("so basically, just go to the bathroom")
DISCOURSE_ADVERBS = frozenset({"basically", "literally", "honestly", "seriously", "essentially", "obviously",
                               "anyway", "anyhow", "frankly", "simply", "totally", "definitely", "sort", "kind"})

# words that never carry a command's meaning, so leaving them unread loses nothing
FILLER = (BOUNDARY | HARD_STOPS | TRAILING | DETERMINERS | PRONOUNS | OBJECT_PRONOUNS | NP_STOP | DISFLUENCIES
          | frozenset(w for phrase in POLITE for w in phrase) | frozenset(w for c in CONNECTORS for w in c)
          | frozenset({"you", "u", "hey", "hi", "hello", "oh", "yo", "guys", "folks", "everyone", "just", "really",
                       "kindly", "go", "ahead", "cheers", "ta", "lovely", "great", "cool", "nice", "good", "sorry",
                       "excuse", "thx", "like", "do", "that", "for", "me", "wait", "then", "no", "yes", "be"})
          | DISCOURSE_ADVERBS) - TIMES



@dataclass(frozen=True)
class Coverage:
    """The words of a command by what they were to the grammar (lower case, as tokenised)."""

    used: tuple[str, ...] = ()  # an intent came from them
    unused: tuple[str, ...] = ()  # content words no clause used
    talk: tuple[str, ...] = ()  # part of a question or a statement
    unread: str = ""  # past the grammar's length limit: not read at all
    asked: tuple[str, ...] = ()  # a tag that put a command as a question ("go to the kitchen, right?")

    def to_dict(self) -> dict[str, Any]:
        return {"used": list(self.used), "unused": list(self.unused), "talk": list(self.talk), "unread": self.unread,
                "asked": list(self.asked)}


def coverage(reading: Reading, vocatives: Iterable[str] = ()) -> Coverage:
    """Sort ``reading``'s words into used, unused content words and talk."""
    used: list[str] = []
    unused: list[str] = []
    talk: list[str] = []
    asked: list[str] = []
    extra = frozenset(vocatives)
    for tok, mark in zip(reading.tokens, reading.marks, strict=True):
        if mark == USED:
            used.append(tok)
        elif mark == TALK:
            talk.append(tok)
        elif mark == ASKED:
            asked.append(tok)
        elif (mark == CHOICE and tok not in BOUNDARY) or (tok not in FILLER and tok not in extra):
            unused.append(tok)  # "or maybe right": in a choice left open even a filler word is unsure
    return Coverage(tuple(used), tuple(unused), tuple(talk), reading.unread, tuple(asked))
