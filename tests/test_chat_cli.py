"""``stuart-bt chat`` as a program drives it: a subprocess fed line by line on stdin, its output
read line by line as it comes (which is what proves the per-line flushing), on the dry backend.

Each test also checks that every daemon the chat started is gone once it has exited.
"""

from __future__ import annotations

import queue
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
CANNED = "Sorry, I can only follow commands for now"


class ChatProcess:
    """The chat in a child process; ``expect`` waits for an output line matching a pattern."""

    def __init__(self, *args: str) -> None:
        self.proc = subprocess.Popen([sys.executable, "-m", "stuart_bt.cli.chat", *args], cwd=REPO,
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True, bufsize=1)
        self.lines: list[str] = []
        self._new: queue.Queue[str] = queue.Queue()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.append(line.rstrip("\n"))
            self._new.put(line)

    def say(self, line: str) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.write(line + "\n")
        self.proc.stdin.flush()

    def expect(self, pattern: str, timeout: float = 20.0) -> str:
        """The first line (seen so far or to come) that matches ``pattern``."""
        regex = re.compile(pattern)
        deadline = time.monotonic() + timeout
        seen = 0
        while True:
            for line in self.lines[seen:]:
                if regex.search(line):
                    return line
            seen = len(self.lines)
            try:
                self._new.get(timeout=max(0.0, min(0.2, deadline - time.monotonic())))
            except queue.Empty:
                if time.monotonic() > deadline:
                    raise AssertionError(f"no line matching {pattern!r} in:\n" + "\n".join(self.lines)) from None

    def finish(self, timeout: float = 30.0) -> int:
        code = self.proc.wait(timeout)
        self._reader.join(5)
        return code

    @property
    def output(self) -> str:
        return "\n".join(self.lines)

    def daemon_pids(self) -> list[int]:
        line = self.expect(r"daemons\s+up:")
        return [int(p) for p in re.findall(r"\w+ (\d+)", line.split("up:", 1)[1])]

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(5)


def alive(pid: int) -> bool:
    """Running (a zombie waiting for a reaper that never comes does not count)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state not in ("Z", "X")


@pytest.fixture
def chat_process():
    started: list[ChatProcess] = []

    def start(*args: str) -> ChatProcess:
        chat = ChatProcess(*args)
        started.append(chat)
        return chat

    yield start
    for chat in started:
        chat.kill()


def test_command_conversation_stop_and_quit(chat_process):
    chat = chat_process("--speed", "4")
    pids = chat.daemon_pids()
    assert len(pids) == 5  # loco, tts, gesture, pick, vision

    chat.say("Hey Stuart, go to the bathroom")
    chat.expect(r"heard\s+'Hey Stuart, go to the bathroom' -> tasks: navigate_to_marker\(target=bathroom\)")
    chat.expect(r"plan\s+mission 1: navigate_to_marker \[speak > navigate\]")
    chat.expect(r"says\s+'Navigating to the bathroom'")
    chat.say("Hey Stuart, how are you today?")
    chat.expect(r"heard\s+'Hey Stuart, how are you today\?' -> conversation")
    chat.expect(rf"reply\s+'{CANNED}")
    chat.say("Hey Stuart, stop")
    chat.expect(r"heard\s+'Hey Stuart, stop' -> stop")
    chat.expect(r"mission 1 stopped")
    chat.say(":queue")
    chat.expect(r"halted\s+mission 1: navigate_to_marker\(place=bathroom\) .*say continue")
    chat.say(":tree")
    chat.expect(r"navigate marker=bathroom")
    chat.say(":quit")

    assert chat.finish() == 0
    assert "bye" in chat.lines[-1]
    assert not [p for p in pids if alive(p)], chat.output


def test_piped_script_runs_to_the_end_of_input(tmp_path: Path):
    """A whole script at once, no :quit: end of input lets the mission finish, then exits."""
    script = "go to the kitchen\n:wait\nwhat is your name\n"
    done = subprocess.run([sys.executable, "-m", "stuart_bt.cli.chat", "--no-wake", "--speed", "50"],
                          check=False, cwd=REPO,
                          input=script, capture_output=True, text=True, timeout=60)

    assert done.returncode == 0, done.stderr[-2000:]
    out = done.stdout
    assert out.index("mission 1 finished: succeeded") < out.index("-> conversation")
    assert f"says      '{CANNED}" in out  # the reply was spoken before the chat ended
    pids = [int(p) for p in re.findall(r"\w+ (\d+)", out.split("up:", 1)[1].splitlines()[0])]
    assert pids and not [p for p in pids if alive(p)]


def test_interrupt_halts_the_mission_and_stops_every_daemon(chat_process):
    chat = chat_process("--speed", "2", "--no-wake")
    pids = chat.daemon_pids()
    chat.say("go to the bathroom")
    chat.expect(r"mission 1 started")

    chat.proc.send_signal(signal.SIGINT)

    assert chat.finish() == 130
    assert not [p for p in pids if alive(p)], chat.output


def test_unknown_console_command_says_what_exists(chat_process):
    chat = chat_process("--speed", "50")
    chat.say(":wait soon")
    chat.expect(r"bad argument for :wait")
    chat.say(":frobnicate")
    chat.expect(r"unknown command :frobnicate \(try :tree, :queue")
    chat.say(":tree")
    chat.expect("no mission has run yet")
    chat.proc.stdin.close()  # end of input with nothing to finish
    assert chat.finish() == 0


def test_chat_is_registered_through_its_add_command():
    import argparse

    from stuart_bt.cli.chat import add_command, cmd_chat

    parser = argparse.ArgumentParser(prog="stuart-bt")
    add_command(parser.add_subparsers())
    args = parser.parse_args(["chat", "--backend", "dry", "--no-wake", "--speed", "3"])
    assert args.func is cmd_chat and args.no_wake and args.speed == 3.0 and args.backend == "dry"
