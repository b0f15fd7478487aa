"""Talking to the world server: a blocking client, and a launcher for the server process.

:class:`WorldClient` is what a sim backend inside a skill daemon uses (one connection per
daemon, one request at a time, thread-safe). :func:`launch_world` is what the runner and the
tests use to start a world: its own session (a Ctrl-C on the terminal reaches the runner, which
then shuts the world down in order), a pipe on its stdin (if the launcher dies, the world sees
EOF and exits), and socket and clock paths in a fresh private directory.
"""

from __future__ import annotations

import contextlib
import itertools
import os
import select
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import IO, Any

from stuart_bt.daemon import protocol
from stuart_bt.daemon.protocol import ProtocolError

from .clock import SimClock, default_clock_path
from .errors import WorldError

READ_CHUNK = 1 << 16


class WorldClient:
    """One connection to the world server: ``call(cmd, **args)`` returns the result dict."""

    def __init__(self, socket_path: str | os.PathLike[str], timeout: float = 30.0,
                 connect_timeout: float = 5.0) -> None:
        self.socket_path = str(socket_path)
        self.timeout = timeout
        self._ids = itertools.count(1)
        self._lock = threading.Lock()
        self._buffer = b""
        self._sock = self._connect(connect_timeout)

    def _connect(self, timeout: float) -> socket.socket:
        deadline = time.monotonic() + timeout
        while True:
            sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            try:
                sock.connect(self.socket_path)
                return sock
            except (FileNotFoundError, ConnectionRefusedError) as e:
                sock.close()
                if time.monotonic() >= deadline:
                    raise WorldError("disconnected", f"no world listening on {self.socket_path}: {e}") from None
                time.sleep(0.05)

    def call(self, cmd: str, **args: Any) -> dict[str, Any]:
        """Send one request and wait for its reply; raises :class:`WorldError` on refusal."""
        with self._lock:
            request_id = f"w{next(self._ids)}"
            try:
                self._sock.sendall(protocol.encode(protocol.request(request_id, cmd, args)))
            except OSError as e:
                raise WorldError("disconnected", f"world at {self.socket_path}: {e}") from None
            deadline = time.monotonic() + self.timeout
            while True:
                reply = self._next_message(deadline)
                if reply.get("id") != request_id:
                    continue  # a stale reply to an earlier request that timed out
                if reply["type"] == protocol.DONE:
                    return reply.get("result") or {}
                if reply["type"] == protocol.ERROR:
                    raise WorldError(reply["code"], reply["reason"])
                raise WorldError("backend_error", f"the world answered {cmd} with a {reply['type']!r} line")

    def _next_message(self, deadline: float) -> dict[str, Any]:
        """The next line from the world, through the same gate and schema as a daemon's line."""
        while b"\n" not in self._buffer:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise WorldError("timeout", f"no reply from the world within {self.timeout:g} s")
            ready, _, _ = select.select([self._sock], [], [], remaining)
            if not ready:
                continue
            try:
                chunk = self._sock.recv(READ_CHUNK)
            except OSError as e:
                raise WorldError("disconnected", f"world at {self.socket_path}: {e}") from None
            if not chunk:
                raise WorldError("disconnected", f"the world at {self.socket_path} closed the connection")
            self._buffer += chunk
        line, self._buffer = self._buffer.split(b"\n", 1)
        try:
            return protocol.check_daemon_message(protocol.decode(line))
        except ProtocolError as e:
            raise WorldError("backend_error", f"the world sent a malformed line: {e.reason}") from None

    def close(self) -> None:
        with contextlib.suppress(OSError):
            self._sock.close()

    def __enter__(self) -> WorldClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class WorldProcess:
    """A running world server started by :func:`launch_world`; ``close()`` stops and reaps it."""

    def __init__(self, proc: subprocess.Popen[bytes], run_dir: Path, socket_path: Path, clock_path: Path,
                 ready: dict[str, Any], owns_dir: bool) -> None:
        self.proc = proc
        self.run_dir = run_dir
        self.socket_path = socket_path
        self.clock_path = clock_path
        self.ready = ready
        self._owns_dir = owns_dir
        self._client: WorldClient | None = None

    @property
    def pid(self) -> int:
        return self.proc.pid

    @property
    def clock_spec(self) -> str:
        """What to give daemons (``--clock``): a reader of the world's sim time."""
        return f"sim:{self.clock_path}"

    def clock(self, driver: bool = False) -> SimClock:
        return SimClock(self.clock_path, driver=driver)

    def client(self) -> WorldClient:
        """A shared connection (make your own :class:`WorldClient` for another thread's use)."""
        if self._client is None:
            self._client = WorldClient(self.socket_path)
        return self._client

    def call(self, cmd: str, **args: Any) -> dict[str, Any]:
        return self.client().call(cmd, **args)

    def close(self, timeout: float = 10.0) -> int | None:
        """Ask the world to shut down (recordings are finished first), escalating to SIGTERM
        and SIGKILL if it does not; remove the run directory. Returns the exit code."""
        if self._client is not None:
            self._client.close()
            self._client = None
        if self.proc.poll() is None:
            try:
                if self.proc.stdin is not None:
                    self.proc.stdin.close()  # the world exits on stdin EOF
                self.proc.send_signal(signal.SIGCONT)  # ... once it runs: a frozen (SIGSTOPped) world would not see it
            except OSError:
                pass
            for sig in (None, signal.SIGTERM, signal.SIGKILL):
                if sig is not None:
                    try:
                        self.proc.send_signal(sig)
                        self.proc.send_signal(signal.SIGCONT)  # a stopped world takes no signal but these
                    except ProcessLookupError:
                        break
                try:
                    self.proc.wait(timeout)
                    break
                except subprocess.TimeoutExpired:
                    continue
        elif self.proc.stdin is not None:
            self.proc.stdin.close()
        code = self.proc.wait()
        if self._owns_dir:
            shutil.rmtree(self.run_dir, ignore_errors=True)
        for path in (self.socket_path, self.clock_path):  # after a SIGKILL nobody else removes them
            with contextlib.suppress(FileNotFoundError, IsADirectoryError):
                path.unlink()
        return code

    def __enter__(self) -> WorldProcess:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def launch_world(scene: str = "lab", seed: int = 0, speed: float = 0.0, record: str | None = None,
                 record_fps: float = 10.0, viewer: bool = False, map_out: str | None = None, loc_noise: bool = False,
                 robot: str | os.PathLike[str] | None = None, start: tuple[float, float, float] | None = None,
                 run_dir: str | os.PathLike[str] | None = None, timeout: float = 60.0,
                 stderr: IO[Any] | int | None = None, extra_args: tuple[str, ...] = (),
                 hold: bool = False) -> WorldProcess:
    """Start ``python -m stuart_bt.sim.world`` and wait for its READY line.

    The socket goes into ``run_dir`` (default: a new private temporary directory, removed again
    by :meth:`WorldProcess.close`); the clock file goes next to it, or into /dev/shm with the
    default. ``stderr`` is where the world's log goes (default: inherited). Raises
    :class:`WorldError` (``start_failed``) if READY does not come in time.
    """
    owns_dir = run_dir is None
    directory = Path(tempfile.mkdtemp(prefix="stuart-world-")) if run_dir is None else Path(run_dir)
    directory.mkdir(parents=True, exist_ok=True)
    socket_path = directory / "world.sock"
    if owns_dir:
        clock_path = default_clock_path(directory.name.removeprefix("stuart-world-"))
    else:
        clock_path = directory / "world.clock"
    argv = [sys.executable, "-m", "stuart_bt.sim.world", "--socket", str(socket_path), "--clock", str(clock_path),
            "--scene", scene, "--seed", str(seed), "--speed", repr(float(speed))]
    if record:
        argv += ["--record", str(record), "--record-fps", repr(float(record_fps))]
    if viewer:
        argv.append("--viewer")
    if map_out:
        argv += ["--map-out", str(map_out)]
    if loc_noise:
        argv.append("--loc-noise")
    if hold:
        argv.append("--hold")
    if owns_dir:
        argv.append("--remove-dir")  # if this process is killed, the world still cleans up after itself
    if robot is not None:
        argv += ["--robot", str(robot)]
    if start is not None:
        argv += ["--start", ",".join(repr(float(v)) for v in start)]
    argv += list(extra_args)
    proc = subprocess.Popen(argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=stderr,
                            start_new_session=True)
    try:
        ready = _wait_ready(proc, timeout)
    except BaseException:
        proc.kill()
        proc.wait()
        if owns_dir:
            shutil.rmtree(directory, ignore_errors=True)
        raise
    return WorldProcess(proc, directory, socket_path, clock_path, ready, owns_dir)


def _wait_ready(proc: subprocess.Popen[bytes], timeout: float) -> dict[str, Any]:
    assert proc.stdout is not None
    fd = proc.stdout.fileno()
    deadline = time.monotonic() + timeout
    buffer = b""
    while b"\n" not in buffer:
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            raise WorldError("start_failed", f"the world sent no READY line within {timeout:g} s")
        ready, _, _ = select.select([fd], [], [], remaining)
        if not ready:
            continue
        chunk = os.read(fd, READ_CHUNK)
        if not chunk:
            code = proc.wait()
            raise WorldError("start_failed", f"the world exited (code {code}) before it was ready; see its stderr")
        buffer += chunk
    proc.stdout.close()  # nothing else comes on stdout
    try:
        message = protocol.check_daemon_message(protocol.decode(buffer.split(b"\n", 1)[0]))
    except ProtocolError as e:
        raise WorldError("start_failed", f"the world's first line is not protocol: {e.reason}") from None
    if message["type"] != protocol.READY:
        raise WorldError("start_failed", f"the world's first line is a {message['type']!r} line, not ready")
    return message
