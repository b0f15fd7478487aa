"""The world server's loop: one thread for physics and requests.

Between two physics steps the server accepts connections and answers whatever requests have
arrived (``selectors``, non-blocking sockets), so no client can stall the world and every reply
sees a consistent state. The world's sim time goes out through the shared clock file after
every step (:mod:`.clock`); when a driver is attached the world steps only up to the driver's
permit (lockstep with the tree's ticks), otherwise it runs free, optionally capped at
``--speed`` times wall time.

Protocol: the daemons' line protocol (docs/protocol.md, docs/sim.md): request ``{"id", "cmd",
"args"}``, reply a ``done`` or an ``error`` line with a code from the shared table.
"""

from __future__ import annotations

import contextlib
import math
import os
import selectors
import signal
import socket
import stat
import sys
import time
import traceback
from typing import Any

from stuart_bt.core.errors import CodedError
from stuart_bt.daemon import protocol
from stuart_bt.daemon.protocol import MAX_LINE, LineBuffer, Oversize, ProtocolError

from .clock import ClockFile
from .world import World

READ_CHUNK = 1 << 16
RATE_WINDOW = 0.25  # wall seconds over which the sim/wall rate is measured
VIEWER_PERIOD = 1.0 / 60.0


class _Client:
    def __init__(self, sock: socket.socket) -> None:
        self.sock = sock
        self.lines = LineBuffer(MAX_LINE)
        self.out = bytearray()


