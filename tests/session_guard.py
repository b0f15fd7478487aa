"""Nothing a test starts outlives the test session, and nothing it writes stays in /tmp.

At session start every process the suite will start is marked: an environment variable naming
this session, inherited by every child (fake robots, world servers, daemons, servers, browsers)
and by their children, even after their parent died and they were re-parented to init. Temporary
files go to a folder of the session's own (``TMPDIR``), so a test that forgets one leaves nothing
in the machine's /tmp.

At session end the processes that still carry the mark are the suite's leftovers: they are
killed, and the run fails naming each one, so a leak is found the day it is written and not on
a CI machine that fills up. The session's temporary folder is then removed.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import tempfile
import time
import uuid
from pathlib import Path

import pytest

MARK = "STUART_BT_TEST_SESSION"
GRACE = 5.0  # seconds a process that is already ending gets before it counts as left behind
GUARD = pytest.StashKey["tuple[str, Path] | None"]()


# -- the plugin (tests/conftest.py lists this module in pytest_plugins) ----------------------------

def pytest_configure(config: pytest.Config) -> None:
    if not hasattr(config, "workerinput"):  # the controlling process only, if ever run distributed
        config.stash[GUARD] = start_session()


@pytest.hookimpl(trylast=True)
def pytest_sessionfinish(session: pytest.Session, exitstatus: int) -> None:
    guard = session.config.stash.get(GUARD, None)
    if guard is None:
        return
    session.config.stash[GUARD] = None  # once
    failure = end_session(*guard)
    if failure is None:
        return
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter is not None:
        reporter.write_sep("=", "processes left behind", red=True)
        reporter.write_line(failure)
    session.exitstatus = pytest.ExitCode.TESTS_FAILED


# -- the mechanism ---------------------------------------------------------------------------------


def start_session() -> tuple[str, Path]:
    """Mark this process's children and give them a private temporary folder; (mark, folder)."""
    mark = f"{os.getpid()}-{uuid.uuid4().hex[:8]}"
    folder = Path(tempfile.mkdtemp(prefix="stuart_bt-tests-"))
    os.environ[MARK] = mark
    os.environ["TMPDIR"] = str(folder)
    # PortAudio's PulseAudio client (listing microphones) would make a runtime folder and link it
    # from ~/.config/pulse; with its own path it makes neither outside this folder
    os.environ["PULSE_RUNTIME_PATH"] = str(folder / "pulse")
    # Chromium (the browser tests) makes ~/.config/chromium for its crash reports whatever its
    # profile folder is; with the configuration home here it makes it in this folder instead
    os.environ["XDG_CONFIG_HOME"] = str(folder / "config")
    tempfile.tempdir = None  # gettempdir() looks at TMPDIR again
    return mark, folder


def marked_processes(mark: str) -> dict[int, str]:
    """Live processes (not this one, not zombies) whose environment carries ``mark``: pid -> command line."""
    needle = f"{MARK}={mark}".encode()
    found: dict[int, str] = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            if needle not in (entry / "environ").read_bytes().split(b"\0"):
                continue
            if (entry / "stat").read_text().rpartition(")")[2].split()[0] == "Z":
                continue  # already dead, waiting to be reaped by its parent
            command = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode("utf-8", "replace").strip()
        except OSError:
            continue  # gone meanwhile, or not ours to read
        found[int(entry.name)] = command[:160]
    return found


def leftovers(mark: str) -> dict[int, str]:
    """The marked processes still alive after a short grace, killed (SIGKILL) before returning."""
    deadline = time.monotonic() + GRACE
    alive = marked_processes(mark)
    while alive and time.monotonic() < deadline:
        time.sleep(0.1)
        alive = marked_processes(mark)
    for pid in alive:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.kill(pid, signal.SIGKILL)
    return alive


def end_session(mark: str, folder: Path) -> str | None:
    """Kill and name leftovers, remove the temporary folder; a failure message or None."""
    alive = leftovers(mark)
    shutil.rmtree(folder, ignore_errors=True)
    if not alive:
        return None
    lines = "\n".join(f"  pid {pid}: {command}" for pid, command in sorted(alive.items()))
    return f"{len(alive)} process(es) started by the tests were still running at the end of the session " \
           f"(now killed):\n{lines}"
