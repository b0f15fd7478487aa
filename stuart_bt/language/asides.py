"""Who each part of an utterance is said to: the robot, or someone else in the room.

In a busy room the robot is spoken to in the middle of talk with other people: "Stuart, go to
the reading room. Anna, can you follow him?", "Sam, grab the extinguisher - Stuart, stop where
you are", "Stuart - Sam, mind the cable - Stuart, forward one metre". A name said as a vocative
(after a pause, with a comma after it) turns the speech to that person until the next one. The
parts said to someone else are no commands to the robot, whatever verbs they hold; a part said
to the robot, even after someone else was addressed first, is.

Someone else's name is told from the words a command may open with by three signs together: it
is written with a capital (recognisers write names so), it is no word the grammar knows ("Right,
...", "Careful, ...", "Please, ..."), and what follows it is said to a person (a verb, a
request, "you"). A place said as a verbless order ("Kitchen, now") has no verb after it, so it
stays an order. Text in lower case with no commas, as some recognisers write it, has no
vocatives to find: it is read as before.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import NamedTuple

from .grammar.lexicon import ALL_VERBS, AUX, DETERMINERS, MODALS, SUBJECTS, TRAILING, WH
from .wake import FILLERS, GREETINGS

# a group in the room called by what it is ("folks, follow him"), in any case
_GROUPS = "folks|guys|everyone|everybody|kids|children|people|team|ladies|gentlemen"

_GROUP_WORDS = frozenset(_GROUPS.split("|"))

_WORD = re.compile(r"\s*([A-Za-z']+)")  # the first word at a position

# a capitalised word or a group after the start or a pause (". ", "! ", "? ", "; ", " - "), then a comma
_VOCATIVE = re.compile(rf"(?:^|(?<=[.!?;:])\s+|\s*[-–—]+\s*)([A-Z][a-z]+|(?i:{_GROUPS})),\s*")

# a stretch between pauses that ends by calling a group ("... - mind the cables, guys - ...")
_GROUP_LAST = re.compile(rf"(?:(?<=[.!?;:])\s+|\s+[-–—]+\s+)([^-–—.!?;:]+?),\s*(?i:{_GROUPS})\s*(?=[-–—.!?;:]|$)")

# words a sentence to a person may open with besides verbs and requests ("Sam, mind the cable")
_SAID_TO_A_PERSON = frozenset({"please", "you", "mind", "careful", "watch", "come", "help", "let", "lets", "do",
                               "dont", "could", "can", "would", "will", "hand", "pass", "grab", "get", "follow",
                               "wait", "hold", "stay", "look", "check", "go", "take", "bring", "tell", "ask",
                               "make", "keep", "open", "close", "move", "stand", "sit", "put", "show"})

_OPENS_A_REQUEST = _SAID_TO_A_PERSON | ALL_VERBS | MODALS

# words that open a sentence with a comma after them and are no one's name
_NOT_A_NAME = (ALL_VERBS | AUX | MODALS | WH | SUBJECTS | DETERMINERS | TRAILING | FILLERS | {
    g for phrase in GREETINGS for g in phrase.split()} | {
    "please", "sorry", "thanks", "no", "yes", "careful", "wait", "okay", "ok", "actually", "oh", "ah", "hmm",
    "great", "good", "nice", "perfect", "excellent", "cool", "brilliant", "sure", "fine", "listen", "look",
    "remember", "honestly", "seriously", "first", "next", "finally", "again", "also", "anyway", "left", "right",
    "forward", "back", "quick", "quickly", "slowly", "sir", "madam"})


class Vocative(NamedTuple):
    """A name said to someone at ``start`` (where its pause begins); the text said to them
    starts at ``end``."""

    start: int
    end: int
    robot: bool


def vocatives(text: str, is_robot: Callable[[str], bool]) -> list[Vocative]:
    """The vocatives in ``text`` in order: the robot's name (``is_robot`` judges a lower-case
    word) or someone else's (module docstring)."""
    found = []
    for m in _VOCATIVE.finditer(text):
        word = m.group(1).lower()
        if is_robot(word):
            found.append(Vocative(m.start(), m.end(), True))
        elif (word in _GROUP_WORDS or word not in _NOT_A_NAME) and _first_word(text, m.end()) in _OPENS_A_REQUEST:
            found.append(Vocative(m.start(), m.end(), False))
    return found


def said_to_the_robot(command: str, is_robot: Callable[[str], bool]) -> str:
    """``command`` (the text after the wake phrase) with every part said to someone else left
    out, and the robot's name where it turns the speech back to the robot: "go to the reading
    room. Anna, can you follow him?" -> "go to the reading room."; "Sam, mind the cable - Stuart,
    forward one metre." -> "forward one metre.". Unchanged when nobody else is addressed."""
    command = _GROUP_LAST.sub(lambda m: ". " if _first_word(m.group(1), 0) in _OPENS_A_REQUEST else m.group(0),
                              command)  # "go to station two - mind the cables, guys - thanks"
    said = vocatives(command, is_robot)
    if said and not said[0].robot and said[0].start == 0 and not any(v.robot for v in said):
        said = said[1:]  # "Kitchen, go!" right after the wake phrase: an order, unless the robot is named again
    if not any(not v.robot for v in said):
        return command
    parts, at, to_robot = [], 0, True
    for v in said:
        if to_robot:
            parts.append(command[at:v.start])
        to_robot, at = v.robot, v.end
        parts.append(". ")  # a new sentence: nothing said to someone else continues a command
    if to_robot:
        parts.append(command[at:])
    return "".join(parts).strip(" .")


def turned_to_the_robot(utterance: str, is_robot: Callable[[str], bool]) -> str | None:
    """The text said to the robot when its name is said as a vocative inside the utterance, not
    at its start ("Sam, grab the extinguisher - Stuart, stop where you are" -> "stop where you
    are"), else None."""
    said = vocatives(utterance, is_robot)
    last = next((v for v in reversed(said) if v.robot and v.start > 0), None)
    if last is None:
        return None
    rest = utterance[last.end:]
    return said_to_the_robot(rest, is_robot).strip() or None


def _first_word(text: str, at: int) -> str:
    m = _WORD.match(text, at)
    return m.group(1).lower().replace("'", "") if m else ""
