"""Speech on the G1: the robot's own TTS (AudioClient.TtsMaker, api 1001), or speech synthesised
here and streamed to its speaker (PlayStream, api 1003: 16 kHz mono int16 in ~3 s chunks).

The robot's TTS answers at once and speaks for a while without saying how long, so the duration
the tree waits for is measured by synthesising the same text locally (espeak-ng, installed with
``make``) when possible, else estimated from the word count. Streamed speech knows its length
exactly. Chunks are sent a little ahead of when they are needed, not all at once, so a cancel
(PlayStop, api 1004) cuts the speech within a chunk.

Options (besides the link settings in :mod:`stuart_bt.skills.vendor`): ``engine`` (``robot``
default, ``espeak-ng`` or ``piper``: local synthesis streamed), ``speaker`` (1: the robot's
English voice), ``piper_model`` (a local piper voice file; piper needs it), ``voice``
(espeak-ng voice, en-us), ``words_per_minute`` (165), ``volume`` (0..100, set at start-up),
``led`` ([R, G, B], set at start-up), ``chunk_seconds`` (3.0), ``lead_seconds`` (1.0).
"""

from __future__ import annotations

import contextlib
import shutil
import tempfile
import wave
from pathlib import Path
from typing import Any

import numpy as np
from unitree_sdk2py.g1.audio.g1_audio_client import AudioClient

from stuart_bt.core.clock import Clock
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import DaemonError, Done, Progress, StartupError
from stuart_bt.skills import vendor

from .dry import DryTts, Utterance, speaking_time
from .speech import SynthesisError, Synthesizer

SERVICE = "voice"
APP_NAME = "stuart_bt"
STREAM_RATE = 16000  # Hz, what PlayStream takes
ENGINES = ("robot", "espeak-ng", "piper")
OWN_OPTIONS = ("engine", "speaker", "piper_model", "voice", "words_per_minute", "volume", "led", "chunk_seconds",
               "lead_seconds")


def pcm16k(path: Path) -> bytes:
    """A WAV file as 16 kHz mono little-endian int16 (resampled linearly, channels averaged)."""
    with wave.open(str(path), "rb") as w:
        rate, channels, width = w.getframerate(), w.getnchannels(), w.getsampwidth()
        raw = w.readframes(w.getnframes())
    if width != 2:
        raise SynthesisError(f"{path.name}: expected 16-bit samples, got {8 * width}-bit")
    samples = np.frombuffer(raw, dtype="<i2").astype(np.float64).reshape(-1, channels).mean(axis=1)
    if rate != STREAM_RATE and len(samples):
        times = np.arange(int(len(samples) * STREAM_RATE / rate)) / STREAM_RATE
        samples = np.interp(times, np.arange(len(samples)) / rate, samples)
    return np.clip(np.round(samples), -32768, 32767).astype("<i2").tobytes()


class RobotUtterance(Utterance):
    """The robot's own TTS: one TtsMaker request, then wait the measured duration."""

    def __init__(self, backend: UnitreeTts, text: str, seconds: float) -> None:
        super().__init__(backend, text)
        self.duration = seconds
        self.tts = backend

    def on_start(self, now: float) -> dict[str, Any]:
        vendor.check(self.tts.audio.TtsMaker(self.text, self.tts.speaker), SERVICE, "TtsMaker")
        return super().on_start(now) or {}


