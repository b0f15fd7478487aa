"""Speech synthesis to WAV files: espeak-ng (Debian package, offline) or piper (local voice model).

The tts backends that produce real audio use this to know how long an utterance really lasts:
the WAV's length is the duration the tree waits for. Nothing is fetched: piper needs a voice
model file that is already on disk (``piper_model`` option), espeak-ng needs only its package.
"""

from __future__ import annotations

import hashlib
import shutil
import subprocess
import wave
from dataclasses import dataclass
from pathlib import Path

from stuart_bt.core.errors import StuartError


class SynthesisError(StuartError, RuntimeError):
    pass


@dataclass(frozen=True)
class Audio:
    path: Path
    seconds: float
    sample_rate: int


def wav_seconds(path: Path) -> tuple[float, int]:
    with wave.open(str(path), "rb") as w:
        return w.getnframes() / float(w.getframerate()), w.getframerate()


class Synthesizer:
    """Writes one WAV per distinct text into ``out_dir`` (cached by text, voice and rate)."""

    def __init__(self, out_dir: Path, engine: str = "auto", voice: str = "en-us", words_per_minute: int = 165,
                 piper_model: str | None = None) -> None:
        self.out_dir = Path(out_dir)
        self.out_dir.mkdir(parents=True, exist_ok=True)
        self.voice, self.words_per_minute, self.piper_model = voice, words_per_minute, piper_model
        self.engine = self._choose(engine)

    def _choose(self, engine: str) -> str:
        if engine in ("auto", "piper") and self.piper_model and shutil.which("piper"):
            if not Path(self.piper_model).is_file():
                raise SynthesisError(f"piper voice model not found: {self.piper_model}")
            return "piper"
        if engine == "piper":
            raise SynthesisError("piper needs the 'piper' program and a local voice model (piper_model option)")
        if engine in ("auto", "espeak-ng") and shutil.which("espeak-ng"):
            return "espeak-ng"
        if engine == "espeak-ng":
            raise SynthesisError("espeak-ng is not installed (make installs it: apt-get install espeak-ng)")
        return "none"

    @property
    def available(self) -> bool:
        return self.engine != "none"

    def synthesize(self, text: str) -> Audio:
        if not self.available:
            raise SynthesisError("no speech synthesizer available")
        key = hashlib.sha1(f"{self.engine}|{self.voice}|{self.words_per_minute}|{text}".encode()).hexdigest()[:16]
        path = self.out_dir / f"{key}.wav"
        if not path.exists():
            tmp = path.with_suffix(".tmp.wav")
            if self.engine == "espeak-ng":
                # text goes through stdin, never the command line: no option can be smuggled in
                cmd = ["espeak-ng", "-v", self.voice, "-s", str(self.words_per_minute), "-w", str(tmp), "--stdin"]
            else:
                cmd = ["piper", "--model", str(self.piper_model), "--output_file", str(tmp)]
            try:
                subprocess.run(cmd, input=text.encode("utf-8"), check=True, timeout=30,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            except (subprocess.CalledProcessError, subprocess.TimeoutExpired, OSError) as e:
                raise SynthesisError(f"{self.engine} failed: {e}") from None
            tmp.replace(path)
        seconds, rate = wav_seconds(path)
        return Audio(path, seconds, rate)
