"""Answers from facts first: the robot's own state and the lab's knowledge, before any model.

A small language model makes things up ("I'm holding a small box of tools" while holding
nothing), and even a good one takes seconds. Questions whose answer the robot *knows* are
answered here, deterministically and in microseconds:

- about itself, from the :class:`Situation` the mission executor fills in: what it holds, where
  it is, what it is doing, what it can do, what it sees, where a thing is;
- about the lab, by retrieval over the lab-knowledge file: every fact (a station, a place, a
  person, a robot, the opening hours) is a small document, scored by the question's content words
  weighted by how rare they are; the best fact is spoken when it matches well enough.

Anything else (chit-chat) goes to the model, given the best matching facts as its only lab
context (:func:`related_facts`), and its reply is checked (:func:`checked_reply`).
"""

from __future__ import annotations

import math
import re
from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

_WORD = re.compile(r"[a-z0-9]+")

# words that carry no topic: a question about "the drone cage" is about "drone" and "cage"
_STOP = frozenset({
    "a", "an", "the", "is", "are", "was", "were", "be", "been", "am", "do", "does", "did", "doing", "done", "have",
    "has", "had", "i", "you", "your", "yours", "me", "my", "we", "our", "us", "it", "its", "this", "that", "these",
    "those", "there", "here", "what", "whats", "where", "wheres", "who", "whos", "when", "why", "how", "which",
    "can", "could", "would", "will", "shall", "should", "may", "might", "must", "tell", "about", "of", "in", "on",
    "at", "to", "for", "from", "with", "and", "or", "but", "so", "if", "please", "stuart", "hey", "hi", "hello",
    "ok", "okay", "they", "them", "he", "she", "his", "her", "him", "any", "some", "much", "many", "more", "most",
    "very", "just", "really", "know", "like", "say", "said", "go", "going", "get", "got", "make", "made", "let",
    "lets", "one", "thing", "things",
})

_ASKS = re.compile(r"^(?:what|whats|where|wheres|who|whos|when|why|how|which|is|are|do|does|did|can|could|tell me"
                   r"|explain|describe)\b|\?\s*$")


def words(text: str) -> list[str]:
    """Lower-case content words with a plural ``s`` taken off ("printers" -> "printer")."""
    out = []
    for w in _WORD.findall(text.lower().replace("'", "")):
        if w in _STOP:
            continue
        out.append(w[:-1] if len(w) > 3 and w.endswith("s") and not w.endswith("ss") else w)
    return out


@dataclass(frozen=True)
class Fact:
    """One thing the lab-knowledge file says, as the robot would say it."""

    topic: str  # what it is about ("Drone cage", "Priya Nair", "opening hours")
    sentence: str  # the answer, spoken as it is
    person: bool = False  # a "who ...?" question is about a person first


def lab_facts(knowledge: Mapping[str, Any]) -> list[Fact]:
    """Every fact in the lab-knowledge file, one per station, place, person, robot and lab line."""
    facts: list[Fact] = []
    lab = knowledge.get("lab") or {}
    if lab.get("description"):
        facts.append(Fact(f"lab {lab.get('name', '')}", str(lab["description"])))
    if lab.get("hours"):
        facts.append(Fact("opening hours open visit time visitor tour start", str(lab["hours"])))
    robot = knowledge.get("robot") or {}
    if robot.get("model"):
        facts.append(Fact("you yourself robot model tall weigh heavy", f"I am a {robot['model']}."))
    if robot.get("senses"):
        facts.append(Fact("sense sensor camera lidar eye see", f"I sense the world with {robot['senses']}."))
    for key in ("stations", "places"):
        for item in knowledge.get(key) or []:
            name = spoken_name(str(item["name"]))
            facts.append(Fact(name, f"The {name}: {spoken_name(str(item['about']))}"))
    for person in knowledge.get("people") or []:
        facts.append(Fact(f"{person['name']} person", f"{person['name']} is the {person['role']}.", person=True))
    for other in knowledge.get("robots") or []:
        facts.append(Fact(f"{other['name']} {other['kind']} robot", f"{_upper_first(other['name'])} "
                          f"({other['kind']}): {other['job']}."))
    return facts


