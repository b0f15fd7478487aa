"""Where sound comes from, chosen by name like the skill backends: ``file:PATH`` (a file, or a
folder of them in name order), ``-`` (raw 16 kHz mono int16 PCM on stdin) and ``mic`` /
``mic:DEVICE`` (a local microphone through PortAudio, the device by name or index).

A source yields blocks of 16 kHz mono int16 samples (:mod:`.audio`) until it ends or is closed.
``live`` says whether it runs at the speed of the world (a microphone) or as fast as it can be
read (a file), which decides whether waiting for more makes sense.
"""

from __future__ import annotations

import contextlib
import fcntl
import ipaddress
import queue
import socket
import struct
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, BinaryIO, Protocol

from ..core.suggest import did_you_mean
from .audio import RATE, SAMPLE_BYTES, AudioError, read_audio, resample

if TYPE_CHECKING:
    import numpy as np

BLOCK_S = 0.03  # seconds per block a source yields: the voice detector's frame
AUDIO_SUFFIXES = (".wav", ".flac", ".mp3", ".ogg", ".opus", ".m4a", ".aac", ".webm")
GAP_S = 1.0  # silence put between two files of a folder, so one file's speech never runs into the next's


class Source(Protocol):
    """A stream of sound: 16 kHz mono int16 blocks."""

    name: str
    live: bool

    def blocks(self) -> Iterator[np.ndarray]: ...

    def close(self) -> None: ...


class FileSource:
    """Files (or folders of audio files, in name order) one after another, with :data:`GAP_S`
    of silence between them. A file that cannot be read raises :class:`AudioError` when its turn
    comes, naming it. ``live=True`` plays them at the speed they were spoken (a recording played
    to a listening robot, as a person would have said it), else as fast as they can be read."""

    def __init__(self, paths: list[str | Path], live: bool = False) -> None:
        self.paths = [p for path in paths for p in _expand(Path(path))]
        self.name = f"file:{paths[0]}" if len(paths) == 1 else f"files ({len(self.paths)})"
        self.live = live
        self._closed = False

    def blocks(self) -> Iterator[np.ndarray]:
        import numpy as np

        step = int(RATE * BLOCK_S)
        started, played = time.monotonic(), 0
        for n, path in enumerate(self.paths):
            clips = [np.zeros(int(RATE * GAP_S), np.int16)] if n else []
            for block in _split(np.concatenate([*clips, read_audio(path)]), step):
                if self._closed:
                    return
                if self.live:  # not ahead of the wall clock: the block is "heard" when it would have been said
                    time.sleep(max(0.0, started + played / RATE - time.monotonic()))
                played += len(block)
                yield block

    def close(self) -> None:
        self._closed = True


class PcmSource:
    """Raw 16 kHz mono little-endian int16 PCM from a byte stream (stdin: ``-``), e.g. piped from
    ``arecord -f S16_LE -r 16000 -c 1`` or ``sox ... -t raw -``."""

    live = True

    def __init__(self, stream: BinaryIO | None = None) -> None:
        self.stream = stream if stream is not None else sys.stdin.buffer
        self.name = "stdin"
        self._closed = False

    def blocks(self) -> Iterator[np.ndarray]:
        import numpy as np

        size = int(RATE * BLOCK_S) * SAMPLE_BYTES
        pending = b""
        while not self._closed:
            data = self.stream.read(size - len(pending))
            if not data:
                return
            pending += data
            if len(pending) == size:
                yield np.frombuffer(pending, "<i2").astype(np.int16)
                pending = b""

    def close(self) -> None:
        self._closed = True


class MicSource:
    """A local microphone through PortAudio (``sounddevice``). The device is chosen by index or
    by (part of) its name; it is opened at 16 kHz when it can be, else at its own rate and
    resampled here. No input device gives one clear :class:`AudioError`."""

    live = True

    def __init__(self, device: str | None = None) -> None:
        self.device = _input_device(device)
        self.name = f"mic:{self.device.name}"
        self._queue: queue.Queue[np.ndarray | None] = queue.Queue(maxsize=200)
        self._stream: object | None = None

    def blocks(self) -> Iterator[np.ndarray]:
        import sounddevice as sd

        rate = RATE if _supports(sd, self.device.index, RATE) else int(self.device.default_samplerate)
        block = int(rate * BLOCK_S)

        def arrived(data: np.ndarray, frames: int, when: object, status: object) -> None:
            with contextlib.suppress(queue.Full):  # the reader fell 6 s behind: this block is lost
                self._queue.put_nowait(data.reshape(-1).copy())

        try:
            stream = sd.InputStream(device=self.device.index, channels=1, samplerate=rate, dtype="int16",
                                    blocksize=block, callback=arrived)
        except sd.PortAudioError as e:
            raise AudioError(f"{self.name}: cannot open it ({e})") from None
        self._stream = stream
        with stream:
            while (samples := self._queue.get()) is not None:
                yield resample(samples, rate) if rate != RATE else samples

    def close(self) -> None:
        self._queue.put(None)


ROBOT_MIC_GROUP = "239.168.123.161"  # where the G1 sends its microphone array's audio (UDP multicast)
ROBOT_MIC_PORT = 5555
RECEIVE_WAIT_S = 0.2  # how long one read waits before looking whether the source was closed
SIOCGIFADDR = 0x8915  # Linux ioctl: an interface's IPv4 address


