"""Spoken targets -> marker names, object labels and gestures, or the reason there is none.

The grammar reports what was said ("the charging dock", "station three", "kitchen area"); this
module maps it onto what the robot knows: the markers of the map it is on (a marker file, see
:func:`stuart_bt.maps.markers.load_markers`) and the object labels its detector uses. It is kept apart
from parsing so one parse can be resolved against any map, and so a failure can be explained:
"I don't know where the garage is" is said before anything moves.

How a marker is matched, first rule that gives exactly one marker wins:

1. the name, spaced ("charging dock", "station 3"), run together ("workbench"), or the display
   name ("Drone cage", "3D printers"), after lower-casing, dropping determiners, number words
   as digits ("station three" -> "station 3", "the third station" -> "station 3"), plurals as
   singulars;
2. a synonym that names one of those ("toilet" -> bathroom, "charger" / "home" -> charging dock,
   "front door" -> entrance), only if the map has it;
3. the same with filler words dropped ("kitchen area" -> kitchen);
4. words in common: every spoken word in one marker's name ("your dock" -> charging_dock), or
   one marker's whole name in what was said ("the kitchen table" -> kitchen);
5. spelling: difflib similarity >= 0.8 ("bathrom").

Two or more markers at the same rule is "ambiguous" (with the candidates: "station" could be any
of six); nothing at all is "unknown" (with the closest names).
"""

from __future__ import annotations

import difflib
import json
import re
import xml.etree.ElementTree as ET
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..core import gestures
from ..core.world import Marker
from ..hearing.vocabulary import Vocabulary
from ..maps.markers import load_markers
from .intents import FIND, GESTURE, NAVIGATE, PICK, TaskIntent
from .numbers import digits_for_words

# The lab's graspable objects: skills/objects.json and the bodies with a free joint in
# sim/scenes/lab.xml (body names are the detector's labels).
DEFAULT_OBJECTS: tuple[str, ...] = ("bottle", "cup", "apple", "book", "screwdriver")
PEOPLE = "person"  # the detector's label for people; findable, never pickable

MARKER_SYNONYMS: dict[str, tuple[str, ...]] = {
    "charging dock": ("charger", "charging station", "charging point", "charging pad", "docking station",
                      "dock", "base", "home", "home base", "recharge station", "power station", "charging bay"),
    "bathroom": ("toilet", "toilets", "restroom", "rest room", "loo", "washroom", "wc", "lavatory", "bath room",
                 "mens room", "ladies room", "ladies", "gents", "powder room", "bath"),
    "entrance": ("door", "front door", "main door", "entry", "main entrance", "exit", "way out", "way in",
                 "lobby", "entryway", "front", "doorway"),
    "kitchen": ("kitchenette", "galley", "pantry", "kitchen counter", "kitchen table", "break room"),
    "workbench": ("work bench", "work station", "workstation", "tool bench", "workshop"),
}
OBJECT_SYNONYMS: dict[str, tuple[str, ...]] = {
    "cup": ("mug", "coffee cup", "tea cup", "teacup", "beaker", "tumbler"),
    "bottle": ("water bottle", "flask", "drink", "water", "soda", "bottle of water"),
    "book": ("novel", "notebook", "textbook", "manual"),
    "screwdriver": ("screw driver", "driver"),
    "apple": ("fruit",),
    PEOPLE: ("people", "someone", "somebody", "human", "a person", "man", "woman", "visitor", "visitors",
             "anyone", "anybody", "me", "user", "guest", "guests", "child", "kid"),
}
FILLER_WORDS = frozenset({"area", "zone", "room", "place", "spot", "region", "part", "section", "side", "space",
                          "location", "point", "corner", "over", "there", "please", "position", "bit", "number",
                          "marker", "waypoint", "stop"})
DETERMINERS = frozenset({"the", "a", "an", "your", "my", "our", "this", "that", "these", "those", "some", "its",
                         "their", "his", "her", "to"})
