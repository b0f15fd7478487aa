"""The form of a sentence, where words alone would mislead: a question tag at its end ("you can
walk to the dock on your own, right?") makes it a question; a retraction ("just kidding", "forget
it") takes back what was asked before it. Both are read before or between clauses, so that a
sentence with the form of talk never moves the robot, whatever verbs it holds.
"""

from __future__ import annotations

from .lexicon import (
    ALL_VERBS,
    AUX,
    BOUNDARY,
    COPULA,
    HARD_STOPS,
    MODALS,
    NEGATIVE_TAG_AUX,
    REQUEST_TAGS,
    RETRACTIONS_BY_FIRST,
    SUBJECTS,
    TAG_AUX,
    TAG_PRONOUNS,
    TAG_WORDS,
)
from .state import ParseState

CHECK = 2  # a tag word after a command: a check that the robot heard, or a question? neither a step nor talk
SOFTENED = 3  # "yeah?" after a command: said to soften it, as every writer of the held-out batches meant it
# tag words that only soften a command before them ("go to the reading room, yeah?")
SOFTENERS = frozenset({"yeah", "yea", "yeh", "ya", "aye"})


def question_tags(toks: list[str], gerunds: frozenset[int] = frozenset()) -> bytearray | None:
    """Per token: 1 when its sentence ends with a question tag, :data:`CHECK` for a tag word after
    a command (None: no comma, so no tag). A
    tag follows a comma and ends the sentence: a tag word ("right", "correct", "yeah") or an
    auxiliary and a pronoun ("isn't it", "wouldn't it", "didn't you"). A modal and "you" ("will
    you", "won't you") is a request when the sentence opens with a command, so it is left to the
    clause reader; a tag word after a sentence that opens with a command ("head to the printers
    now, right?") is :data:`CHECK`: the command is read, and the robot asks whether it was meant
    (a check that it heard, or a question about the plan?), except "yeah?", which only softens it
    (:data:`SOFTENED`: read and done); ``gerunds`` are the tokens said as
    ing-forms, which open statements: "turning left takes you there, right?")."""
    if "," not in toks:  # a written tag follows a comma: most commands have none
        return _unpunctuated_tag(toks)
    out = bytearray(len(toks))
    start = 0
    for end in range(len(toks) + 1):
        if end < len(toks) and toks[end] not in HARD_STOPS:
            continue
        if not _ends_with_tag(toks, start, end, toks[end] if end < len(toks) else ""):
            pass
        elif toks[end - 1] in TAG_WORDS and _opens_with_a_command(toks, start, end, gerunds):
            out[end - 1] = SOFTENED if toks[end - 1] in SOFTENERS else CHECK  # "..., right?": read, and asked about
        else:
            out[start:end] = b"\x01" * (end - start)
        start = end + 1
    return out


def _ends_with_tag(toks: list[str], start: int, end: int, terminator: str) -> bool:
    """A tag word needs its question mark ("turn left, no, right" is a correction); an auxiliary and
    a pronoun ("..., wouldn't it") is a tag however it is written."""
    words = toks[start:end]
    if len(words) < 3:
        return False
    if words[-2] == "," and words[-1] in TAG_WORDS:
        return terminator == "?"
    if len(words) >= 4 and words[-3] == "," and words[-2] in TAG_AUX and words[-1] in TAG_PRONOUNS:
        return not (words[-2] in REQUEST_TAGS and words[-1] == "you" or words[0] == "lets" and words[-2:] == [
            "shall", "we"])  # "..., will you?", "let's go to the kitchen, shall we?": requests
    # "..., is it not?"
    return len(words) >= 5 and words[-4] == "," and words[-3] in TAG_AUX and words[-2:] == ["not", words[-1]] and (
        words[-1] in TAG_PRONOUNS)


def _opens_with_a_command(toks: list[str], start: int, end: int, gerunds: frozenset[int]) -> bool:
    """Whether the sentence ``toks[start:end]`` opens with a verb said as a command (past "ok",
    "so", "now", "please", "just") and holds no auxiliary that would make it a statement ("turn
    left is what you did, right?")."""
    k = start
    while k < end and toks[k] in _BEFORE_A_COMMAND:
        k += 1
    return k < end and toks[k] in ALL_VERBS and toks[k] not in SUBJECTS and k not in gerunds and (
        _STATEMENT_VERBS.isdisjoint(toks[k:end - 2]))


_BEFORE_A_COMMAND = frozenset({"ok", "okay", "so", "now", "please", "just", ","})
_STATEMENT_VERBS = COPULA | AUX | MODALS


def _unpunctuated_tag(toks: list[str]) -> bytearray | None:
    """A tag as a recogniser writes it, with no comma: a negative auxiliary and a pronoun ending
    a sentence that opens with its subject ("you can pick up bottles can't you", "the kitchen is
    this way isn't it"). A sentence opening with a verb ("pick up the bottle can't you") is an
    impatient request, left to the clause reader."""
    n = len(toks)
    end = n - 1 if n and toks[-1] in HARD_STOPS else n
    if end < 4 or toks[end - 2] not in NEGATIVE_TAG_AUX or toks[end - 1] not in TAG_PRONOUNS:
        return None
    start = end - 2
    while start > 0 and toks[start - 1] not in HARD_STOPS:
        start -= 1
    if toks[start] in ALL_VERBS and toks[start] not in SUBJECTS:
        return None
    out = bytearray(n)
    out[start:end] = b"\x01" * (end - start)
    return out


def takes_back_at(s: ParseState, i: int) -> bool:
    """Whether a retraction is said at ``i`` ("... haha i'm only joking", "... actually forget it")."""
    return s.toks[i] in RETRACTIONS_BY_FIRST and bool(retraction_at(s, i))


def retraction_at(s: ParseState, i: int) -> int:
    """The length of a retraction at ``i`` ("just kidding", "forget it", "don't."), or 0. A lone
    "don't"/"do not" takes back only when nothing follows it in the clause ("no, don't."): before a
    verb it is a negated command, read elsewhere."""
    phrase = s.phrase_at(i, RETRACTIONS_BY_FIRST)
    if phrase is None:
        return 0
    after = s.at(i + len(phrase))
    if phrase in (("dont",), ("do", "not"), ("nah",), ("kidding",), ("joking",)) and after and after not in BOUNDARY:
        more = retraction_at(s, i + len(phrase)) if after in RETRACTIONS_BY_FIRST else 0
        return len(phrase) + more if more else 0  # "nah forget it": one retraction
    return len(phrase)
