"""Speech from the browser's microphone, heard like a microphone on the robot.

The web console's push-to-talk (:mod:`.audio`) hands a whole utterance here: the press of the
button already cut it, so no voice detector runs. It is transcribed by the same recogniser as
``stuart-bt listen`` (loaded on first use, then kept: loading costs about a second, and a server
that nobody talks to should not pay it), with the robot's own vocabulary, and submitted exactly as
heard speech is (:func:`~stuart_bt.mission.listening.take_heard`), with source ``browser``, to
the robot the server has now: the mission executor, or the talk of the running tree.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING, Any

from ..hearing.pipeline import is_speech, transcribe
from ..mission.listening import act_on_reading, chosen_reading, hearing_fields

if TYPE_CHECKING:
    import numpy as np

    from ..hearing.recognisers import Recogniser

SOURCE = "browser"


class BrowserEars:
    """The recogniser for one server's browsers (one at a time: two utterances at once would
    share the two cores and both be late)."""

    def __init__(self, engine: str | None = None) -> None:
        self.engine = engine
        self._recogniser: Recogniser | None = None
        self._lock = threading.Lock()

    def recogniser(self) -> Recogniser:
        if self._recogniser is None:
            from ..hearing.recognisers import make_recogniser

            self._recogniser = make_recogniser(self.engine) if self.engine else make_recogniser()
        return self._recogniser

    def hear(self, robot: Any, samples: np.ndarray, ended_at: float) -> dict[str, Any]:
        """16 kHz mono int16 ``samples`` (one utterance, ended at ``perf_counter()`` ``ended_at``)
        -> what ``robot`` (anything with ``parser``, ``resolver``, ``attention``, ``events`` and
        ``submit``) heard and understood (blocking: call it off the event loop)."""
        with self._lock:
            heard = transcribe(self.recogniser(), samples, robot.resolver.vocabulary(), source=SOURCE,
                               ended_at=ended_at)
        fields = hearing_fields(heard)
        if not is_speech(heard.transcript):
            robot.events.publish("heard", acted=False, reason="no_speech", **fields)
            return {**fields, "kind": "no_speech", "intents": []}
        fields = chosen_reading(robot, fields)
        command = act_on_reading(robot, fields)
        if command is None:
            return {**fields, "kind": "dropped", "intents": []}
        return {**fields, "kind": command.kind, "intents": [i.to_dict() for i in command.intents]}