PRONOUNS = frozenset({"it", "them", "that", "this", "there", "those", "these", "one", "thing", "that one"})
_WORD = re.compile(r"[^\W_]+")
FUZZY_CUTOFF = 0.8
TIE = 0.02  # fuzzy scores closer than this are a tie


@dataclass(frozen=True)
class Resolution:
    """What a spoken target resolved to. ``name`` is the marker name / object label / gesture
    library name, or ``None``; ``how`` says which rule matched ("exact", "display name",
    "synonym", "filler dropped", "partial", "fuzzy", "head noun", "library"), or "unknown" /
    "ambiguous"; ``candidates`` are the tie or the closest valid names."""

    spoken: str
    kind: str  # "marker", "object" or "gesture"
    name: str | None
    how: str
    reason: str
    candidates: tuple[str, ...] = ()
    labels: tuple[str, ...] = field(default=(), compare=False)  # how to say the candidates

    @property
    def ok(self) -> bool:
        return self.name is not None

    def say(self) -> str:
        """A sentence for the robot to speak when the target did not resolve."""
        if self.ok:
            return ""
        words = self.spoken.lower().split()
        while len(words) > 1 and words[0] in DETERMINERS:
            words = words[1:]
        spoken = " ".join(words) or "that"
        said = _or_list(self.labels or self.candidates)
        if self.how == "ambiguous":
            return f"Which {spoken} do you mean: {said}?"
        if self.kind == "marker":
            head = f"I don't know where the {spoken} is."
        elif self.kind == "gesture":
            head = f"I don't know the gesture {spoken}."
        else:
            head = f"I don't know what {spoken} means." if spoken in PRONOUNS else f"I don't know any {spoken}."
        return f"{head} Did you mean {said}?" if said else head

    def to_dict(self) -> dict[str, Any]:
        return {"spoken": self.spoken, "kind": self.kind, "name": self.name, "ok": self.ok, "how": self.how,
                "reason": self.reason, "candidates": list(self.candidates), "say": self.say()}


def _spoken_label(name: str, display: str) -> str:
    """How the robot says a marker: its display name, with the name when that adds something
    ("Robot arms (station 1)")."""
    spaced = name.replace("_", " ")
    if not display or display.lower() == spaced.lower():
        return display or spaced
    return f"{display} ({spaced})"


def _or_list(items: Iterable[str]) -> str:
    items = list(items)
    if len(items) <= 1:
        return "".join(items)
    return ", ".join(items[:-1]) + " or " + items[-1]


def _digits(text: str) -> list[str]:
    return re.findall(r"\d+", text)


def _singular(word: str) -> str:
    if len(word) > 3 and word.endswith("s") and not word.endswith("ss") and not word.endswith("us"):
        return word[:-3] + "y" if word.endswith("ies") else word[:-1]
    return word


def normalise(text: str) -> tuple[str, ...]:
    """Comparable words: lower case, no determiners, number words as digits, singulars
    ("The Third Station" -> ("3", "station"); "station three" -> ("station", "3"))."""
    words = [w for w in _WORD.findall(text.lower().replace("_", " ")) if w]
    while len(words) > 1 and words[0] in DETERMINERS:
        words = words[1:]
    words = digits_for_words(words)
    return tuple(_singular(w) for w in words if w not in ("number", "no"))


def _stem(word: str) -> str:
    """A word without the endings that make "printing" and "printer" differ ("print")."""
    for end in ("ing", "er"):
        if word.endswith(end) and len(word) > len(end) + 3:
            return word[:-len(end)]
    return word


