"""Fakes of the G1's ears, shared by the ears daemon's tests and ``listen --source robot``'s: the
microphone array (16 kHz int16 datagrams sent to the multicast group on loopback, at the pace
they were spoken) and the robot's own recogniser (a process publishing text on DDS
``rt/audio_msg`` in a private loopback domain). Fixtures: ``mic_array``, ``robot_recogniser``."""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from unitree_fake import private_domain

GROUP = "239.168.123.161"
DATAGRAM_SAMPLES = 512  # samples per datagram the fake robot sends (32 ms at 16 kHz)
PUBLISHER = Path(__file__).parent / "fakes" / "audio_msg_publisher.py"


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class FakeMicArray:
    """The G1's microphone array on loopback: samples sent as int16 datagrams to the multicast
    group, at the pace they were spoken, from a thread the test ends."""

    def __init__(self, port: int) -> None:
        self.port = port
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_IF, socket.inet_aton("127.0.0.1"))
        self.sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)
        self.sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def play(self, samples: np.ndarray, then_quiet_s: float = 1.5) -> None:
        """Send ``samples``, then ``then_quiet_s`` of silence (the array never stops sending: an
        utterance ends on the silence after it, as it would on the robot)."""
        if self._thread is not None:
            self._thread.join()
        samples = np.concatenate([samples, np.zeros(int(16_000 * then_quiet_s), np.int16)])
        self._thread = threading.Thread(target=self._send, args=(samples,), daemon=True)
        self._thread.start()

    def _send(self, samples: np.ndarray) -> None:
        started = time.monotonic()
        for k, first in enumerate(range(0, len(samples), DATAGRAM_SAMPLES)):
            if self._stop.is_set():
                return
            time.sleep(max(0.0, started + k * DATAGRAM_SAMPLES / 16_000 - time.monotonic()))
            self.sock.sendto(samples[first:first + DATAGRAM_SAMPLES].astype("<i2").tobytes(), (GROUP, self.port))

    def close(self) -> None:
        self._stop.set()
        if self._thread:
            self._thread.join(timeout=5)
        self.sock.close()


@pytest.fixture
def mic_array():
    arrays: list[FakeMicArray] = []

    def make(port: int) -> FakeMicArray:
        arrays.append(FakeMicArray(port))
        return arrays[-1]

    yield make
    for array in arrays:
        array.close()


class FakeRobotRecogniser:
    """The robot's recogniser: a process publishing each line given to ``send`` on ``rt/audio_msg``."""

    def __init__(self, domain: int) -> None:
        self.proc = subprocess.Popen([sys.executable, str(PUBLISHER), "--domain", str(domain)], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                                     start_new_session=True)
        assert self.proc.stdout is not None and self.proc.stdout.readline().strip() == "ready"

    def send(self, text: str) -> None:
        assert self.proc.stdin is not None and self.proc.stdout is not None
        self.proc.stdin.write(text + "\n")
        self.proc.stdin.flush()
        self.proc.stdout.readline()

    def close(self) -> None:
        with contextlib.suppress(OSError):
            if self.proc.stdin:
                self.proc.stdin.close()
        with contextlib.suppress(subprocess.TimeoutExpired):
            self.proc.wait(timeout=5)
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(self.proc.pid, signal.SIGKILL)
        self.proc.wait()


@pytest.fixture
def robot_recogniser():
    pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")
    domain, claim = private_domain()
    fake = FakeRobotRecogniser(domain)
    try:
        yield domain, fake
    finally:
        fake.close()
        claim.close()
