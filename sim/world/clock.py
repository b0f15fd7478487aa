"""The world's sim time, shared through a 64-byte memory-mapped file.

The world server writes its sim time after every physics step; every other process (the
executor, the skill daemons) maps the same file and reads it, so asking the time costs one
memory load and no system call. The file also carries a *permit*: when a driver (the executor's
:class:`SimClock` with ``driver=True``) is attached, the world steps only while its time is below
the permit, and the driver raises the permit one tick at a time. The tree's tick loop therefore
paces the world: the world runs as fast as it can while the tree keeps up, and waits when the
tree is busy, so nothing the tree decides is ever late in sim time.

Layout: eight 8-byte slots, native byte order (all readers are on the same machine).
"""

from __future__ import annotations

import contextlib
import math
import mmap
import os
import sys
import threading
import time
from pathlib import Path

MAGIC = 0x31304B4C43555453  # "STUCLK01" read as a little-endian int64
SIZE = 64
# slot indices (each 8 bytes)
_MAGIC, _TIME, _PERMIT, _DRIVER, _WORLD, _RATE, _STATE, _STOP_WALL = range(8)
RUNNING, STOPPED = 1, 2
LIVENESS_PERIOD = 0.5  # wall seconds between checks that the world (or the driver) still exists
STALL_S = 0.25  # wall seconds a world's time may stand still, with the driver waiting on it, before it is stalled


class _Slots:
    """Typed views of the mapped file: the same 64 bytes as float64 and as int64 slots.

    An aligned 8-byte slot is read and written with one machine load/store, so a reader never
    sees half of an update.
    """

    def __init__(self, path: str, create: bool) -> None:
        flags = os.O_RDWR | (os.O_CREAT | os.O_TRUNC if create else 0)
        fd = os.open(path, flags, 0o600)
        try:
            if create:
                os.ftruncate(fd, SIZE)
            elif os.fstat(fd).st_size < SIZE:
                raise ValueError(f"{path} is not a world clock file (too short)")
            self.mm = mmap.mmap(fd, SIZE)
        finally:
            os.close(fd)
        view = memoryview(self.mm)
        self.f = view.cast("d")
        self.q = view.cast("q")
        self._view = view
        if not create and self.q[_MAGIC] != MAGIC:
            self.close()
            raise ValueError(f"{path} is not a world clock file (bad magic)")

    def close(self) -> None:
        self.f.release()
        self.q.release()
        self._view.release()
        self.mm.close()


def _pid_alive(pid: int) -> bool:
    """Whether ``pid`` is a running process. A zombie (dead, not yet reaped: the world is the tree
    process's own child, reaped only when it closes the world) counts as dead; ``kill(pid, 0)``
    alone would call it alive, and a clock waiting on a dead world's time would wait forever."""
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        with open(f"/proc/{pid}/stat", "rb") as stat:
            state = stat.read().rpartition(b")")[2].split()[0]
    except (OSError, IndexError):
        return True  # no /proc to ask: kill() said it exists
    return state not in (b"Z", b"X")


class ClockFile:
    """The world server's side: creates the file, publishes time, reads the permit."""

    def __init__(self, path: str | os.PathLike[str], timestep: float) -> None:
        self.path = str(path)
        self._slots = _Slots(self.path, create=True)
        f, q = self._slots.f, self._slots.q
        f[_TIME] = 0.0
        f[_PERMIT] = 0.0
        q[_DRIVER] = 0
        q[_WORLD] = os.getpid()
        f[_RATE] = 0.0
        q[_STATE] = RUNNING
        f[_STOP_WALL] = 0.0
        q[_MAGIC] = MAGIC  # last: a reader that sees the magic sees a complete header
        self.timestep = timestep
        self._next_driver_check = 0.0

    def publish(self, t: float) -> None:
        self._slots.f[_TIME] = t

    def set_rate(self, rate: float) -> None:
        self._slots.f[_RATE] = rate

    @property
    def permit(self) -> float:
        return self._slots.f[_PERMIT]

    def driven(self) -> bool:
        """Whether a live driver is attached (a dead driver's pid is cleared, so the world free-runs)."""
        pid = self._slots.q[_DRIVER]
        if pid == 0:
            return False
        now = time.monotonic()
        if now >= self._next_driver_check:
            self._next_driver_check = now + LIVENESS_PERIOD
            if not _pid_alive(pid):
                self._slots.q[_DRIVER] = 0
                print(f"world: clock driver pid {pid} is gone; free-running", file=sys.stderr)
                return False
        return True

    def close(self, remove: bool = True) -> None:
        """Mark the clock stopped (readers continue on wall time from here) and remove the file."""
        f, q = self._slots.f, self._slots.q
        f[_STOP_WALL] = time.time()
        q[_STATE] = STOPPED
        self._slots.close()
        if remove:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(self.path)