class StreamedUtterance(Utterance):
    """Local speech sent to the speaker in chunks, each a little before it is needed."""

    def __init__(self, backend: UnitreeTts, text: str, pcm: bytes) -> None:
        super().__init__(backend, text)
        self.tts = backend
        self.chunk_bytes = int(backend.chunk_seconds * STREAM_RATE) * 2
        self.chunks = [pcm[i:i + self.chunk_bytes] for i in range(0, len(pcm), self.chunk_bytes)]
        self.duration = len(pcm) / 2 / STREAM_RATE
        self.sent = 0
        backend.streams += 1
        self.stream_id = f"{APP_NAME}-{backend.streams}"

    def on_start(self, now: float) -> dict[str, Any]:
        accepted = super().on_start(now) or {}
        self._send_due(now)
        return {**accepted, "chunks": len(self.chunks), "sample_rate": STREAM_RATE}

    def _send_due(self, now: float) -> None:
        while self.sent < len(self.chunks) and now >= self.started + self.sent * self.tts.chunk_seconds - self.tts.lead:
            code, _ = self.tts.audio.PlayStream(APP_NAME, self.stream_id, self.chunks[self.sent])
            vendor.check(code, SERVICE, f"PlayStream (chunk {self.sent + 1} of {len(self.chunks)})")
            self.sent += 1

    def next_due(self) -> float:
        due = super().next_due()
        if self.sent < len(self.chunks):
            due = min(due, self.started + self.sent * self.tts.chunk_seconds - self.tts.lead)
        return due

    def poll(self, now: float) -> Progress | Done | None:
        self._send_due(now)
        return super().poll(now)

    def cancel(self, now: float) -> dict[str, Any]:
        self.tts.audio.PlayStop(APP_NAME)
        return super().cancel(now)


class UnitreeTts(DryTts):
    name = "unitree"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, {})
        self.options = options
        self.link = vendor.link_from(options, "tts", OWN_OPTIONS)
        where = "tts unitree options"
        self.engine = vendor.startup_option(
            lambda: a.string(options, "engine", where, default="robot", choices=ENGINES))
        self.speaker = int(vendor.startup_option(lambda: a.number(options, "speaker", where, default=1)))
        self.chunk_seconds = vendor.startup_option(lambda: a.number(options, "chunk_seconds", where, default=3.0,
                                                                    minimum=0.5))
        self.lead = vendor.startup_option(lambda: a.number(options, "lead_seconds", where, default=1.0, minimum=0.0))
        self.streams = 0
        self._audio_dir = Path(tempfile.mkdtemp(prefix="stuart_bt-robot-audio-"))
        try:
            self._connect(options, where)
        except BaseException:
            self.close()  # a daemon that does not start leaves no audio folder behind
            raise

    def _connect(self, options: dict[str, Any], where: str) -> None:
        local = "espeak-ng" if self.engine == "robot" else self.engine
        try:
            self.synth = Synthesizer(self._audio_dir, "auto" if self.engine == "robot" else local,
                                     options.get("voice", "en-us"), int(options.get("words_per_minute", 165)),
                                     options.get("piper_model"))
        except SynthesisError as e:
            raise StartupError(f"tts unitree engine {self.engine!r}: {e}") from None
        vendor.connect(self.link)
        self.audio = vendor.ready_client(AudioClient(), SERVICE, self.link)
        if "volume" in options:
            volume = vendor.startup_option(lambda: a.number(options, "volume", where))
            if not 0 <= volume <= 100:
                raise StartupError(f"{where}: 'volume' must be 0..100, got {volume:g}")
            vendor.check(self.audio.SetVolume(int(volume)), SERVICE, "SetVolume")
        if "led" in options:
            rgb = options["led"]
            if not (isinstance(rgb, list) and len(rgb) == 3 and all(isinstance(c, int) and 0 <= c <= 255 for c in rgb)):
                raise StartupError(f"{where}: 'led' must be [R, G, B] with 0..255 each, got {rgb!r}")
            vendor.check(self.audio.LedControl(*rgb), SERVICE, "LedControl")

    def say(self, text: str) -> Utterance:
        if not text.strip():
            raise DaemonError("bad_request", "say: 'text' is empty")
        if self.engine == "robot":
            seconds = speaking_time(text)
            if self.synth.available:
                with contextlib.suppress(SynthesisError):  # the estimate will do: timing only
                    seconds = self.synth.synthesize(text).seconds
            return RobotUtterance(self, text, seconds)
        try:
            audio = self.synth.synthesize(text)
        except SynthesisError as e:
            raise DaemonError("backend_error", str(e)) from None
        return StreamedUtterance(self, text, pcm16k(audio.path))

    def state(self) -> dict[str, Any]:
        return {**super().state(), "engine": self.engine}

    def close(self) -> None:
        shutil.rmtree(self._audio_dir, ignore_errors=True)
