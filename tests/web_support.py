"""What the browser tests share: a ``stuart-bt serve`` process on loopback and a real Chromium.

The server is the real CLI in its own process (as a user starts it), on a free port; the
browser is Debian's Chromium driven by Playwright (never a browser download), headless, in a
fresh profile. ``STUART_BT_SCREENSHOTS=DIR`` makes the tests save a picture of each view there
(``make screenshots`` sets it to docs/images).
"""

from __future__ import annotations

import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
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
