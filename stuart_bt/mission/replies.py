"""Conversation: answering what is said to the robot that is not a command.

A :class:`~stuart_bt.conversation.reply.Conversation` may be slow (a language model), so replies
are thought about on a thread of their own and never hold up the mission worker or the tick
thread. The answer is queued to be said like any other job, or, while a mission runs, said at the
mission's next pause in speech (:meth:`Replies.say_aside`), so a question asked during a walk is
answered during the walk.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import TYPE_CHECKING, Any

from ..conversation.facts import FactAnswers, Situation, checked_reply, spoken_name
from ..conversation.prompt import load_knowledge
from ..conversation.reply import Reply
from .queue import Look, Mission, Say
from .running import look_tree

if TYPE_CHECKING:
    from ..conversation.reply import Conversation
    from ..core.events import EventStream
    from ..core.world import WorldState
    from ..run.session import Session
    from .queue import JobQueue

MAX_PENDING_REPLIES = 2  # questions being thought about at once; more talk meanwhile goes unanswered

COULD_NOT_ANSWER = "Sorry, I could not answer that."  # what the robot says when answering failed


def warn_unanswered(events: EventStream, text: str, error: Exception) -> None:
    """The warning that says why ``text`` got :data:`COULD_NOT_ANSWER` (answers are made on a
    thread of their own, where the error would otherwise vanish)."""
    events.publish("warning", message=f"could not answer {text[:60]!r}: {type(error).__name__}: {error}")


class Replies:
    """Replies to talk. ``offer`` may turn a request into a task proposal instead (True: it did);
    ``run_tree`` runs the one-leaf tree that looks before a question about what the robot sees."""

    def __init__(self, jobs: JobQueue, session: Session, conversation: Conversation,
                 offer: Callable[[str], bool], run_tree: Callable[..., Any]) -> None:
        self.jobs = jobs
        self.session = session
        self.conversation = conversation
        self.offer = offer
        self.run_tree = run_tree
        self._talk = ThreadPoolExecutor(max_workers=1, thread_name_prefix="conversation")
        self.facts = FactAnswers(getattr(conversation, "knowledge", None) or load_knowledge())
        self._unanswered = 0  # utterances let go while too many replies were pending
        self._last_unanswered_warning = float("-inf")

    def close(self) -> None:
        self._talk.shutdown(wait=False, cancel_futures=True)

    def converse(self, text: str) -> None:
        """Answer in the conversation thread; a question about what the robot sees, asked while
        it is idle, first gets one fresh look (an ``observe`` tree) so the answer is current.
        A robot answers one question at a time: while MAX_PENDING_REPLIES are being thought
        about, more talk is let go (a warning, at most one a second, counts it) instead of piling
        up replies that would keep the next command waiting."""
        from ..conversation.prompt import is_vision_question

        jobs = self.jobs
        with jobs.cond:
            if jobs.pending_replies >= MAX_PENDING_REPLIES:
                self._unanswered += 1
                now = time.monotonic()
                if now - self._last_unanswered_warning >= 1.0:
                    self._last_unanswered_warning = now
                    jobs.events.publish("warning", message=f"too much talk at once: {self._unanswered} "
                                        f"utterance(s) not answered so far (latest: {text[:60]!r})")
                return
            jobs.pending_replies += 1
            look_first = (is_vision_question(text) and jobs.current is None and not jobs.queue
                          and self.session.supervisor is not None and "vision" in self.session.supervisor.families)
            if look_first:
                jobs.queue.appendleft(Look(text))
                jobs.cond.notify_all()
        if not look_first:
            self.answer(text)

    def look_then_answer(self, question: str) -> None:
        """On the worker: one look, then the answer (``pending_replies`` was counted already)."""
        try:
            self.run_tree(look_tree(), None)  # a failed look leaves the memory as it was: still answer
        finally:
            self.answer(question)

    def answer(self, text: str) -> None:
        """Reply from the world state as it is now (the reply thread; ``pending_replies`` was
        counted by :meth:`converse`): from facts when the robot knows the answer, else from the
        conversation backend, its reply checked against what the robot knows."""
        from ..perception.context import seen_objects  # no cv2 or numpy: plain world-state reading

        jobs = self.jobs
        world = self.session.blackboard.world
        busy = jobs.current is not None and not isinstance(jobs.current, Look)
        seen = seen_objects(world, self.session.clock.now())
        context = {"held": world.held, "at": world.last_marker, "busy": busy, "detections": seen}
        situation = situation_now(world, jobs.current if busy else None, [d["label"] for d in seen])
        known = self.facts.answer(text, situation)

        def answer() -> None:
            try:
                if known is not None:
                    self._publish_reply(text, Reply(known), "facts")
                    return
                if self.offer(text):
                    return
                reply = self.conversation.reply(text, context)
                reply = Reply(checked_reply(reply.text, situation), list(reply.gestures))
                self._publish_reply(text, reply, "model")
            except Exception as e:  # noqa: BLE001 - on this thread an error would vanish, and nobody answer
                warn_unanswered(jobs.events, text, e)
                self._publish_reply(text, Reply(COULD_NOT_ANSWER), "error")
            finally:
                with jobs.cond:
                    jobs.pending_replies -= 1
                    jobs.cond.notify_all()

        self._talk.submit(answer)

    def _publish_reply(self, text: str, reply: Reply, source: str) -> None:
        """Said now, or at a running mission's next pause in speech."""
        jobs = self.jobs
        jobs.events.publish("reply", text=reply.text, gestures=list(reply.gestures), to=text, source=source)
        with jobs.cond:
            if isinstance(jobs.current, Mission) and jobs.executor is not None:
                jobs.asides.append(reply.text)  # said at the mission's next pause in speech
            else:
                jobs.queue_reply(Say(reply.text, "reply"))

    def say_aside(self) -> None:
        """Before a mission tick: a reply that is waiting goes to the speech daemon when the mission
        is not speaking, so a question asked during a walk is answered during the walk. The
        mission's own next speech takes the voice back (the daemon preempts the older one)."""
        supervisor = self.session.supervisor
        if not self.jobs.asides or supervisor is None or "tts" not in supervisor.families:
            return
        tts = supervisor.client("tts")
        if any(r.cmd == "say" for r in tts.in_flight):
            return
        with self.jobs.cond:
            text = self.jobs.asides.popleft() if self.jobs.asides else None
        if text is not None:
            tts.request("say", {"text": text}, path="reply")


