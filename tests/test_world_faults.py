"""The simulator's world server dying, freezing, or losing its tree process: the run ends with one
clear sentence and a stopped robot, Ctrl-C always works, and nothing is left behind.

Each test runs ``stuart-bt run`` as a real process in its own process group, finds its world
server among its children, does something bad to one of them, and ends everything it started
even when it fails.
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from stuart_bt.daemon.supervisor import DaemonStartError
from stuart_bt.run.session import RunOptions, Session
from stuart_bt.tree.loader import load_tree

pytest.importorskip("mujoco", reason="the world server needs the 'sim' extra")

REPO = Path(__file__).resolve().parents[1]
TOUR = REPO / "trees" / "lab_tour.yaml"
WAIT = 60.0  # wall seconds for anything to happen on a loaded machine


def _children(pid: int) -> dict[int, str]:
    """pid -> command line of every live process below ``pid``."""
    parents: dict[int, list[int]] = {}
    for proc in Path("/proc").iterdir():
        if proc.name.isdigit():
            try:
                ppid = int((proc / "stat").read_text().rpartition(")")[2].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            parents.setdefault(ppid, []).append(int(proc.name))
    out: dict[int, str] = {}
    stack = list(parents.get(pid, []))
    while stack:
        child = stack.pop()
        out[child] = _cmdline(child)
        stack += parents.get(child, [])
    return out


def _cmdline(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode("utf-8", "replace")
    except OSError:
        return ""


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rpartition(")")[2].split()[0]
    except (OSError, IndexError):
        return False
    return state != "Z"


def _wait(predicate, what: str, timeout: float = WAIT) -> float:
    """Seconds until ``predicate()`` held; fails the test naming ``what`` after ``timeout``."""
    start = time.monotonic()
    while not predicate():
        if time.monotonic() - start > timeout:
            raise AssertionError(f"timed out after {timeout:g} s waiting for {what}")
        time.sleep(0.02)
    return time.monotonic() - start


class Run:
    """``stuart-bt run TOUR --backend sim`` in its own process group."""

    def __init__(self, tmp_path: Path) -> None:
        self.report = tmp_path / "report.json"
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "stuart_bt.cli", "run", str(TOUR), "--backend", "sim", "--view", "log",
             "--speed", "1", "--report", str(self.report)],
            cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
        self.started: dict[int, str] = {}

    def world(self) -> int:
        """The world server's pid, once it and the daemons are up (the tour has started walking)."""
        def up() -> bool:
            if self.proc.poll() is not None:
                raise AssertionError(f"the run ended before its world started: {self.proc.stderr.read()[-800:]}")
            self.started = _children(self.proc.pid)
            return any("stuart_bt.sim.world" in c for c in self.started.values()) and \
                any("stuart_bt.skills.loco" in c for c in self.started.values())
        _wait(up, "the world server and the daemons to start")
        time.sleep(1.0)  # let the tour get going
        self.started = _children(self.proc.pid)
        return next(pid for pid, c in self.started.items() if "stuart_bt.sim.world" in c)

    def world_dir(self, world: int) -> Path:
        words = self.started[world].split()
        return Path(words[words.index("--socket") + 1]).parent

    def finish(self, timeout: float = WAIT) -> tuple[int, str]:
        _, err = self.proc.communicate(timeout=timeout)
        return self.proc.returncode, err

    def end(self) -> None:
        """Whatever happened: nothing this run started is left."""
        for pid in [self.proc.pid, *self.started]:
            try:
                os.kill(pid, signal.SIGCONT)
                os.kill(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        with contextlib.suppress(subprocess.TimeoutExpired, ValueError):
            self.proc.communicate(timeout=10)


@pytest.fixture
def run(tmp_path: Path) -> Iterator[Run]:
    made = Run(tmp_path)
    try:
        yield made
    finally:
        made.end()


@pytest.mark.slow
@pytest.mark.timeout(240)
def test_a_killed_world_server_ends_the_run_with_one_clear_error_and_stopped_daemons(run: Run):
    world = run.world()
    os.kill(world, signal.SIGKILL)
    took = _wait(lambda: run.proc.poll() is not None, "the run to end after its world died")
    code, err = run.finish()
    assert code == 1
    assert "world server" in err and "SIGKILL" in err
    assert "Traceback" not in err
    assert not [pid for pid in run.started if _alive(pid)], "daemons outlived the run"
    assert not run.world_dir(world).exists()
    print(f"run ended {took:.2f} s after the world was killed")


@pytest.mark.slow
@pytest.mark.timeout(240)
def test_ctrl_c_stops_the_run_even_while_the_world_is_frozen(run: Run):
    world = run.world()
    os.kill(world, signal.SIGSTOP)
    time.sleep(1.0)  # the tree waits for sim time that does not come
    os.kill(run.proc.pid, signal.SIGINT)
    took = _wait(lambda: run.proc.poll() is not None, "the run to end after Ctrl-C")
    code, err = run.finish()
    assert code == 130
    assert "Traceback" not in err
    assert not [pid for pid in run.started if _alive(pid)]
    print(f"run ended {took:.2f} s after Ctrl-C with its world frozen")


@pytest.mark.slow
@pytest.mark.timeout(240)
def test_a_world_frozen_for_a_while_carries_on_when_it_resumes(run: Run):
    world = run.world()
    os.kill(world, signal.SIGSTOP)
    time.sleep(3.0)
    assert run.proc.poll() is None, "a frozen world is waited for, not given up on"
    os.kill(world, signal.SIGCONT)
    time.sleep(2.0)
    assert run.proc.poll() is None, f"the run ended after its world resumed: {run.finish()}"
    assert _alive(world)
    os.kill(run.proc.pid, signal.SIGTERM)
    code, err = run.finish()
    assert code == 143 and "Traceback" not in err
    events = json.loads(run.report.read_text())["events"]
    lost = [e["reason"] for e in events if e["kind"] == "daemon_state" and e["state"] in ("hung", "died")]
    assert lost == [], "a daemon waiting on the frozen world was taken for hung"


@pytest.mark.slow
@pytest.mark.timeout(240)
def test_killing_the_tree_process_leaves_no_world_daemon_or_world_folder_behind(run: Run):
    world = run.world()
    folder = run.world_dir(world)
    assert folder.exists()
    os.kill(run.proc.pid, signal.SIGKILL)
    took = _wait(lambda: not [pid for pid in run.started if _alive(pid)], "the world and daemons to exit")
    _wait(lambda: not folder.exists(), f"{folder} to be removed", timeout=10)
    print(f"world and daemons gone {took:.2f} s after the tree process was killed")


class _WorldKilledBeforeTheDaemons(Session):
    """A session whose world server is killed the moment it is up, before a daemon starts."""

    def _start_world(self, start) -> None:
        super()._start_world(start)
        os.kill(self.world.pid, signal.SIGKILL)
        self.world.proc.wait(timeout=WAIT)


@pytest.mark.slow
def test_a_world_that_dies_while_the_daemons_start_is_named_as_the_cause():
    session = _WorldKilledBeforeTheDaemons(load_tree(TOUR), RunOptions(backend="sim"))
    with pytest.raises(DaemonStartError) as failed:
        session.start()
    session.close()
    message = str(failed.value)
    assert message.startswith("the simulator's world server") and "killed by SIGKILL" in message, message
    assert "while the daemons were starting" in message and "Traceback" not in message
    assert session.supervisor is not None
    assert all(d.process is None or d.process.poll() is not None for d in session.supervisor._daemons.values())
