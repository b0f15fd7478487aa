"""The robot's own ears in front of a mission executor (``stuart-bt listen --source robot``).

The G1 hears in two ways, both vendor code, so both run in the ``ears`` daemon (process
isolation, like every unitree backend; ``skills/ears``): its microphone array (UDP multicast,
cut and recognised by the hearing pipeline inside the daemon) or its own recogniser's text on
DDS ``rt/audio_msg``. :class:`RobotEars` starts that one daemon, asks it to ``listen``, and
hands each utterance in its progress lines to the executor exactly as a local microphone's
(:func:`~stuart_bt.mission.listening.act_on_heard`): same ``heard`` and ``utterance`` events,
same rule that the robot's own voice never commands it. The daemon says when an utterance
ended and how long it was; :meth:`RobotVoice.spoke_over` says whether the robot was talking
then, so a sentence of its own that its microphones caught is dropped, and a stop said over it
still stops it.

The daemon's events go on the executor's event stream (the report and the log show the ears
like any other daemon); its clock is real time whatever the executor's speed, because sound is.
"""

from __future__ import annotations

import queue
import threading
import time
from typing import TYPE_CHECKING, Any

from ..core.clock import ScaledClock
from ..core.events import Event
from ..daemon.supervisor import Supervisor
from .listening import RobotVoice, act_on_heard

if TYPE_CHECKING:
    from ..daemon.client import Request
    from .executor import MissionExecutor

FAMILY = "ears"
MODES = {"robot": "mic", "robot:mic": "mic", "robot:asr": "asr"}  # --source -> the ears daemon's mode
ENGINES = {"mic": "whisper+grammar", "asr": "robot"}  # when the daemon does not name its recogniser
ASR_AUDIO_S = 1.0  # the robot's recogniser says nothing of timing: judge its text by the last second


def is_robot_source(spec: str) -> bool:
    return spec in MODES


class RobotEars:
    """The ears daemon (the unitree backend) heard through ``robot``.
    The same life cycle as :class:`~stuart_bt.mission.listening.Listener`: ``start``, ``done``
    when the sound ends, ``error`` when it failed, ``close`` (the daemon is always reaped)."""

    def __init__(self, robot: MissionExecutor, spec: str, options: dict[str, Any] | None = None,
                 handshake_timeout: float = 30.0) -> None:
        self.robot = robot
        self.mode = MODES[spec]
        self.source = f"robot_{self.mode}"
        options = {"mode": self.mode, **(options or {})}
        if self.mode == "mic":
            options.setdefault("vocabulary", robot.resolver.vocabulary().to_dict())
        self.supervisor = Supervisor("unitree", ScaledClock(1.0), robot.events, families=(FAMILY,),
                                     options={FAMILY: options}, handshake_timeout=handshake_timeout)
        self.voice = RobotVoice(robot.events)
        self.error: str | None = None
        self.done = threading.Event()
        self._closing = threading.Event()
        self._listen: Request | None = None
        self._heard: queue.Queue[dict[str, Any]] = queue.Queue()
        self._thread = threading.Thread(target=self._run, name="robot-ears", daemon=True)
        self._unsubscribe = robot.events.subscribe(self._on_event)

    def start(self) -> RobotEars:
        """Start the daemon (a failure to start is raised here, with the daemon's reason)."""
        self.supervisor.start()
        self._thread.start()
        return self

    def close(self, timeout: float = 5.0) -> None:
        self._closing.set()
        if self._thread.is_alive():
            self._thread.join(timeout)
        self.supervisor.shutdown()
        self._unsubscribe()

    def _run(self) -> None:
        try:
            self._listen = self.supervisor.client(FAMILY).request("listen")
            while not self._closing.is_set() and not self._listen.finished:
                self.supervisor.wait(self._listen, timeout=0.1)
                self._act()
            self._act()
            if self._listen.status == "error":
                self.error = f"{self._listen.error_code}: {self._listen.reason}"
                self.robot.events.publish("warning", message=f"hearing stopped: the robot's ears: {self.error}")
        finally:
            self.done.set()

    def _act(self) -> None:
        """Submit what was heard since the last look (after the daemon's own event is published,
        so the log reads progress line, then ``heard``, then ``utterance``)."""
        while True:
            try:
                heard = self._heard.get_nowait()
            except queue.Empty:
                return
            act_on_heard(self.robot, self._fields(heard))

    def _on_event(self, event: Event) -> None:
        """A progress line of our listen request: one utterance heard (kept for :meth:`_act`)."""
        d = event.data
        if (event.kind != "daemon" or d.get("family") != FAMILY or d.get("type") != "progress"
                or self._listen is None or d.get("id") != self._listen.id):
            return
        heard = (d.get("data") or {}).get("heard")
        if isinstance(heard, dict) and str(heard.get("text") or "").strip():
            self._heard.put(heard)

    def _fields(self, heard: dict[str, Any]) -> dict[str, Any]:
        """The daemon's description of an utterance as :func:`hearing_fields` gives it."""
        now = time.perf_counter()
        audio_s = heard.get("audio_s")
        latency_s = heard.get("latency_s") or 0.0
        ended = now - latency_s
        began = ended - (audio_s if audio_s else ASR_AUDIO_S)
        return {"text": str(heard["text"]).strip(), "source": self.source, "audio_s": audio_s,
                "confidence": heard.get("confidence"), "no_speech": heard.get("no_speech"),
                "latency_s": latency_s, "engine": str(heard.get("engine") or ENGINES[self.mode]),
                "start_s": heard.get("start_s"),
                "over_robot_speech": self.voice.spoke_over(began, ended),
                **({"readings": heard["readings"]} if isinstance(heard.get("readings"), list) else {})}