NEAR_PLACE_M = 1.5  # an object this close to a marker is "near the kitchen"


def situation_now(world: WorldState, current: Any, seen: list[str]) -> Situation:
    """What the robot knows about itself, for :class:`~stuart_bt.conversation.facts.FactAnswers`."""
    places: dict[str, str] = {}
    for marker in world.markers.values():
        display = marker.label
        places[display.lower()] = places[marker.name.replace("_", " ")] = spoken_name(display)
    at = world.markers[world.last_marker].label if world.last_marker in world.markers else ""
    objects = {o.label: _where(o.x, o.y, world) for o in world.objects.values()}
    doing = ""
    if isinstance(current, Mission):
        doing = "busy with: " + ", then ".join(current.texts[current.done:] or current.texts)
    return Situation(at=spoken_name(at), held=world.held or "", doing=doing, seen=seen, places=places,
                     objects=objects)


def _where(x: float, y: float, world: WorldState) -> str:
    near = min(world.markers.values(), key=lambda m: (m.x - x) ** 2 + (m.y - y) ** 2, default=None)
    if near is not None and (near.x - x) ** 2 + (near.y - y) ** 2 <= NEAR_PLACE_M ** 2:
        return f"near the {spoken_name(near.label)}"
    return f"at x {x:.1f}, y {y:.1f} metres on my map"
