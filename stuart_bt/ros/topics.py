"""What the bridge publishes, decided from events alone (no rclpy here, so it is testable anywhere).

:class:`EventTranslator` reads one :class:`~stuart_bt.core.events.Event` at a time and says which
messages it makes, as :class:`Outgoing` values (a topic key and a plain payload); the node turns
them into ROS messages on the ROS thread. Topic names are relative, so ``--namespace`` prefixes
them all. The message formats are documented in docs/ros.md.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..core.events import Event
from ..core.jsonfile import to_json

# topic key -> relative topic name (the original system's names; docs/ros.md)
AUDIO_IN = "audio_msg"  # raw speech-recogniser text: the wake filter applies
LLM_INPUT = "llm/input"  # already wake-filtered text
MISSION_IN = "stuart/mission"  # an utterance without the wake phrase, from any machine
PICK_TARGET = "pick_target"  # an object label, or "confirm" for the pick confirmation gate
TASK_INTENT = "llm/task_intent"
RESPONSE = "llm/response"
STATUS = "bt/status"
EVENTS = "bt/events"
POSE = "robot_pose"
MEMORY_SUMMARY = "spatial_memory/summary"
MEMORY_MARKERS = "spatial_memory/markers"

MAP_FRAME = "map"
CONFIRM_WORDS = frozenset({"confirm", "confirmed", "yes", "go ahead"})


@dataclass(frozen=True)
class Outgoing:
    """One message to publish: ``topic`` is a key above, ``payload`` a str (String topics), a pose
    dict ``{x, y, yaw}`` (POSE) or a list of object dicts (MEMORY_MARKERS)."""

    topic: str
    payload: Any


class EventTranslator:
    """Events in, messages out. One per bridge; called on the ROS thread, in event order.

    - ``utterance`` -> one TaskIntent JSON per intent on TASK_INTENT (the ``stuart-bt parse``
      objects, a leading "stop" included), in the order they were said;
    - ``command`` tts ``say`` -> RESPONSE with the spoken text; when it is a conversation
      ``reply`` that carried gestures, their tags follow it (``"Hello! [high wave]"``);
    - ``heard`` (speech this process heard and acted on, from a source other than ROS itself) ->
      AUDIO_IN with its text, as the robot's recogniser published it in the original system;
    - ``pose`` -> POSE; ``memory`` (perception's spatial memory summary, after a ``find``) ->
      MEMORY_SUMMARY (the summary itself) and MEMORY_MARKERS (its well-formed objects);
    - every event -> EVENTS, as its JSON-lines log line.
    """

    def __init__(self) -> None:
        self._tagged: dict[str, list[str]] = {}  # reply text -> its gestures, until it is spoken

    def translate(self, event: Event) -> list[Outgoing]:
        out: list[Outgoing] = []
        d = event.data
        if event.kind == "utterance":
            intents = d.get("parsed") if d.get("parsed") is not None else d.get("intents")
            out += [Outgoing(TASK_INTENT, to_json(i, ensure_ascii=False)) for i in intents or []]
        elif event.kind == "reply" and d.get("gestures"):
            self._tagged[str(d.get("text", ""))] = [str(g) for g in d["gestures"]]
        elif event.kind == "command" and d.get("family") == "tts" and d.get("cmd") == "say":
            text = str((d.get("args") or {}).get("text") or "")
            if text:
                tags = self._tagged.pop(text, [])
                out.append(Outgoing(RESPONSE, " ".join([text, *(f"[{g}]" for g in tags)])))
        elif event.kind == "heard" and d.get("acted") and not str(d.get("source", "")).startswith("ros:"):
            out.append(Outgoing(AUDIO_IN, str(d.get("text", ""))))
        elif event.kind == "pose" and all(isinstance(d.get(k), (int, float)) for k in ("x", "y")):
            out.append(Outgoing(POSE, {"x": float(d["x"]), "y": float(d["y"]), "yaw": float(d.get("yaw") or 0.0)}))
        elif event.kind == "memory":  # the stuart_bt.memory/1 summary (docs/perception.md), as it is
            out.append(Outgoing(MEMORY_SUMMARY, to_json(d, ensure_ascii=False, default=str)))
            out.append(Outgoing(MEMORY_MARKERS, memory_objects(d)))
        out.append(Outgoing(EVENTS, event.to_json()))
        return out


def memory_objects(data: dict[str, Any]) -> list[dict[str, Any]]:
    """The objects of a ``memory`` event that have a label and a map position, each with an ``id``
    (the memory's own, e.g. ``bottle_1``, else its label); the rest of each object's fields
    (confidence, last_seen, ...) are kept as they are."""
    objects = data.get("objects")
    if isinstance(objects, dict):  # {label: {x, y, z, ...}} is accepted too
        objects = [{"label": k, **v} for k, v in objects.items() if isinstance(v, dict)]
    good = []
    for obj in objects if isinstance(objects, list) else []:
        if isinstance(obj, dict) and obj.get("label") and all(isinstance(obj.get(k), (int, float)) for k in ("x", "y")):
            good.append({**obj, "id": str(obj.get("id") or obj["label"]), "label": str(obj["label"]),
                         "z": float(obj.get("z") or 0.0)})
    return good
