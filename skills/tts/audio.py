"""Speech with real audio: every utterance is synthesized to a WAV whose length is its duration.

Used by the ``sim`` backend (and usable on a desktop): the tree waits exactly as long as the
words take to say. Without a synthesizer it falls back to the dry estimate and says so in the
state, so a missing package degrades timing, never the run.
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path
from typing import Any

from stuart_bt.core.clock import Clock
from stuart_bt.daemon.backend import DaemonError

from .dry import DryTts, Utterance, speaking_time
from .speech import SynthesisError, Synthesizer


class AudioUtterance(Utterance):
    def __init__(self, backend: AudioTts, text: str, seconds: float, wav: str | None) -> None:
        super().__init__(backend, text)
        self.duration = seconds
        self.wav = wav

    def on_start(self, now: float) -> dict[str, Any]:
        accepted = super().on_start(now) or {}
        return {**accepted, "wav": self.wav}

    def finish(self, now: float) -> dict[str, Any]:
        return {**super().finish(now), "wav": self.wav}


class AudioTts(DryTts):
    """Options: ``audio_dir`` (default: a temp folder), ``engine`` (auto | espeak-ng | piper | none),
    ``voice`` (espeak-ng voice, default en-us), ``words_per_minute`` (165), ``piper_model``."""

    name = "sim"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        self._own_dir = not options.get("audio_dir")  # a folder we made is ours to remove
        out = Path(options.get("audio_dir") or tempfile.mkdtemp(prefix="stuart_bt-audio-"))
        self.synth = Synthesizer(out, options.get("engine", "auto"), options.get("voice", "en-us"),
                                 int(options.get("words_per_minute", 165)), options.get("piper_model"))

    def say(self, text: str) -> Utterance:
        if not self.synth.available:
            return AudioUtterance(self, text, speaking_time(text), None)
        try:
            audio = self.synth.synthesize(text)
        except SynthesisError as e:
            raise DaemonError("backend_error", str(e)) from None
        return AudioUtterance(self, text, audio.seconds, str(audio.path))

    def state(self) -> dict[str, Any]:
        return {**super().state(), "engine": self.synth.engine}

    def close(self) -> None:
        if self._own_dir:
            shutil.rmtree(self.synth.out_dir, ignore_errors=True)