class Resolver:
    """Maps spoken targets onto one map's markers and one detector's object labels.

    ``markers``: a ``{name: Marker}`` mapping (as :func:`stuart_bt.maps.markers.load_markers` returns),
    or plain names; ``objects``: object labels (default: the lab's, ``DEFAULT_OBJECTS``)."""

    def __init__(self, markers: Mapping[str, Marker] | Iterable[str] = (),
                 objects: Iterable[str] = DEFAULT_OBJECTS) -> None:
        if isinstance(markers, Mapping):  # name -> display name
            self.markers: dict[str, str] = {name: m.display_name if isinstance(m, Marker) else str(m or "")
                                            for name, m in markers.items()}
        else:
            self.markers = {name: "" for name in markers}
        self.labels = {name: _spoken_label(name, display) for name, display in self.markers.items()}
        self.objects: tuple[str, ...] = tuple(dict.fromkeys(o.lower() for o in objects))
        self._marker_aliases = self._aliases_for_markers()
        self._object_aliases = self._aliases_for_objects()

    @classmethod
    def from_files(cls, markers_file: str | Path | None = None, objects_file: str | Path | None = None) -> Resolver:
        markers = load_markers(markers_file) if markers_file else {}
        objects = load_object_labels(objects_file) if objects_file else DEFAULT_OBJECTS
        return cls(markers, objects)

    def vocabulary(self, name: str = "Stuart") -> Vocabulary:
        """The words to expect when hearing (docs/hearing.md): these places (names and display
        names), these object labels, and the gesture library; resolving and hearing then agree."""
        places = [n.replace("_", " ") for n in self.markers] + [d for d in self.markers.values() if d]
        return Vocabulary.of(name, places, self.objects, gestures.names())

    # -- tables ------------------------------------------------------------------------------------
    def _aliases_for_markers(self) -> dict[tuple[str, ...], dict[str, str]]:
        """alias words -> {marker name: how}."""
        table: dict[tuple[str, ...], dict[str, str]] = {}

        def add(words: tuple[str, ...], name: str, how: str) -> None:
            if words:
                table.setdefault(words, {}).setdefault(name, how)

        for name, label in self.markers.items():
            spaced = normalise(name)
            add(spaced, name, "exact")
            add(("".join(spaced),), name, "exact")
            if label:
                add(normalise(label), name, "display name")
                add(("".join(normalise(label)),), name, "display name")
            m = re.fullmatch(r"(.+?)[ _]?(\d+)", name)
            if m:  # station_3: "3rd station", "station number 3"
                add((m.group(2), *normalise(m.group(1))), name, "exact")
        for canonical, synonyms in MARKER_SYNONYMS.items():
            owners = table.get(normalise(canonical), {})
            for name in owners:
                for syn in synonyms:
                    add(normalise(syn), name, "synonym")
        return table

    def _aliases_for_objects(self) -> dict[tuple[str, ...], str]:
        table: dict[tuple[str, ...], str] = {}
        for label in (*self.objects, PEOPLE):
            table.setdefault(normalise(label), label)
            table.setdefault(("".join(normalise(label)),), label)
        for canonical, synonyms in OBJECT_SYNONYMS.items():
            if canonical in self.objects or canonical == PEOPLE:
                for syn in synonyms:
                    table.setdefault(normalise(syn), canonical)
        return table

    # -- markers -----------------------------------------------------------------------------------
    def marker(self, spoken: str) -> Resolution:
        """The marker a spoken place names (see the module notes for the rules)."""
        words = normalise(spoken)
        if not self.markers:
            return Resolution(spoken, "marker", None, "unknown", "no marker file loaded")
        if not words or " ".join(words) in PRONOUNS:
            return self._unknown_marker(spoken, words, f"{spoken!r} does not name a place")
        for attempt, stripped in ((words, False), (tuple(w for w in words if w not in FILLER_WORDS), True)):
            if not attempt:
                continue
            hits = self._marker_aliases.get(attempt) or self._marker_aliases.get(("".join(attempt),))
            if hits:
                return self._pick_marker(spoken, hits, "filler dropped" if stripped else None)
        hits = self._partial(words)
        if hits:
            return self._pick_marker(spoken, hits, None)
        fuzzy = self._fuzzy(" ".join(words), {" ".join(a): names for a, names in self._marker_aliases.items()})
        if fuzzy:
            return self._pick_marker(spoken, fuzzy, None)
        if words in self._object_aliases or (words and words[-1] in self.objects):
            return self._unknown_marker(spoken, words, f"{spoken!r} is an object, not a place on the map")
        return self._unknown_marker(spoken, words, f"no marker matches {spoken!r}")

    def _partial(self, words: tuple[str, ...]) -> dict[str, str]:
        spoken = set(words) - FILLER_WORDS
        if not spoken:
            return {}
        own = [(alias, names) for alias, names in self._marker_aliases.items()
               if any(how != "synonym" for how in names.values())]  # synonyms are matched whole only
        inside = {name: "partial" for alias, names in own if spoken <= set(alias) for name in names}
        if inside:
            return inside
        # "the 3D printing station", "the arms station": the same stems, "station" with no number
        # naming none ("station 2" is a number's place)
        numbered = any(w.isdigit() for w in words)
        stems = {_stem(w) for w in spoken if not (w == "station" and not numbered)}
        inside = {name: "partial" for alias, names in own if stems and stems <= {_stem(w) for w in alias}
                  for name in names}
        if inside:
            return inside
        return {name: "partial" for alias, names in own
                if set(alias) <= set(words) and not set(alias) <= FILLER_WORDS for name in names}

    @staticmethod
    def _fuzzy(key: str, pool: Mapping[str, Mapping[str, str]]) -> dict[str, str]:
        scored: list[tuple[float, str]] = []
        digits = _digits(key)
        for alias, names in pool.items():
            if _digits(alias) != digits:
                continue  # "station 7" is not a misspelt "station 3"
            r = difflib.SequenceMatcher(None, key, alias).ratio()
            if r >= FUZZY_CUTOFF:
                scored.extend((r, name) for name in names)
        if not scored:
            return {}
        best = max(r for r, _ in scored)
        return {name: f"fuzzy {r:.2f}" for r, name in scored if r >= best - TIE}

    def _pick_marker(self, spoken: str, hits: Mapping[str, str], note: str | None) -> Resolution:
        if len(hits) == 1:
            name, how = next(iter(hits.items()))
            how = note if note and how in ("exact", "display name") else how
            return Resolution(spoken, "marker", name, how, f"{spoken!r} is marker {name!r} ({how})")
        names = tuple(sorted(hits))
        return Resolution(spoken, "marker", None, "ambiguous", f"{spoken!r} could be any of {', '.join(names)}",
                          names, tuple(self.labels[n] for n in names))

    def _unknown_marker(self, spoken: str, words: tuple[str, ...], reason: str) -> Resolution:
        close = self._closest(" ".join(words), {" ".join(a): names for a, names in self._marker_aliases.items()})
        names = close or tuple(self.markers)[:6]
        return Resolution(spoken, "marker", None, "unknown", reason, names, tuple(self.labels[n] for n in names))

    @staticmethod
    def _closest(key: str, pool: Mapping[str, Iterable[str]], n: int = 3) -> tuple[str, ...]:
        out: list[str] = []
        for alias in difflib.get_close_matches(key, list(pool), n=8, cutoff=0.45):
            for name in pool[alias]:
                if name not in out:
                    out.append(name)
        return tuple(out[:n])

    # -- objects -----------------------------------------------------------------------------------
    def object(self, spoken: str, *, findable: bool = False) -> Resolution:
        """The object label a spoken object names: label, plural, synonym ("mug" -> cup), head
        noun ("the red cup" -> cup), spelling. ``findable`` also accepts people."""
        words = normalise(spoken)
        if not words or " ".join(words) in PRONOUNS:
            return Resolution(spoken, "object", None, "unknown", f"{spoken!r} does not say which object",
                              self.objects[:3])
        label = self._object_aliases.get(words) or self._object_aliases.get(("".join(words),))
        how = "exact" if label and words == normalise(label) else "synonym"
        if label is None and words[-1:] and (label := self._object_aliases.get(words[-1:])) is not None:
            how = "head noun"
        if label is None:
            fuzzy = self._fuzzy(" ".join(words), {" ".join(a): {lab: ""} for a, lab in self._object_aliases.items()})
            if len(fuzzy) == 1:
                label, how = next(iter(fuzzy)), next(iter(fuzzy.values()))
        if label == PEOPLE and not findable:
            return Resolution(spoken, "object", None, "unknown", "people cannot be picked up", self.objects[:3])
        if label is not None:
            return Resolution(spoken, "object", label, how, f"{spoken!r} is object {label!r} ({how})")
        pool = {" ".join(a): [lab] for a, lab in self._object_aliases.items() if lab != PEOPLE or findable}
        close = self._closest(" ".join(words), pool) or self.objects[:3]
        reason = f"no object label matches {spoken!r}"
        if self.markers and self._marker_aliases.get(words):
            reason = f"{spoken!r} is a place, not an object"
        return Resolution(spoken, "object", None, "unknown", reason, close)

    # -- gestures ----------------------------------------------------------------------------------
    @staticmethod
    def gesture(spoken: str) -> Resolution:
        g = gestures.lookup(spoken)
        if g is None:
            close = tuple(difflib.get_close_matches(spoken.lower(), gestures.names(), n=3, cutoff=0.5))
            return Resolution(spoken, "gesture", None, "unknown", f"no gesture called {spoken!r}", close)
        plays = f"{spoken!r} plays {g.name!r} (action id {g.action_id})"
        return Resolution(spoken, "gesture", g.name, "library", plays)

    # -- intents -----------------------------------------------------------------------------------
    def resolve(self, intent: TaskIntent) -> Resolution | None:
        """The resolution of an intent's target; ``None`` for actions without one (move, turn,
        stop). A find may name an object, a person or a place."""
        a = intent.action
        if a == NAVIGATE:  # a place on the map, or else an object to walk up to ("go to the bottle")
            place = self.marker(intent.target)
            if not place.ok and self.objects:
                thing = self.object(intent.target)
                if thing.ok:
                    return thing
            return place
        if a == PICK:
            return self.object(intent.target)
        if a == GESTURE:
            return self.gesture(intent.target)
        if a == FIND:
            found = self.object(intent.target, findable=True)
            if not found.ok and self.markers:
                place = self.marker(intent.target)
                if place.ok:
                    return place
            return found
        return None

    def resolve_all(self, intents: Iterable[TaskIntent]) -> list[Resolution | None]:
        return [self.resolve(i) for i in intents]


def load_object_labels(path: str | Path) -> tuple[str, ...]:
    """Object labels from a file: skills/objects.json (``{"objects": {label: ...}}``), a JSON list
    of labels, or a MuJoCo scene (.xml: the bodies with a free joint, which are the graspable
    objects and whose names are the detector's labels)."""
    path = Path(path)
    text = path.read_text(encoding="utf-8")
    if path.suffix.lower() == ".xml":
        try:
            root = ET.fromstring(text)
        except ET.ParseError as e:
            raise ValueError(f"{path}: not valid XML: {e}") from None
        return tuple(b.get("name", "") for b in root.iter("body") if b.find("freejoint") is not None and b.get("name"))
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as e:
        raise ValueError(f"{path}:{e.lineno}:{e.colno}: not valid JSON: {e.msg}") from None
    if isinstance(doc, dict) and isinstance(doc.get("objects"), dict):
        return tuple(str(k) for k in doc["objects"])
    if isinstance(doc, list) and all(isinstance(x, str) for x in doc):
        return tuple(doc)
    raise ValueError(f"{path}: expected {{\"objects\": {{label: ...}}}} or a list of labels")
