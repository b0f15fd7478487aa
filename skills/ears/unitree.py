"""The G1's ears, two ways (option ``mode``):

- ``mic``: the robot's four-microphone array, sent as 16 kHz mono int16 UDP datagrams to a
  multicast group (``group`` 239.168.123.161, ``port`` 5555), joined on ``mic_interface`` (an
  address or interface name; default the link's ``interface``). The hearing pipeline (voice
  activity cuts, the whisper recogniser with a ``vocabulary`` prompt) runs here in the daemon.
- ``asr``: the text of the robot's own recogniser on DDS topic ``rt/audio_msg`` (std_msgs
  String). Some firmware sends plain text, some a JSON object with the text in a field; both are
  read, and anything else is a ``log`` warning, never a failed command.

``vocabulary`` is an object with ``name``, ``places``, ``objects``, ``gestures``, ``extra`` (the
words to expect, see :class:`stuart_bt.hearing.vocabulary.Vocabulary`); ``model_dir`` a local
whisper model. Link options as in :mod:`stuart_bt.skills.vendor`.
"""

from __future__ import annotations

import json
import threading
from typing import Any

from unitree_sdk2py.idl.std_msgs.msg.dds_ import String_

from stuart_bt.core.clock import Clock
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, DaemonError, StartupError
from stuart_bt.hearing.audio import AudioError
from stuart_bt.hearing.pipeline import hear
from stuart_bt.hearing.sources import ROBOT_MIC_GROUP, ROBOT_MIC_PORT, MulticastSource
from stuart_bt.hearing.vocabulary import Vocabulary
from stuart_bt.skills import vendor

from .backend import Deliver, EarsBackend, Listening, heard_line

ASR_TOPIC = "rt/audio_msg"
MODES = ("mic", "asr")
OWN_OPTIONS = ("mode", "group", "port", "mic_interface", "vocabulary", "model_dir")
VOCABULARY_KEYS = ("name", "places", "objects", "gestures", "extra")
TEXT_FIELDS = ("text", "asr_text", "content", "result")  # where firmware versions put the words


def asr_text(data: str) -> str:
    """The words in one ``rt/audio_msg`` sample: plain text, or a JSON object's text field.
    Raises ValueError, saying why, for JSON that is broken or holds no text."""
    data = data.strip()
    if not data.startswith(("{", "[")):
        return data
    try:
        message = json.loads(data)
    except ValueError as e:
        raise ValueError(f"not JSON ({e})") from None
    if not isinstance(message, dict):
        raise ValueError("JSON that is not an object")
    for key in TEXT_FIELDS:
        if isinstance(message.get(key), str):
            return str(message[key]).strip()
    raise ValueError(f"a JSON object with no text field (one of {', '.join(TEXT_FIELDS)})")


def vocabulary_from(options: dict[str, Any], where: str) -> Vocabulary:
    spec = options.get("vocabulary", {})
    if not isinstance(spec, dict) or set(spec) - set(VOCABULARY_KEYS):
        raise StartupError(f"{where}: 'vocabulary' must be an object with {', '.join(VOCABULARY_KEYS)}, got {spec!r}")
    lists = {k: v for k, v in spec.items() if k != "name"}
    if not all(isinstance(v, list) and all(isinstance(w, str) for w in v) for v in lists.values()):
        raise StartupError(f"{where}: 'vocabulary' places, objects, gestures and extra must be lists of strings")
    return Vocabulary.of(str(spec.get("name", "Stuart")), **lists)


class UnitreeEars(EarsBackend):
    name = "unitree"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        self.link = vendor.link_from(options, "ears", OWN_OPTIONS)
        where = "ears unitree options"
        self.mode = vendor.startup_option(lambda: a.string(options, "mode", where, default="mic", choices=MODES))
        self._deliver: Deliver | None = None
        if self.mode == "mic":
            self._start_mic(options, where)
        else:
            vendor.connect(self.link)
            self._subscriber = vendor.subscribe(ASR_TOPIC, String_, self._on_asr)

    def _start_mic(self, options: dict[str, Any], where: str) -> None:
        self.group = vendor.startup_option(lambda: a.string(options, "group", where, default=ROBOT_MIC_GROUP))
        self.port = int(vendor.startup_option(lambda: a.number(options, "port", where, default=ROBOT_MIC_PORT)))
        self.mic_interface = vendor.startup_option(
            lambda: a.string(options, "mic_interface", where, default=self.link.interface))
        self.vocabulary = vocabulary_from(options, where)
        from stuart_bt.hearing.recognisers import make_recogniser

        extra = {"model_dir": options["model_dir"]} if "model_dir" in options else {}
        try:
            self.recogniser = make_recogniser(**extra)  # the default engine (docs/hearing.md)
        except (AudioError, OSError) as e:
            raise StartupError(f"ears unitree: no recogniser for the robot's microphones: {e}") from None

    def listen(self) -> Activity:
        if self.mode == "asr":
            stopped = threading.Event()
            return Listening(self, lambda deliver: self._follow_asr(deliver, stopped), stopped.set)
        try:
            source = MulticastSource(self.group, self.port, self.mic_interface)
        except AudioError as e:
            raise DaemonError("backend_error", str(e)) from None
        return Listening(self, lambda deliver: self._hear_mic(source, deliver), source.close)

    def _hear_mic(self, source: MulticastSource, deliver: Deliver) -> None:
        for heard in hear(source, self.recogniser, self.vocabulary):
            t = heard.transcript
            deliver(heard_line(t.text, "robot_mic", round(t.confidence, 4), round(t.audio_s, 3),
                               round(heard.start_s, 3), round(t.no_speech, 4), latency_s=round(heard.latency_s, 3),
                               readings=[list(r) for r in t.readings()], engine=t.engine))

    def _follow_asr(self, deliver: Deliver, stopped: threading.Event) -> None:
        self._deliver = deliver
        try:
            stopped.wait()
        finally:
            self._deliver = None

    def _on_asr(self, sample: Any) -> None:
        """A DDS thread: one sample of the robot's recogniser."""
        deliver = self._deliver
        try:
            text = asr_text(str(sample.data))
        except ValueError as e:
            self.warn(f"ears: ignored a {ASR_TOPIC} sample: {e}: {str(sample.data)[:80]!r}")
            return
        if text and deliver is not None:
            deliver(heard_line(text, "robot_asr"))

    def state(self) -> dict[str, Any]:
        return {**super().state(), "mode": self.mode}

    def close(self) -> None:
        subscriber = getattr(self, "_subscriber", None)
        if subscriber is not None:
            subscriber.Close()