def spoken_name(text: str) -> str:
    """A name or sentence as said inside a sentence: "A netted cage" -> "a netted cage", "Drone
    cage" -> "drone cage"; "3D printers" and "LiDAR" stay as they are."""
    first = text.split(" ", 1)[0]
    return text[:1].lower() + text[1:] if first[1:] == first[1:].lower() else text


def _upper_first(text: str) -> str:
    return text[:1].upper() + text[1:]


class FactIndex:
    """The lab's facts, searchable by the words of a question. A fact's topic words count double:
    "what happens in the drone cage?" is about the drone cage even if other facts mention drones."""

    def __init__(self, facts: Sequence[Fact]) -> None:
        self.facts = list(facts)
        self._docs = [Counter(words(f.topic) * 2 + words(f.sentence)) for f in self.facts]
        df = Counter(w for doc in self._docs for w in set(doc))
        n = len(self._docs)
        self._idf = {w: math.log(1 + n / c) for w, c in df.items()}

    def search(self, question: str, k: int = 3) -> list[tuple[float, Fact]]:
        """The ``k`` best facts with their scores (0: nothing in common), best first."""
        asked = set(words(question))
        who = question.lower().lstrip().startswith("who")
        scored = []
        for fact, doc in zip(self.facts, self._docs, strict=True):
            score = sum(self._idf[w] * min(doc[w], 2) for w in asked if w in doc)
            if score > 0:
                scored.append((score * (2.0 if who and fact.person else 1.0), fact))
        scored.sort(key=lambda pair: -pair[0])
        return scored[:k]


@dataclass
class Situation:
    """What the robot knows about itself right now, in plain data (the mission executor fills it
    in from the world state, the queue and the domain)."""

    at: str = ""  # display name of the place it last arrived at
    held: str = ""  # the object in its hand
    doing: str = ""  # "going to the kitchen, then picking up the bottle"; "" when idle
    seen: list[str] = field(default_factory=list)  # labels seen in the last minute, nearest first
    places: dict[str, str] = field(default_factory=dict)  # spoken name -> display name, every marker
    objects: dict[str, str] = field(default_factory=dict)  # label -> where it is ("on the workbench")
    abilities: str = ("walk to a named place, turn, step, pick up small objects, look for things, "
                      "and wave, clap or give a high five")


_HOLD = re.compile(r"\b(?:holding|carrying|in your hands?|have you got|got in your hand|what do you have)\b")
_WHERE_ME = re.compile(r"\bwhere (?:are|r) (?:you|we)\b|\byour (?:location|position)\b|\bwhere am i\b")
_DOING = re.compile(r"\bwhat (?:are|r) you (?:doing|up to|busy with|working on)\b|\bare you busy\b")
_ABLE = re.compile(r"\bwhat (?:can|could) you do\b|\bwhat are you (?:able|good) (?:to|at)\b"
                   r"|\byour (?:skills|abilities)\b|\bwhat do you do\b")
_SEE = re.compile(r"\bwhat (?:do|can) you see\b|\bwhat(?:s| is) in front of you\b|\bcan you see\b|\bdo you see\b"
                  r"|\bwhat are you looking at\b")
_WHERE_IS = re.compile(r"\bwhere(?:s| is| are| can i find| would i find| did you (?:see|put)| have you seen)"
                       r"\s+"
                       r"(?:the |my |a |an |our )?(?P<thing>[a-z0-9 ]+?)\s*(?:$|\bnow\b|\btoday\b)")


