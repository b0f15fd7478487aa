"""``WS /ws/audio``: push-to-talk from the web console, one utterance per press.

Protocol (every message the server sends is strict JSON text):

| from the page | meaning |
|---|---|
| ``{"type": "start", "rate": 48000}`` | the button is pressed: a recording at ``rate`` Hz begins |
| binary frames | mono little-endian int16 PCM at that rate, at most :data:`MAX_FRAME` bytes each |
| ``{"type": "stop"}`` | released: transcribe what came and say it to the robot (missions, or the running tree) |
| ``{"type": "cancel"}`` | drop the recording |

The server answers ``{"type": "recording", "rate", "max_s"}`` to a start, ``{"type": "cut",
"max_s", "message"}`` once when a recording passes :data:`MAX_SECONDS` (the rest is dropped),
``{"type": "heard", "text", "kind", "intents", "audio_s", "confidence", ..., "cut"}`` to a stop,
and ``{"type": "error", "error": "one sentence"}`` to anything it refuses. One recording at a
time per connection. A frame over the size limit closes the socket (1009); any other mistake
only drops the recording in hand. Host, Origin and token are checked as for ``/ws``.

The browser sends its own rate (an AudioContext runs at the sound card's, usually 48 kHz) and the
server resamples to 16 kHz once per utterance; recognition runs in a thread, never on the loop.
"""

from __future__ import annotations

import asyncio
import json
import logging
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..core.errors import StuartError

if TYPE_CHECKING:
    from starlette.websockets import WebSocket

    from .security import Guard

MAX_SECONDS = 15.0  # of audio in one press; a longer one is cut there (and the page is told)
MAX_FRAME = 64 * 1024  # bytes in one message: a 4096-sample block is 8 KiB
RATES = (8_000, 96_000)  # sample rates a page may declare
log = logging.getLogger("stuart_bt.web")


class Refused(Exception):
    """A message the protocol does not allow: one sentence for the page."""


@dataclass
class Recording:
    """One press of the button: the declared rate and the PCM bytes so far (up to the limit)."""

    rate: int
    chunks: list[bytes] = field(default_factory=list)
    size: int = 0
    cut: bool = False

    @property
    def limit(self) -> int:
        return int(self.rate * MAX_SECONDS) * 2

    def add(self, data: bytes) -> bool:
        """Keep ``data`` up to the limit; True the first time the limit is passed."""
        room = self.limit - self.size
        if len(data) > room:
            self.chunks.append(data[:max(room, 0)])
            self.size = self.limit
            first, self.cut = not self.cut, True
            return first
        self.chunks.append(data)
        self.size += len(data)
        return False

    def samples(self) -> Any:
        """16 kHz mono int16 samples of the whole recording."""
        import numpy as np

        from ..hearing.audio import resample

        return resample(np.frombuffer(b"".join(self.chunks), dtype="<i2"), self.rate)


class TalkSession:
    """The state of one ``/ws/audio`` connection; ``hear(samples, ended_at) -> dict`` does the
    recognition (blocking) and ``None`` means this server cannot hear (a replay)."""

    def __init__(self, websocket: WebSocket, hear: Any) -> None:
        self.ws = websocket
        self.hear = hear
        self.recording: Recording | None = None

    async def send(self, message_type: str, /, **fields: Any) -> None:
        await self.ws.send_text(json.dumps({"type": message_type, **fields}, allow_nan=False))

    async def on_bytes(self, data: bytes) -> None:
        if self.recording is None:
            raise Refused("audio came without a start: send {\"type\": \"start\", \"rate\": N} first")
        if len(data) % 2:
            self.recording = None
            raise Refused("a frame of int16 samples has an even number of bytes; the recording is dropped")
        if self.recording.add(data):
            await self.send("cut", max_s=MAX_SECONDS,
                            message=f"a press holds at most {MAX_SECONDS:g} s of audio; the rest is cut")

    async def on_text(self, text: str) -> None:
        message = _message(text)
        kind = message["type"]
        if kind == "start":
            await self.start(message.get("rate"))
        elif kind == "stop":
            await self.stop()
        elif kind == "cancel":
            self.recording = None
        else:
            raise Refused(f"unknown message type {kind!r}: start, stop or cancel")

    async def start(self, rate: Any) -> None:
        if self.hear is None:
            raise Refused("push-to-talk needs a robot: this is the replay of a saved log")
        if self.recording is not None:
            raise Refused("already recording: one recording at a time (send stop first)")
        if isinstance(rate, bool) or not isinstance(rate, int) or not RATES[0] <= rate <= RATES[1]:
            raise Refused(f"'rate' must be a whole number of samples per second, {RATES[0]} to {RATES[1]}")
        self.recording = Recording(rate)
        await self.send("recording", rate=rate, max_s=MAX_SECONDS)

    async def stop(self) -> None:
        recording, self.recording = self.recording, None
        if recording is None:
            raise Refused("nothing is recording: send start first")
        if recording.size == 0:
            raise Refused("no audio came between start and stop")
        ended_at = time.perf_counter()
        loop = asyncio.get_running_loop()
        try:
            result = await loop.run_in_executor(None, _heard, self.hear, recording, ended_at)
        except StuartError as e:
            raise Refused(str(e)) from None
        await self.send("heard", cut=recording.cut, **result)


def _heard(hear: Any, recording: Recording, ended_at: float) -> dict[str, Any]:
    return hear(recording.samples(), ended_at)


def _message(text: str) -> dict[str, Any]:
    """A control message: a JSON object with a string ``type`` (no NaN or Infinity)."""
    try:
        message = json.loads(text, parse_constant=_no_constant)
    except ValueError as e:
        raise Refused(f"a control message must be JSON: {e}") from None
    if not isinstance(message, dict) or not isinstance(message.get("type"), str):
        raise Refused("a control message is a JSON object with a 'type'")
    return message


def _no_constant(name: str) -> Any:
    raise ValueError(f"{name} is not JSON")


async def audio_socket(websocket: WebSocket, guard: Guard, hear: Any) -> None:
    """Serve one ``/ws/audio`` connection until the page closes it."""
    from starlette.websockets import WebSocketDisconnect

    if not guard.host_ok(websocket.headers) or not guard.origin_ok(websocket.headers) or \
            not guard.token_ok(websocket.query_params, websocket.headers, websocket.cookies):
        await websocket.close(code=1008)
        return
    await websocket.accept()
    session = TalkSession(websocket, hear)
    try:
        while await _one(websocket, session):
            pass
    except WebSocketDisconnect:
        pass


async def _one(websocket: WebSocket, session: TalkSession) -> bool:
    """Take one message; False when the connection is over."""
    message = await websocket.receive()
    if message["type"] == "websocket.disconnect":
        return False
    data, text = message.get("bytes"), message.get("text")
    size = len(data) if data is not None else len((text or "").encode())
    if size > MAX_FRAME:
        await session.send("error", error=f"a message is at most {MAX_FRAME} bytes; closing")
        await websocket.close(code=1009)
        return False
    try:
        await (session.on_bytes(data) if data is not None else session.on_text(text or ""))
    except Refused as e:
        await session.send("error", error=str(e))
    except Exception as e:
        log.error("/ws/audio failed: %s: %s", type(e).__name__, e, exc_info=e)
        session.recording = None
        await session.send("error", error="internal error; the server's log says more")
    return True
