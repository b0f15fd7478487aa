"""The words the robot expects to hear, given to the recogniser as context.

A small general recogniser knows nothing of this lab: without help, ``tiny.en`` heard "turn
left, I need a reason" and "Hey Stewart Wayne". Whisper-style recognisers take a *prompt*, text
they treat as what was said just before; a prompt in the shape of the commands people give,
naming this robot, these places, these objects and these gestures, makes those words the likely
ones. The vocabulary comes from the same files the grammar resolves against (markers, object
labels, the gesture library), so a new marker is heard as soon as it is on the map.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

PROMPT_CHARS = 600  # whisper keeps the last ~224 prompt tokens; a longer prompt only costs time


@dataclass(frozen=True)
class Vocabulary:
    """The robot's name, and the places, objects and gestures it knows (as people say them)."""

    name: str = "Stuart"
    places: tuple[str, ...] = ()
    objects: tuple[str, ...] = ()
    gestures: tuple[str, ...] = ()
    extra: tuple[str, ...] = field(default=())  # any other words to expect (people's names, ...)

    @classmethod
    def of(cls, name: str = "Stuart", places: Iterable[str] = (), objects: Iterable[str] = (),
           gestures: Iterable[str] = (), extra: Iterable[str] = ()) -> Vocabulary:
        """Deduplicated, in the order given, lower case except the robot's name."""
        def clean(words: Iterable[str]) -> tuple[str, ...]:
            return tuple(dict.fromkeys(w.strip().replace("_", " ") for w in words if w and w.strip()))
        return cls(name, clean(places), clean(objects), clean(gestures), clean(extra))

    def to_dict(self) -> dict[str, object]:
        """Plain JSON (a daemon option); :meth:`of` takes it back."""
        return {"name": self.name, "places": list(self.places), "objects": list(self.objects),
                "gestures": list(self.gestures), "extra": list(self.extra)}

    def prompt(self) -> str:
        """Context text for the recogniser: commands in the form people say them, naming every
        place, object and gesture once, and the amounts and units the grammar reads."""
        where = f"go to the {_either(self.places)}" if self.places else "go there"
        parts = [f"Hey {self.name}, {where}.", "Walk forward two metres, turn left 90 degrees, stop."]
        if self.objects:
            parts.append(f"Pick up the {_either(self.objects)}; find the {self.objects[0]}.")
        if self.gestures:
            parts.append(f"{_either(self.gestures).capitalize()}.")
        if self.extra:
            parts.append(", ".join(self.extra) + ".")
        text = " ".join(parts)
        return text if len(text) <= PROMPT_CHARS else text[:PROMPT_CHARS].rsplit(" ", 1)[0]

    def words(self) -> list[str]:
        """Every word the vocabulary names, once (for a command-only grammar engine)."""
        seen: dict[str, None] = {}
        for phrase in (self.name, *self.places, *self.objects, *self.gestures, *self.extra):
            for word in phrase.lower().split():
                seen.setdefault(word, None)
        return list(seen)


def _either(items: tuple[str, ...]) -> str:
    if len(items) <= 1:
        return "".join(items)
    return ", ".join(items[:-1]) + " or " + items[-1]