class Server:
    """The loop: physics steps, paced by the clock's permit and ``speed``, with requests
    answered in between."""

    def __init__(self, world: World, socket_path: str, clock: ClockFile, speed: float = 0.0,
                 watch_stdin: bool = True, viewer: Any = None, out_fd: int = 1, hold: bool = False) -> None:
        self.world = world
        self.hold = hold  # take no step until a clock driver has attached (a run starts at t = 0)
        self.socket_path = socket_path
        self.clock = clock
        self.speed = speed
        self.viewer = viewer
        self.out_fd = out_fd
        self.selector = selectors.DefaultSelector()
        self.clients: dict[int, _Client] = {}
        self.signals: list[int] = []
        self.reason = ""
        self.listener = self._listen(socket_path)
        self.selector.register(self.listener, selectors.EVENT_READ, "listen")
        self.stdin_fd: int | None = None
        if watch_stdin:
            try:
                fd = sys.stdin.fileno()
                self.selector.register(fd, selectors.EVENT_READ, "stdin")
                self.stdin_fd = fd
            except (ValueError, OSError, AttributeError):
                pass  # no usable stdin: nothing to watch
        for signum in (signal.SIGTERM, signal.SIGINT):
            signal.signal(signum, lambda signum, _frame: self.signals.append(signum))

    @staticmethod
    def _listen(path: str) -> socket.socket:
        if os.path.exists(path):
            if not stat.S_ISSOCK(os.stat(path).st_mode):
                raise FileExistsError(f"{path} exists and is not a socket")
            os.unlink(path)  # stale socket of a world that died
        sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        sock.bind(path)
        sock.listen(32)
        sock.setblocking(False)
        return sock

    # -- the loop ----------------------------------------------------------------------------

    def run(self) -> str:
        world, clock = self.world, self.clock
        wall_ref, sim_ref = time.monotonic(), world.t
        rate_wall, rate_sim = wall_ref, world.t
        idle = 5e-5
        held_by_permit = False
        next_viewer = 0.0
        clock.publish(world.t)
        while not self._should_stop():
            now_wall = time.monotonic()
            t = world.t
            if self.hold and clock.driven():
                self.hold = False
            if self.hold or (clock.driven() and t >= clock.permit):
                held_by_permit = True
                self._serve(0.0)
                time.sleep(idle)
                idle = min(idle * 2.0, 5e-4)
            else:
                if held_by_permit:  # the speed cap counts from when the world may go again
                    held_by_permit = False
                    wall_ref, sim_ref = now_wall, t
                allowed = math.inf if self.speed <= 0 else sim_ref + self.speed * (now_wall - wall_ref)
                if t < allowed:
                    world.step()
                    clock.publish(world.t)
                    idle = 5e-5
                    if allowed - world.t > 0.1 and self.speed > 0:  # fell behind: do not burst later
                        wall_ref, sim_ref = now_wall, world.t
                    self._serve(0.0)
                else:
                    self._serve(min((t - allowed) / self.speed + 1e-4, 0.005))
            if now_wall - rate_wall >= RATE_WINDOW:
                clock.set_rate((world.t - rate_sim) / (now_wall - rate_wall))
                rate_wall, rate_sim = now_wall, world.t
            if self.viewer is not None and now_wall >= next_viewer:
                next_viewer = now_wall + VIEWER_PERIOD
                if not self.viewer.is_running():
                    self.reason = "the viewer window was closed"
                    break
                with self.viewer.lock():
                    world.sync_pose()
                    self.viewer.sync()
        return self.reason

    def _should_stop(self) -> bool:
        if self.signals:
            self.reason = f"received {signal.Signals(self.signals[0]).name}"
            return True
        if self.world.stop_requested:
            self.reason = "shutdown requested"
            return True
        return bool(self.reason)

    def _serve(self, timeout: float) -> None:
        if timeout > 0 and timeout < 0.001:  # epoll waits whole milliseconds: sleep the rest
            events = self.selector.select(0)
            if not events:
                time.sleep(timeout)
                events = self.selector.select(0)
        else:
            events = self.selector.select(timeout)
        for key, mask in events:
            if key.data == "listen":
                self._accept()
            elif key.data == "stdin":
                self._read_stdin()
            else:
                client = self.clients.get(key.fd)
                if client is None:
                    continue
                if mask & selectors.EVENT_READ:
                    self._read(client)
                if mask & selectors.EVENT_WRITE and key.fd in self.clients:
                    self._flush(client)

    def _accept(self) -> None:
        try:
            sock, _ = self.listener.accept()
        except (BlockingIOError, InterruptedError):
            return
        sock.setblocking(False)
        client = _Client(sock)
        self.clients[sock.fileno()] = client
        self.selector.register(sock, selectors.EVENT_READ, "client")

    def _read_stdin(self) -> None:
        try:
            data = os.read(self.stdin_fd, READ_CHUNK)  # type: ignore[arg-type]
        except OSError:
            data = b""
        if not data:
            self.reason = "stdin closed (the parent went away)"

    def _read(self, client: _Client) -> None:
        try:
            data = client.sock.recv(READ_CHUNK)
        except (BlockingIOError, InterruptedError):
            return
        except OSError:
            data = b""
        if not data:
            self._drop(client)
            return
        for line in client.lines.feed(data):
            self._send(client, self._answer(line))
            if client.sock.fileno() not in self.clients:
                return

    def _answer(self, line: bytes | Oversize) -> dict[str, Any]:
        """One request line -> its reply, in the daemons' shape (docs/protocol.md): ``done`` with
        the result, or ``error`` with a code from the shared table. Nothing a client sends can
        take the world down."""
        if isinstance(line, Oversize):
            return protocol.error(None, "bad_request", f"line of {line.size}+ bytes is too long")
        request_id: str | None = None
        try:
            message = protocol.decode(line)
            request_id, cmd, args = protocol.parse_request(message)
            return protocol.done(request_id, self.world.handle(cmd, args))
        except ProtocolError as e:
            return protocol.error(e.request_id, "bad_request", e.reason)
        except CodedError as e:  # a WorldError, or an argument check shared with the daemons
            return protocol.error(request_id, e.code, e.reason)
        except Exception as e:  # noqa: BLE001 - a bug must not take the world down: report it, keep running
            traceback.print_exc()
            return protocol.error(request_id, "backend_error", f"{type(e).__name__}: {e}")

    def _send(self, client: _Client, message: dict[str, Any]) -> None:
        try:
            client.out += protocol.encode(message)
        except ValueError as e:  # NaN or the like in a result
            client.out += protocol.encode(protocol.error(message.get("id"), "backend_error", str(e)))
        self._flush(client)

    def _flush(self, client: _Client) -> None:
        try:
            while client.out:
                sent = client.sock.send(client.out)
                del client.out[:sent]
        except (BlockingIOError, InterruptedError):
            pass
        except OSError:
            self._drop(client)
            return
        events = selectors.EVENT_READ | (selectors.EVENT_WRITE if client.out else 0)
        self.selector.modify(client.sock, events, "client")

    def _drop(self, client: _Client) -> None:
        fd = client.sock.fileno()
        if fd in self.clients:
            del self.clients[fd]
            with contextlib.suppress(KeyError, ValueError):
                self.selector.unregister(client.sock)
        client.sock.close()

    def close(self) -> None:
        for client in list(self.clients.values()):
            try:  # last replies (e.g. to shutdown) go out before the socket closes
                client.sock.setblocking(True)
                client.sock.settimeout(0.5)
                if client.out:
                    client.sock.sendall(client.out)
            except OSError:
                pass
            self._drop(client)
        self.selector.close()
        self.listener.close()
        with contextlib.suppress(FileNotFoundError):
            os.unlink(self.socket_path)
