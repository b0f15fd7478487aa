"""The robot's commands as a JSGF grammar, for a command-only recogniser.

A recogniser held to a grammar hears only sentences of that grammar, so it hears "then turn
around" where a general one heard "and enter around". The grammar is generated from the same
:class:`~.vocabulary.Vocabulary` as the whisper prompt (the robot's name, every place by name
and display name, the object labels, the gesture library) and from the command shapes below:
the verbs of each kind of command, directions, amounts in words with their units, politeness
and connectors between commands. No sentence is listed: a new marker is in the grammar as soon
as it is on the map. Every sentence the grammar can produce is one the command grammar
(:mod:`stuart_bt.language`) reads as intents; tests/test_hearing_grammar_engine.py keeps it so.

A grammar engine answers inside its grammar whatever it hears: talk comes out as some
command. So it is never used alone; :mod:`.second_opinion` has whisper judge what it heard.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from .pronounce import ONES, TENS
from .vocabulary import Vocabulary

GREETINGS = ("hey", "hi", "hello", "ok", "okay")
POLITE = ("please", "could you", "can you", "would you", "could you please", "can you please", "would you please")
TRAILERS = ("please", "now")
CONNECTORS = ("and", "then", "and then", "after that")
MOST_COMMANDS = 3  # commands in one utterance

GO_VERBS = ("go", "walk", "head", "move", "navigate", "drive", "come")
GO_TO = ("to", "over to", "back to")
PICK_VERBS = ("pick up", "grab", "get", "fetch", "take", "bring me")
FIND_VERBS = ("find", "look for", "search for", "locate")
FIND_WHERE = ("in", "at")
TURN_VERBS = ("turn", "rotate", "spin")
TURN_SIDES = ("left", "right")
AROUND = ("around",)
MOVE_VERBS = ("walk", "move", "go", "step")
MOVE_DIRECTIONS = ("forward", "forwards", "back", "backward", "backwards", "left", "right")
LENGTH_UNITS = ("metre", "metres", "meter", "meters")
ANGLE_UNITS = ("degree", "degrees")
GESTURE_LEADS = ("do", "give me", "show me", "make")
GESTURE_ARTICLES = ("a", "an")  # "give me the hug" asks to be handed something
GESTURE_VERBS = ("wave", "clap", "hug", "shake hands")  # gestures said as a verb alone: "Hey Stuart, wave"
# The gesture library takes these as other names of a gesture, but said to the robot they are a
# greeting and half a verb: the command grammar does not read "Hey Stuart, do a hello" as one
NOT_GESTURE_NAMES = frozenset({"hello", "release"})
STOPS = ("stop", "halt", "freeze", "stand still", "stop now", "stop moving")
ARTICLES = ("the", "a", "an", "my")


def spoken(phrase: str) -> list[str]:
    """A phrase as grammar tokens: lower case, its written words kept ("3d", "x-ray") but
    anything JSGF reserves dropped; each token is given a pronunciation (:mod:`.pronounce`)."""
    tokens = (w.strip(".'-") for w in re.findall(r"[\w'.-]+", phrase.lower().replace("_", " ")))
    return [w for w in tokens if w]


def _either(phrases: Iterable[str]) -> str:
    """JSGF alternatives of ``phrases`` (each already grammar tokens), duplicates dropped."""
    seen = dict.fromkeys(" ".join(spoken(p)) for p in phrases)
    seen.pop("", None)
    return " | ".join(f"({p})" if " " in p else p for p in seen)


def jsgf(vocabulary: Vocabulary) -> str:
    """The grammar of commands to the robot called ``vocabulary.name``, about its places,
    objects and gestures."""
    body = "\n".join(f"<{name}> = {rule};" for name, rule in rules(vocabulary).items())
    return f"#JSGF V1.0;\ngrammar commands;\npublic <utterance> = <addressed>;\n{body}\n"


def rules(v: Vocabulary) -> dict[str, str]:
    """The grammar's rules, name -> JSGF body, from the top (``addressed``) down."""
    more = " ".join(["[<connector> <command>]"] * (MOST_COMMANDS - 1))
    table = {
        "addressed": f"[<greeting>] <name> <command> {more}",
        "greeting": _either(GREETINGS),
        "name": _either([v.name]),
        "connector": _either(CONNECTORS),
        "command": "[<polite>] <action> [<trailer>]",
        "polite": _either(POLITE),
        "trailer": _either(TRAILERS),
        "action": " | ".join(f"<{k}>" for k in _kinds(v)),
        "stop": _either(STOPS),
        "turn": f"({_either(TURN_VERBS)}) (({_either(TURN_SIDES)}) [[by] <number> <angle_unit>] | {_either(AROUND)})",
        "move": f"({_either(MOVE_VERBS)}) ({_either(MOVE_DIRECTIONS)}) [<distance>]",
        "distance": "<number> <length_unit> | half a <length_unit> | a <length_unit> "
                    "| <number> and a half <length_unit>",
        "length_unit": _either(LENGTH_UNITS),
        "angle_unit": _either(ANGLE_UNITS),
        "number": "<units> | <teens> | <tens> [<units>] | (a | one | two | three) hundred [[and] <tens_units>]",
        "tens_units": "<units> | <teens> | <tens> [<units>]",
        "units": _either(ONES[1:10]),
        "teens": _either(ONES[10:]),
        "tens": _either(w for w in TENS if w),
    }
    if v.places:
        table["go"] = f"({_either(GO_VERBS)}) ({_either(GO_TO)}) <place>"
        table["place"] = "[the] <place_name>"
        table["place_name"] = _either(v.places)
    if v.objects:
        table["pick"] = f"({_either(PICK_VERBS)}) <thing>"
        where = f" [({_either(FIND_WHERE)}) the <place_name>]" if v.places else ""
        table["find"] = f"({_either(FIND_VERBS)}) <thing>{where}"
        table["thing"] = f"[{_either(ARTICLES)}] ({_either(v.objects)})"
    gestures = [g for g in v.gestures if g.lower() not in NOT_GESTURE_NAMES]
    if gestures:
        bare = [g for g in gestures if g.lower() in GESTURE_VERBS]
        led = f"({_either(GESTURE_LEADS)}) [{_either(GESTURE_ARTICLES)}] ({_either(gestures)})"
        table["gesture"] = f"{led} | {_either(bare)}" if bare else led
    return table


