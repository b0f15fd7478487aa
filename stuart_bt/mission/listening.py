"""Hearing in front of a mission executor: what is heard is said, like typed text.

A :class:`Listener` runs the hearing pipeline (source -> utterances -> transcripts,
:mod:`stuart_bt.hearing`) on its own thread and submits each transcript to the executor with
where it came from and how sure the recogniser was, so missions, chat, the web view, the report
and the ROS bridge work from speech unchanged. Every utterance heard is also a ``heard`` event,
the ones not acted on included, with the reason.

**The robot's own voice never commands it.** :class:`RobotVoice` follows the tts daemon's
requests on the event stream; while one is playing, the segmenter marks what it cuts, and such
an utterance is acted on only when it is a stop ("Hey Stuart, stop" while the robot talks:
barge-in). Anything else heard then is dropped as ``over_robot_speech``.
"""

from __future__ import annotations

import math
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..core.events import Event, EventStream
from ..hearing.audio import AudioError
from ..hearing.pipeline import Heard, hear
from ..hearing.vad import Segmenter
from ..language.readings import choose_reading, rival_reading
from .commands import STOP, interpret

if TYPE_CHECKING:
    from ..hearing.recognisers import Recogniser
    from ..hearing.sources import Source
    from ..hearing.vocabulary import Vocabulary
    from .commands import Command
    from .executor import MissionExecutor

SPEECH_COMMANDS = ("say",)  # tts commands during which the robot's voice is in the room


class RobotVoice:
    """Whether the robot is talking now, read from the event stream (no reach into the executor):
    a tts ``say`` command starts it, that request's ``done`` or ``error`` (or a tts ``stop``)
    ends it. ``on_change(speaking)`` is called on every change."""

    def __init__(self, events: EventStream, on_change: Callable[[bool], None] | None = None) -> None:
        self._playing: set[str] = set()
        self._lock = threading.Lock()
        self._on_change = on_change or (lambda speaking: None)
        self._spans: deque[list[float]] = deque(maxlen=64)  # [start, end] perf_counter s (end inf: still talking)
        events.subscribe(self.on_event)

    def spoke_over(self, start: float, end: float) -> bool:
        """Was the robot talking over most of [start, end] (``perf_counter`` seconds), or when it
        began? The judgement the segmenter makes frame by frame, for an utterance that was cut
        elsewhere (the robot's own ears cut in their daemon and say only when it ended)."""
        with self._lock:
            spans = [(a, b) for a, b in self._spans if b > start and a < end]
        began_over = any(a <= start < b for a, b in spans)
        overlap = sum(min(b, end) - max(a, start) for a, b in spans)
        return began_over or 2 * overlap > end - start

    @property
    def speaking(self) -> bool:
        with self._lock:
            return bool(self._playing)

    def on_event(self, event: Event) -> None:
        d = event.data
        if d.get("family") != "tts" or event.kind not in ("command", "daemon"):
            return
        with self._lock:
            before = bool(self._playing)
            if event.kind == "command" and d.get("cmd") in SPEECH_COMMANDS:
                self._playing.add(str(d.get("id")))
            elif event.kind == "command" and d.get("cmd") == "stop":
                self._playing.clear()
            elif event.kind == "daemon" and d.get("type") in ("done", "error"):
                self._playing.discard(str(d.get("id")))
            now = bool(self._playing)
            if now != before:
                self._mark(now)
        if now != before:
            self._on_change(now)

    def _mark(self, speaking: bool) -> None:
        if speaking:
            self._spans.append([time.perf_counter(), math.inf])
        elif self._spans:
            self._spans[-1][1] = time.perf_counter()