class SimClock:
    """The world's sim time behind the :class:`stuart_bt.core.clock.Clock` protocol.

    ``driver=True`` (one per world: the executor) makes the world run in lockstep with this
    clock's :meth:`sleep_until`; any other process uses ``driver=False`` and only reads. When the
    world has exited, time carries on at wall rate from the world's last sim time, so timeouts
    still fire and a run can end instead of hanging.
    """

    def __init__(self, path: str | os.PathLike[str], driver: bool = False) -> None:
        self.path = str(path)
        try:
            self._slots = _Slots(self.path, create=False)
        except FileNotFoundError:
            raise FileNotFoundError(f"no world clock at {self.path}: is the world server running?") from None
        self._f = self._slots.f
        self._q = self._slots.q
        self.driver = driver
        self._world_pid = int(self._q[_WORLD])
        self._closed = False
        self._world_gone_at: tuple[float, float] | None = None  # (sim time, wall time) when it vanished
        self._next_liveness = 0.0
        # (sim time, monotonic time since when it has stood still while asked to move; nan: not asked)
        self._still: tuple[float, float] = (math.nan, math.nan)
        if driver:
            current = int(self._q[_DRIVER])
            if current not in (0, os.getpid()) and _pid_alive(current):
                self._slots.close()
                raise RuntimeError(f"the world at {self.path} already has a clock driver (pid {current})")
            self._q[_DRIVER] = os.getpid()

    # -- the Clock protocol ---------------------------------------------------------------

    def now(self) -> float:
        if self._world_gone_at is not None:
            sim, wall = self._world_gone_at
            return sim + (time.time() - wall)
        if self._q[_STATE] == STOPPED:
            return self._f[_TIME] + (time.time() - self._f[_STOP_WALL])
        return self._f[_TIME]

    @property
    def factor(self) -> float:
        """Sim seconds per wall second. A driver says ``inf``: time moves only when it sleeps,
        so its caller must call :meth:`sleep_until` rather than wait on the wall clock. Readers
        get the world's measured rate, never below 1 (waiting a little too briefly is harmless;
        too long would make them late)."""
        if self.driver and self.alive:
            return math.inf
        if not self.alive:
            return 1.0
        return max(1.0, self._f[_RATE])

    def sleep_until(self, t: float, wake: threading.Event | None = None, max_wall: float | None = None) -> None:
        """Wait until sim time ``t`` (a driver lets the world step up to it first). Returns early
        when ``wake`` is set (a stop request: the world may be frozen, e.g. by SIGSTOP, and Ctrl-C
        must still work), after ``max_wall`` wall seconds (the caller has other duties, such as
        keep-alives to the daemons, and calls again), and when the world is gone (then waiting on
        at wall rate)."""
        if self.driver and self.alive and self._f[_PERMIT] < t:
            self._f[_PERMIT] = t
        pause = 5e-5
        give_up = math.inf if max_wall is None else time.monotonic() + max_wall
        while True:
            now = self.now()
            if now >= t or (wake is not None and wake.is_set()) or time.monotonic() >= give_up:
                return
            if not self._check_alive():
                gone_wait = t - self.now()
                if gone_wait > 0:
                    if wake is not None:
                        wake.wait(gone_wait)
                    else:
                        time.sleep(gone_wait)
                return
            rate = self._f[_RATE]
            # the world's pace says roughly when t arrives: sleep part of that (paused: back off)
            pause = min(max(5e-5, 0.5 * (t - now) / rate), 0.02) if rate > 0 else min(pause * 2.0, 0.002)
            time.sleep(pause)

    @property
    def poll_interval(self) -> float:
        """Longest wall wait between two looks at the time for a reader with something due.
        Lockstep time comes in bursts (the executor's ticks), so dividing by the average rate
        oversleeps; a short interval keeps daemons' results on time in sim seconds."""
        return 0.002 if self.alive else math.inf

    def spec(self) -> str:
        """What a daemon needs to build a reader of the same time: ``sim:PATH``."""
        return f"sim:{self.path}"

    # -- the rest --------------------------------------------------------------------------

    @property
    def alive(self) -> bool:
        """Whether the world still publishes time (False once it stopped or vanished)."""
        return self._world_gone_at is None and self._q[_STATE] != STOPPED

    @property
    def permit(self) -> float:
        return self._f[_PERMIT]

    def world_stalled(self) -> bool:
        """Whether the world stands still while it is expected to move: alive, its time below
        the driver's permit (or running free at a measured pace) and unchanged for
        :data:`STALL_S` wall seconds, as when it is frozen by a signal, stopped in a debugger or
        starved by a loaded machine. A world waiting for the driver (time at the permit) or
        paused (no pace) is not stalled. Daemons wait on such a world, so their silence then
        is no sign of a hang (:class:`stuart_bt.daemon.supervisor.Supervisor`, ``stalled``)."""
        if not self._check_alive():
            return False
        now, wall = self._f[_TIME], time.monotonic()
        expected = now < self._f[_PERMIT] if self._q[_DRIVER] else self._f[_RATE] > 0
        if not expected or now != self._still[0]:  # moving, or not asked to: the count starts again
            self._still = (now, wall if expected else math.nan)
            return False
        if self._still[1] != self._still[1]:  # asked to move from now on
            self._still = (now, wall)
        return wall - self._still[1] >= STALL_S

    def _check_alive(self) -> bool:
        if not self.alive:
            return False
        wall = time.monotonic()
        if wall >= self._next_liveness:
            self._next_liveness = wall + LIVENESS_PERIOD
            if not _pid_alive(self._world_pid):
                self._world_gone_at = (self._f[_TIME], time.time())  # whoever runs the world says why
                return False
        return True

    def close(self) -> None:
        """Detach (a driver hands the world back to free-running)."""
        if self._closed:
            return
        self._closed = True
        if self._world_gone_at is None:
            sim = self._f[_TIME]
            self._world_gone_at = (sim, time.time())
        if self.driver and self._q[_DRIVER] == os.getpid():
            self._q[_DRIVER] = 0
        self._f = self._q = None  # type: ignore[assignment]
        self._slots.close()

    def __enter__(self) -> SimClock:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"SimClock({self.path!r}, driver={self.driver})"


def default_clock_path(tag: str) -> Path:
    """Where a world's clock file goes: /dev/shm when there is one (it is memory either way)."""
    base = Path("/dev/shm") if Path("/dev/shm").is_dir() else Path("/tmp")
    return base / f"stuart-world-{tag}.clock"
