"""One tree run that people talk to: what ``stuart-bt ros TREE`` puts behind its topics.

The ROS bridge and the hearing front ends (:mod:`.listening`, :mod:`.robot_ears`) drive "a robot":
something with ``events``, ``parser``, ``resolver``, ``attention``, ``submit`` and
``daemon_request``. The mission executor is one; :class:`TalkingTree` is the other: a
:class:`~stuart_bt.run.session.Session` that runs one YAML tree, as ``stuart-bt run`` does, with
a :class:`~.tour_talk.TourTalk` taking every utterance (a question is answered at the next pause
in speech, "stop" holds the tree, "continue" lets it go on). Nothing here knows about ROS.
"""

from __future__ import annotations

import threading
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from ..language import Parser, Resolver
from ..run.session import RunOptions, Session
from .tour_talk import TourTalk

if TYPE_CHECKING:
    from ..conversation.reply import Conversation
    from ..core.events import EventStream
    from ..run.executor import RunOutcome
    from ..tree.spec import TreeSpec
    from .attention import Attention
    from .commands import Command


class TalkingTree:
    """A session for ``spec`` and the talk to its tree. ``start`` (daemons, the world), then
    ``run`` (blocking, on any thread), then ``close`` (always: daemons shut down)."""

    def __init__(self, spec: TreeSpec, options: RunOptions, conversation: Conversation | None = None,
                 name: str = "Stuart") -> None:
        self.session = Session(spec, options)
        self.parser = Parser(name)
        self.resolver = Resolver.from_files(spec.markers_file)
        self.conversation = conversation
        self.talk: TourTalk | None = None
        self._running = threading.Event()
        self._closed = False

    @property
    def events(self) -> EventStream:
        return self.session.events

    @property
    def attention(self) -> Attention:
        return self._talk().attention

    def start(self) -> TalkingTree:
        self.session.start()
        assert self.session.executor is not None
        self.talk = TourTalk(self.session, self.session.executor, self.parser, self.resolver, self.conversation)
        return self

    def run(self) -> RunOutcome:
        """The tree from its start to its end (or a stop request); utterances meanwhile go to the talk."""
        self._running.set()
        try:
            return self.session.run()
        finally:
            self._running.clear()

    def request_stop(self, reason: str) -> None:
        """End the run at the next tick (any thread; from a signal, through
        :mod:`stuart_bt.core.interrupts`; before ``run`` it ends at once)."""
        self.session.request_stop(reason)

    def close(self) -> None:
        """Shut the daemons (and the world) down; only the first call does anything."""
        if self._closed:
            return
        self._closed = True
        if self.talk is not None:
            self.talk.close()
        self.session.close()

    def __enter__(self) -> TalkingTree:
        try:
            return self.start()
        except BaseException:
            self.close()
            raise

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- what the front ends call (any thread) ----------------------------------------------------------
    def submit(self, utterance: str, woken: bool = False, *, source: str = "typed",
               heard: Mapping[str, Any] | None = None) -> Command:
        """One utterance to the running tree (:meth:`TourTalk.submit`)."""
        return self._talk().submit(utterance, woken, source=source, heard=heard)

    def daemon_request(self, family: str, cmd: str, args: dict[str, Any] | None = None) -> bool:
        """Send one command to a skill daemon before the tree's next tick (``("pick", "confirm")``
        for the pick confirmation gate); False, and nothing sent, when the tree is not running."""
        executor = self.session.executor
        if executor is None or not self._running.is_set():
            return False
        self.session.request_before_tick(executor, family, cmd, args)
        return True

    def _talk(self) -> TourTalk:
        if self.talk is None:
            raise RuntimeError("the tree has not started: call start() first")
        return self.talk