class MulticastSource:
    """The G1's microphone array: 16 kHz mono int16 datagrams sent to a UDP multicast group.

    Plain sockets, no vendor SDK. ``interface`` (an IPv4 address or a network interface name:
    the port on the robot's network) says where to join the group; a unicast ``group`` (a
    loopback address in a test) is simply bound and read. Datagrams are joined and cut into the
    30 ms blocks the voice detector wants, whatever size the robot sends."""

    live = True

    def __init__(self, group: str = ROBOT_MIC_GROUP, port: int = ROBOT_MIC_PORT, interface: str = "lo") -> None:
        self.group, self.port = group, port
        self.address = interface_address(interface)
        self.name = f"udp:{group}:{port}"
        self._closed = False
        self.sock = self._open()

    def _open(self) -> socket.socket:
        sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            sock.bind((self.group, self.port))
            if ipaddress.ip_address(self.group).is_multicast:
                membership = socket.inet_aton(self.group) + socket.inet_aton(self.address)
                sock.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, membership)
            sock.settimeout(RECEIVE_WAIT_S)
        except (OSError, ValueError) as e:
            sock.close()
            raise AudioError(f"{self.name}: cannot listen on interface {self.address} ({e})") from None
        return sock

    def blocks(self) -> Iterator[np.ndarray]:
        import numpy as np

        size = int(RATE * BLOCK_S) * SAMPLE_BYTES
        pending = b""
        while not self._closed:
            try:
                pending += self.sock.recv(65536)
            except TimeoutError:
                continue
            except OSError:  # closed under the reader
                return
            whole = len(pending) - len(pending) % size
            for start in range(0, whole, size):
                yield np.frombuffer(pending[start:start + size], "<i2").astype(np.int16)
            pending = pending[whole:]

    def close(self) -> None:
        self._closed = True
        self.sock.close()


def interface_address(interface: str) -> str:
    """An IPv4 address as given, or the address of the network interface named ``interface``."""
    with contextlib.suppress(ValueError):
        return str(ipaddress.IPv4Address(interface))
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        try:
            packed = fcntl.ioctl(s.fileno(), SIOCGIFADDR, struct.pack("256s", interface.encode()[:15]))
        except OSError:
            names = [name for _, name in socket.if_nameindex()]
            raise AudioError(f"no IPv4 network interface {interface!r}{did_you_mean(interface, names)}; "
                             f"have: {', '.join(names)}") from None
    return socket.inet_ntoa(packed[20:24])


SOURCES: dict[str, Callable[[str, bool], Source]] = {
    "file": lambda arg, live: FileSource([arg], live),
    "mic": lambda arg, live: MicSource(arg or None),
    "-": lambda arg, live: PcmSource(),
}


def open_source(spec: str, live: bool = False, elsewhere: Sequence[str] = ()) -> Source:
    """A source by name: ``file:PATH``, ``mic``, ``mic:DEVICE``, ``-``; a bare path is a file.
    ``live``: a file plays at the speed it was spoken (for a listening robot). ``elsewhere``: the
    names a caller opens itself (the robot's ears run in a daemon), so a misspelt one is suggested
    and listed too."""
    name, _, arg = spec.partition(":")
    if spec == "-":
        return PcmSource()
    if name in SOURCES:
        return SOURCES[name](arg, live)
    if Path(spec).exists():
        return FileSource([spec], live)
    known = [*SOURCES, *elsewhere]
    listing = ", ".join(["file:PATH", "mic[:DEVICE]", *elsewhere, "- (raw PCM on stdin)"])
    raise AudioError(f"no sound source {spec!r}{did_you_mean(spec if spec in elsewhere else name, known)}; "
                     f"sources are {listing}")


@dataclass(frozen=True)
class InputDevice:
    """An audio input as PortAudio sees it."""

    index: int
    name: str
    channels: int
    default_samplerate: float


def list_input_devices() -> list[InputDevice]:
    """The machine's input devices (``stuart-bt listen --devices``)."""
    try:
        import sounddevice as sd
    except OSError as e:  # no libportaudio2
        raise AudioError(f"no microphone support: {e}") from None
    return [InputDevice(i, str(d["name"]), int(d["max_input_channels"]), float(d["default_samplerate"]))
            for i, d in enumerate(sd.query_devices()) if d["max_input_channels"] > 0]


def _input_device(device: str | None) -> InputDevice:
    devices = list_input_devices()
    if not devices:
        raise AudioError("no microphone: this machine has no audio input device (try --source file:PATH or -)")
    if device is None:
        import sounddevice as sd

        default = sd.default.device[0]
        return next((d for d in devices if d.index == default), devices[0])
    if device.isdigit():
        found = [d for d in devices if d.index == int(device)]
    else:
        found = [d for d in devices if device.lower() in d.name.lower()]
    if not found:
        names = [d.name for d in devices]
        raise AudioError(f"no input device {device!r}{did_you_mean(device, names)}; inputs: {', '.join(names)}")
    return found[0]


def _supports(sd: object, index: object, rate: int) -> bool:
    try:
        sd.check_input_settings(device=index, samplerate=rate, channels=1, dtype="int16")  # type: ignore[attr-defined]
        return True
    except Exception:  # noqa: BLE001 - PortAudio says no in several ways; any of them means "not at this rate"
        return False


def _expand(path: Path) -> list[Path]:
    if path.is_dir():
        return sorted(p for p in path.iterdir() if p.suffix.lower() in AUDIO_SUFFIXES)
    return [path]


def _split(samples: np.ndarray, step: int) -> Iterator[np.ndarray]:
    for start in range(0, len(samples), step):
        yield samples[start:start + step]


__all__ = ["SOURCES", "FileSource", "InputDevice", "MicSource", "MulticastSource", "PcmSource", "Source",
           "interface_address", "list_input_devices", "open_source"]