class Listener:
    """Hears ``source`` until it ends or :meth:`close`, submitting what it hears to ``robot``."""

    def __init__(self, robot: MissionExecutor, source: Source, recogniser: Recogniser,
                 vocabulary: Vocabulary | None = None, segmenter: Segmenter | None = None) -> None:
        self.robot = robot
        self.source = source
        self.recogniser = recogniser
        self.vocabulary = vocabulary
        self.segmenter = segmenter or Segmenter()
        self.voice = RobotVoice(robot.events, self._robot_speaking)
        self.error: str | None = None
        self.done = threading.Event()
        self._thread = threading.Thread(target=self._run, name="hearing", daemon=True)

    def start(self) -> Listener:
        self._thread.start()
        return self

    def close(self, timeout: float = 5.0) -> None:
        """Stop hearing: the source is closed, the thread ends after the utterance in hand."""
        self.source.close()
        if self._thread.is_alive():
            self._thread.join(timeout)

    def _robot_speaking(self, speaking: bool) -> None:
        self.segmenter.speaking = speaking

    def _run(self) -> None:
        try:
            for heard in hear(self.source, self.recogniser, self.vocabulary, self.segmenter):
                self.take(heard)
        except AudioError as e:
            self.error = e.reason
            self.robot.events.publish("warning", message=f"hearing stopped: {e.reason}")
        finally:
            self.done.set()

    def take(self, heard: Heard) -> None:
        """Act on one utterance heard (also called directly by a source that hears on its own)."""
        take_heard(self.robot, heard)


def take_heard(robot: MissionExecutor, heard: Heard) -> Command | None:
    """Submit one utterance heard to ``robot`` like typed text, with a ``heard`` event; what was
    heard over the robot's own voice is dropped unless it is a stop. Shared by the
    :class:`Listener` and the web console's push-to-talk, so speech is judged the same way
    whatever brought it; returns what it was understood as (None when dropped)."""
    return act_on_heard(robot, hearing_fields(heard))


def act_on_heard(robot: MissionExecutor, fields: dict[str, Any]) -> Command | None:
    """:func:`take_heard` for an utterance described by its :func:`hearing_fields` (the robot's
    own ears describe what they heard in a daemon's progress line, not as a :class:`Heard`).
    With the recogniser's other ``readings``, the one to act on is chosen first
    (:func:`~stuart_bt.language.readings.choose_reading`); ``recognised`` then keeps its best."""
    return act_on_reading(robot, chosen_reading(robot, fields))


def act_on_reading(robot: MissionExecutor, fields: dict[str, Any]) -> Command | None:
    """:func:`act_on_heard` once the reading to act on is ``fields["text"]`` (:func:`chosen_reading`)."""
    if fields["over_robot_speech"]:
        command = interpret(robot.parser, fields["text"], robot.attention.held())
        if command.kind != STOP:
            robot.attention.after(command)  # "Hey Stuart" ... "stop", cut in two over the robot's voice
            robot.events.publish("heard", acted=False, reason="over_robot_speech", **fields)
            return None
    robot.events.publish("heard", acted=True, **fields)
    return robot.submit(fields["text"], source=fields["source"],
                        heard={**{k: fields.get(k) for k in HEARD_IN_UTTERANCE},
                               **({"rival_reading": fields["rival_reading"]} if "rival_reading" in fields else {})})


def chosen_reading(robot: MissionExecutor, fields: dict[str, Any]) -> dict[str, Any]:
    """``fields`` with ``text`` the reading to act on (and ``recognised`` the recogniser's best,
    when that is another)."""
    readings = [(str(r[0]), float(r[1])) for r in fields.get("readings") or []]
    index = choose_reading(readings, robot.parser, robot.resolver) if readings else 0
    rival = rival_reading(readings, index, robot.parser, robot.resolver) if readings else None
    if rival is not None:  # two readings that ask for different things: the robot asks which
        fields = {**fields, "rival_reading": readings[rival][0]}
    if index == 0:
        return fields
    return {**fields, "text": readings[index][0], "recognised": fields["text"]}


HEARD_IN_UTTERANCE = ("audio_s", "confidence", "no_speech", "latency_s", "engine")


def hearing_fields(heard: Heard) -> dict[str, Any]:
    """What an event says about an utterance heard (rounded; strict JSON)."""
    t = heard.transcript
    return {"text": heard.text, "source": heard.source, "audio_s": round(t.audio_s, 3),
            "confidence": round(t.confidence, 4), "no_speech": round(t.no_speech, 4),
            "latency_s": round(heard.latency_s, 3), "engine": t.engine, "start_s": round(heard.start_s, 3),
            "over_robot_speech": heard.over_robot_speech,
            **({"readings": [list(r) for r in t.readings()]} if t.alternatives else {})}
