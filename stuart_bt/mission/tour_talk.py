"""Talking to the robot while a tree runs (a tour): questions are answered, "stop" pauses it,
"continue" goes on.

The original tour guide could not react to its audience. Here a tree run by ``stuart-bt run``
takes utterances (typed with ``--talk``, or heard with ``--hear``) while it ticks:

- "Hey Stuart, what happens in the drone cage?" is answered at the next pause in the robot's
  speech: the tour holds (the walk stops, the gesture ends), the answer is spoken, and the tour
  goes on from the step it was at (that step starts again);
- "Hey Stuart, stop" holds the tour at the next tick, motion stopped, until "continue";
- a command ("go to the kitchen") is not run in the middle of a tour: the robot says so.

Answers come from facts first (:mod:`stuart_bt.conversation.facts`), the conversation backend for
the rest (on a thread of its own: the tick thread never waits on a model). Everything the robot
is asked to do with its daemons happens on the tick thread, in a pre-tick duty.
"""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Mapping
from concurrent.futures import ThreadPoolExecutor
from typing import TYPE_CHECKING, Any

from ..conversation.facts import FactAnswers, Situation, checked_reply
from ..conversation.prompt import load_knowledge
from .attention import Attention
from .commands import CONTINUE, CONVERSATION, IGNORE, STOP, Command, interpret
from .replies import COULD_NOT_ANSWER, situation_now, warn_unanswered

if TYPE_CHECKING:
    from ..conversation.reply import Conversation
    from ..daemon.client import Request
    from ..language import Parser, Resolver
    from ..run.executor import Executor
    from ..run.session import Session

BUSY_WITH_TOUR = "I'm in the middle of the tour. Say stop first, and I'll listen."


class TourTalk:
    """Utterances for a running tree. ``submit`` may be called from any thread."""

    def __init__(self, session: Session, executor: Executor, parser: Parser, resolver: Resolver,
                 conversation: Conversation | None = None) -> None:
        self.session, self.executor = session, executor
        self.parser, self.resolver = parser, resolver
        self.events = session.events
        self.attention = Attention()
        self.conversation = conversation
        self.facts = FactAnswers(getattr(conversation, "knowledge", None) or load_knowledge())
        self._answers: deque[str] = deque()  # to say at the next pause in speech
        self._lock = threading.Lock()
        self._stopped_by_user = False
        self._hush = False  # a stop said while an answer is spoken ends the answer too
        self._answering: Request | None = None  # the answer being spoken (tick thread only)
        self._thinking = ThreadPoolExecutor(max_workers=1, thread_name_prefix="tour-talk")
        executor.pre_tick.append(self._duties)

    def close(self) -> None:
        self._thinking.shutdown(wait=False, cancel_futures=True)

    @property
    def stopped_by_user(self) -> bool:
        """"Stop" was said and no "continue" since: the tree waits for a person, not for an answer."""
        with self._lock:
            return self._stopped_by_user

    # -- input (any thread) ---------------------------------------------------------------------------
    def submit(self, utterance: str, woken: bool = False, *, source: str = "typed",
               heard: Mapping[str, Any] | None = None) -> Command:
        held = self.attention.take() and not woken
        command = interpret(self.parser, utterance, woken or held)
        self.attention.after(command)
        self.events.publish("utterance", text=utterance, kind=command.kind, source=source,
                            intents=[i.to_dict() for i in command.intents],
                            parsed=[i.to_dict() for i in command.parse.intents], **(heard or {}))
        if command.kind == STOP:
            with self._lock:
                self._stopped_by_user = self._hush = True
                self._answers.clear()
            self.executor.hold(f"stop said: {command.text}")
        elif command.kind == CONTINUE:
            with self._lock:
                self._stopped_by_user = False
                speaking = self._answering is not None or bool(self._answers)
            if not speaking:
                self.executor.resume()
        elif command.kind == CONVERSATION:
            self._thinking.submit(self._answer, command.text)
        elif command.kind != IGNORE:
            self._queue(BUSY_WITH_TOUR, command.text, "tour")
        return command

    def _answer(self, text: str) -> None:
        """On the thinking thread, whose errors would vanish with its future: a question that
        cannot be answered still gets a reply, and a warning says why."""
        try:
            self._answer_now(text)
        except Exception as e:  # noqa: BLE001 - anything, or the person waits for an answer forever
            warn_unanswered(self.events, text, e)
            self._queue(COULD_NOT_ANSWER, text, "error")

    def _answer_now(self, text: str) -> None:
        situation = self._situation()
        known = self.facts.answer(text, situation)
        if known is not None:
            self._queue(known, text, "facts")
        elif self.conversation is not None:
            reply = self.conversation.reply(text, {"at": self.session.blackboard.world.last_marker, "busy": True})
            self._queue(checked_reply(reply.text, situation), text, "model")

    def _queue(self, sentence: str, to: str, source: str) -> None:
        self.events.publish("reply", text=sentence, gestures=[], to=to, source=source)
        self._answers.append(sentence)

    def _situation(self) -> Situation:
        situation = situation_now(self.session.blackboard.world, None, [])
        situation.doing = f"giving the tour ({self.session.spec.file})"
        return situation

    # -- duties (tick thread, before every tick and while held) ----------------------------------------
    def _duties(self) -> None:
        supervisor = self.session.supervisor
        if supervisor is None or "tts" not in supervisor.families:
            self._answers.clear()  # nothing to say them with
            return
        with self._lock:
            hush, self._hush = self._hush, False
        if hush and self._answering is not None and not self._answering.finished:
            supervisor.client("tts").stop()
        if self._answering is not None:
            if not self._answering.finished:
                return
            self._answering = None
            with self._lock:
                go_on = not self._stopped_by_user and not self._answers
            if go_on:
                self.executor.resume()
            return
        if not self._answers:
            return
        tts = supervisor.client("tts")
        if not self.executor.held and any(r.cmd == "say" for r in tts.in_flight):
            return  # the tour is speaking: answer at its next pause
        if not self.executor.paused:
            self.executor.hold("answering a question")
            return  # the next tick pauses the tree (and stops its speech and motion); then speak
        self._answering = tts.request("say", {"text": self._answers.popleft()}, path="reply")