class FactAnswers:
    """Answers a question from the :class:`Situation` and the lab's facts, or says it cannot
    (``None``: the question is for the model). ``threshold``: how well a lab fact must match."""

    def __init__(self, knowledge: Mapping[str, Any], threshold: float = 1.5) -> None:
        self.index = FactIndex(lab_facts(knowledge))
        self.threshold = threshold

    def answer(self, question: str, situation: Situation) -> str | None:
        text = " ".join(_WORD.findall(question.lower().replace("'", "")))
        for rule in (_about_holding, _about_place, _about_doing, _about_abilities, _about_seeing):
            said = rule(text, situation)
            if said:
                return said
        where = _WHERE_IS.search(text)
        if where:
            said = _where_is(where.group("thing").strip(), situation)
            if said:
                return said
        best = self.index.search(question, 1) if _ASKS.search(text) or question.rstrip().endswith("?") else []
        if best and best[0][0] >= self.threshold:  # a lab fact only for a question, never for a request
            return best[0][1].sentence
        return None


def _about_holding(text: str, s: Situation) -> str | None:
    if not _HOLD.search(text):
        return None
    return f"I'm holding the {s.held}." if s.held else "I'm not holding anything."


def _about_place(text: str, s: Situation) -> str | None:
    if not _WHERE_ME.search(text):
        return None
    return f"I'm at the {s.at}." if s.at else "I'm not at any of the places I know by name right now."


def _about_doing(text: str, s: Situation) -> str | None:
    if not _DOING.search(text):
        return None
    return f"I'm {s.doing}." if s.doing else "Nothing right now: I'm waiting for what you would like me to do."


def _about_abilities(text: str, s: Situation) -> str | None:
    return f"I can {s.abilities}. Just ask." if _ABLE.search(text) else None


def _about_seeing(text: str, s: Situation) -> str | None:
    if not _SEE.search(text):
        return None
    if not s.seen:
        return "I don't see anything I recognise right now."
    return "I can see " + listing([with_article(label) for label in s.seen]) + "."


def _where_is(thing: str, s: Situation) -> str | None:
    """A place on the map or an object in memory; None when the robot does not know the thing."""
    key = " ".join(words(thing))
    for spoken, display in s.places.items():
        if key and key == " ".join(words(spoken)):
            return f"The {display} is on my map: say 'go to the {display}' and I'll take you there."
    for label, where in s.objects.items():
        if key and key == " ".join(words(label)):
            return f"The {label} is {where}, as far as I know."
    if key:
        return f"I don't know where the {thing} is. I can look for it if you like."
    return None


def listing(items: Iterable[str]) -> str:
    """ "a, b and c" (one item: itself)."""
    items = list(items)
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def with_article(label: str) -> str:
    """ "a bottle", "an apple" (an underscore in a label is a space)."""
    name = label.replace("_", " ")
    return ("an " if name[:1].lower() in "aeiou" else "a ") + name


def related_facts(index: FactIndex, question: str, k: int = 3) -> str:
    """The facts most related to ``question``, as lines for a model's prompt (its only lab context)."""
    return "\n".join(f.sentence for _, f in index.search(question, k))


MAX_REPLY_CHARS = 240
_CLAIMS_HOLDING = re.compile(r"\b(?:i(?:'m| am) (?:holding|carrying)|in my hands?|i(?:'ve| have) got (?:a|the))\b",
                             re.IGNORECASE)
_SENTENCE_END = re.compile(r"(?<=[.!?])\s+")


def checked_reply(text: str, situation: Situation) -> str:
    """A model's reply made safe to speak: no sentence that claims to hold something while the
    hands are empty, at most MAX_REPLY_CHARS (cut at a sentence end), never empty."""
    sentences = [s for s in _SENTENCE_END.split(text.strip()) if s]
    if not situation.held:
        sentences = [s for s in sentences if not _CLAIMS_HOLDING.search(s)]
    kept: list[str] = []
    for sentence in sentences:
        if kept and len(" ".join([*kept, sentence])) > MAX_REPLY_CHARS:
            break
        kept.append(sentence[:MAX_REPLY_CHARS])
    return " ".join(kept) or "Sorry, I don't know."
