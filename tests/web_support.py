"""What the web tests share: a ``stuart-bt serve`` process on loopback, a real Chromium, and for
tests without a browser one HTTP call (:func:`call`) and the event socket (:class:`EventFeed`).

The server is the real CLI in its own process (as a user starts it), on a free port; the
browser is Debian's Chromium driven by Playwright (never a browser download), headless, in a
fresh profile. ``STUART_BT_SCREENSHOTS=DIR`` makes the tests save a picture of each view there
(``make screenshots`` sets it to docs/images).
"""

from __future__ import annotations

import contextlib
import http.client
import json
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run"]
REPO = Path(__file__).resolve().parents[1]
STARTUP = 90.0  # wall seconds for daemons (and the simulator) to come up on a loaded machine


def free_port(host: str = "127.0.0.1") -> int:
    with socket.socket() as s:
        s.bind((host, 0))
        return s.getsockname()[1]


class Served:
    """``stuart-bt serve ARGS`` until closed; ``url`` is the address it printed."""

    def __init__(self, *args: str, host: str = "127.0.0.1", cwd: Path = REPO) -> None:
        self.port = free_port(host)
        self.log = tempfile.NamedTemporaryFile("w+", prefix="serve-", suffix=".log", delete=False)  # noqa: SIM115
        env = dict(os.environ, MUJOCO_GL="egl", PYTHONUNBUFFERED="1")
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "stuart_bt.cli", "serve", *args, "--host", host, "--port", str(self.port)],
            cwd=cwd, stdout=self.log, stderr=subprocess.STDOUT, env=env, start_new_session=True)
        self.output_text = ""
        self.url = self._wait_for_url()

    def _wait_for_url(self) -> str:
        deadline = time.monotonic() + STARTUP
        while time.monotonic() < deadline:
            text = self.output()
            found = re.search(r"serving .* at (http://\S+)", text)
            if found:
                return found.group(1)
            if self.proc.poll() is not None:
                raise AssertionError(f"stuart-bt serve exited with {self.proc.returncode}:\n{text}")
            time.sleep(0.1)
        self.close()
        raise AssertionError(f"stuart-bt serve printed no address in {STARTUP:g} s:\n{self.output()}")

    def output(self) -> str:
        return Path(self.log.name).read_text(encoding="utf-8", errors="replace")

    def close(self) -> int | None:
        """Ctrl-C, as a user stops it; the exit status (None if it had to be killed)."""
        code: int | None = self.proc.poll()
        if code is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                code = self.proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
        if not self.log.closed:
            self.output_text = self.output()
            self.log.close()
            Path(self.log.name).unlink(missing_ok=True)
        return code

    def __enter__(self) -> Served:
        return self

    def __exit__(self, kind: object, *exc: object) -> None:
        self.close()
        if kind is not None:  # the test failed: what the server said is the first thing to read
            print(f"--- stuart-bt serve said:\n{self.output_text}")


def call(served: Served, method: str, path: str, body: Any = None, raw: bytes | None = None) -> tuple[int, Any]:
    """One request to the server as a script would send it: ``body`` as JSON (or ``raw`` bytes);
    the status and the answer (JSON, or the text when it is none)."""
    conn = http.client.HTTPConnection("127.0.0.1", served.port, timeout=60)
    try:
        data = raw if raw is not None else None if body is None else json.dumps(body).encode()
        conn.request(method, path, body=data, headers={"Content-Type": "application/json"})
        response = conn.getresponse()
        text = response.read().decode("utf-8", "replace")
    finally:
        conn.close()
    try:
        return response.status, json.loads(text)
    except ValueError:
        return response.status, text


class EventFeed:
    """The server's event socket (``/ws``), read on a thread as a browser would: the ``hello``
    history, then every batch, kept in order. Close it (or use ``with``) to end the thread."""

    def __init__(self, served: Served) -> None:
        from websockets.sync.client import connect

        self.events: list[dict[str, Any]] = []
        self._cond = threading.Condition()
        self._stack = contextlib.ExitStack()  # the socket is used as its context manager (closed in close())
        self._socket = self._stack.enter_context(connect(served.url.replace("http://", "ws://").rstrip("/") + "/ws",
                                                         open_timeout=30, max_size=None))
        self._greeted = threading.Event()
        self._thread = threading.Thread(target=self._read, name="event-feed", daemon=True)
        self._thread.start()
        if not self._greeted.wait(30):  # from here on ``events`` holds at least the server's history
            self.close()
            raise AssertionError("the event socket sent no hello in 30 s")

    def _read(self) -> None:
        from websockets.exceptions import ConnectionClosed

        try:
            while True:
                message = json.loads(self._socket.recv())
                batch = message.get("events", []) if message.get("type") in ("hello", "events") else []
                with self._cond:
                    self.events.extend(batch)
                    self._cond.notify_all()
                self._greeted.set()
        except ConnectionClosed:
            pass

    def wait_for(self, pred: Callable[[dict[str, Any]], bool], timeout: float = 60.0,
                 since: int = 0) -> dict[str, Any]:
        """The first event (from index ``since`` on) that ``pred`` accepts, waiting for it; an
        AssertionError naming the last few events when none came in ``timeout`` wall seconds."""
        deadline = time.monotonic() + timeout
        with self._cond:
            while True:
                for event in self.events[since:]:
                    if pred(event):
                        return event
                since = len(self.events)
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise AssertionError(f"no such event in {timeout:g} s; the last ones: {self.events[-8:]}")
                self._cond.wait(remaining)

    def of(self, kind: str) -> list[dict[str, Any]]:
        with self._cond:
            return [e for e in self.events if e["kind"] == kind]

    def close(self) -> None:
        self._stack.close()
        self._thread.join(timeout=10)

    def __enter__(self) -> EventFeed:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def browser_tests() -> Any:
    """Skip the calling test module, with the reason, unless playwright and the web extra are
    installed; the playwright sync API."""
    pytest.importorskip("starlette", reason="the web view needs the web extra (make test installs it)")
    return pytest.importorskip("playwright.sync_api",
                               reason="the browser tests need playwright (make test installs it)")


@pytest.fixture
def page(tmp_path: Path) -> Iterator[Any]:
    """The fixture of every browser test: a page in a fresh headless Chromium profile."""
    yield from chromium_page(browser_tests(), tmp_path)


def chromium_page(playwright_mod: Any, tmp_path: Path, extra_args: tuple[str, ...] = ()) -> Iterator[Any]:
    """A page in a fresh headless Chromium profile (``extra_args``: more Chromium flags)."""
    if not Path(CHROMIUM).exists():
        pytest.skip(f"{CHROMIUM} is not installed (scripts/system-deps.sh installs Debian chromium)")
    with playwright_mod.sync_playwright() as pw:
        context = pw.chromium.launch_persistent_context(
            str(tmp_path / "profile"), executable_path=CHROMIUM, headless=True, args=[*CHROMIUM_ARGS, *extra_args],
            viewport={"width": 1400, "height": 860})
        try:
            page = context.pages[0] if context.pages else context.new_page()
            yield page
        finally:
            context.close()


def screenshot(page: Any, name: str) -> None:
    """Save ``docs/images/web_<name>.png`` (or into $STUART_BT_SCREENSHOTS) when asked to."""
    folder = os.environ.get("STUART_BT_SCREENSHOTS")
    if folder:
        Path(folder).mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(Path(folder) / f"web_{name}.png"))