def _kinds(v: Vocabulary) -> list[str]:
    kinds = ["stop", "turn", "move"]
    if v.places:
        kinds.append("go")
    if v.objects:
        kinds += ["pick", "find"]
    if any(g.lower() not in NOT_GESTURE_NAMES for g in v.gestures):
        kinds.append("gesture")
    return kinds


def matcher(vocabulary: Vocabulary) -> re.Pattern[str]:
    """A regular expression for the same commands as :func:`jsgf`, over text made
    :func:`normalise`: is what another recogniser heard a sentence of this grammar? (An amount
    may be written in digits: "turn left 90 degrees".)"""
    table = rules(vocabulary)
    done: dict[str, str] = {"number": r"(?:\d+ |" + _regex(table["number"], table, {}) + ")"}
    return re.compile(_regex(table["addressed"], table, done))


def normalise(text: str) -> str:
    """Text as grammar tokens, one space after each: lower case, no punctuation around words."""
    return "".join(w + " " for w in spoken(text))


_REGEX = {"(": "(?:", "[": "(?:", "]": ")?", ")": ")", "|": "|", "+": "+"}  # JSGF -> regular expression


def _regex(rule: str, rules: dict[str, str], done: dict[str, str]) -> str:
    out: list[str] = []
    for token in re.findall(r"<[^>]+>|[()\[\]|+]|[^\s()\[\]|+<>]+", rule):
        if token.startswith("<"):
            name = token[1:-1]
            if name not in done:
                done[name] = "(?:" + _regex(rules[name], rules, done) + ")"
            out.append(done[name])
        else:
            out.append(_REGEX.get(token, re.escape(token) + " "))
    return "".join(out)


def words(grammar: str) -> list[str]:
    """Every token of a JSGF grammar text that names a word (for the pronunciation dictionary)."""
    out: dict[str, None] = {}
    for line in grammar.splitlines():
        if "=" not in line or line.startswith("#"):
            continue
        rule = re.sub(r"<[^>]*>", " ", line.split("=", 1)[1])
        for token in re.findall(r"[^\s()\[\]|;*+/]+", rule):
            out.setdefault(token, None)
    return list(out)


_UNITS = {w: n for n, w in enumerate(ONES[:10])}
_TEENS = {w: n for n, w in enumerate(ONES) if n >= 10}
_TENS = {w: 10 * n for n, w in enumerate(TENS) if w}


def as_digits(tokens: list[str]) -> list[str]:
    """The grammar's amounts in digits, as a general recogniser writes them ("turn left ninety
    degrees" -> "turn left 90 degrees"; "a hundred and eighty degrees" -> "180 degrees"): a
    number right before its unit; other words as they are ("high five", "one and a half")."""
    units = set(LENGTH_UNITS) | set(ANGLE_UNITS)
    out: list[str] = []
    i = 0
    while i < len(tokens):
        value, end = _number(tokens, i)
        if end > i and end < len(tokens) and tokens[end] in units:
            out.append(str(value))
            i = end
        else:
            out.append(tokens[i])
            i += 1
    return out


def _number(tokens: list[str], i: int) -> tuple[int, int]:
    """(value, end) of the number of :func:`jsgf`'s ``<number>`` rule at ``i``; end == i when none."""
    def at(j: int) -> str:
        return tokens[j] if j < len(tokens) else ""

    value, j = 0, i
    if at(j + 1) == "hundred" and (at(j) in ("a", "one") or at(j) in _UNITS):
        value, j = 100 * _UNITS.get(at(j), 1), j + 2
        if at(j) == "and" and (at(j + 1) in _UNITS or at(j + 1) in _TEENS or at(j + 1) in _TENS):
            j += 1
    if at(j) in _TENS:
        value, j = value + _TENS[at(j)], j + 1
        if at(j) in _UNITS and _UNITS[at(j)]:
            value, j = value + _UNITS[at(j)], j + 1
    elif at(j) in _TEENS or at(j) in _UNITS:
        value, j = value + _TEENS.get(at(j), _UNITS.get(at(j), 0)), j + 1
    return value, j
