"""Ctrl-C and SIGTERM are handled on the interrupts' own thread: a handler that set an event the
main thread was waiting on, from inside the handler, could hang the program (the main thread
holding the very lock that ``set`` needs: seen in the Ctrl-C test of a fresh clone)."""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap
import threading

from stuart_bt.core.interrupts import Interrupts

# The fault as it happened: the signal arrives while the main thread holds the lock of the event
# that the handling sets (as it does inside Event.wait). In a child process, so a hang fails the
# test instead of hanging it.
HELD_LOCK = textwrap.dedent("""
    import os, signal, threading, time
    from stuart_bt.core.interrupts import Interrupts

    stop = threading.Event()
    with Interrupts(lambda signum: stop.set()):
        with stop._cond:  # held, as inside stop.wait()
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.1)  # the handler runs here, on this thread
        print("stopped" if stop.wait(5.0) else "not stopped", flush=True)
""")


def test_a_signal_while_the_main_thread_holds_the_events_lock_still_sets_it_and_nothing_hangs():
    done = subprocess.run([sys.executable, "-c", HELD_LOCK], capture_output=True, text=True, timeout=30)
    assert done.returncode == 0 and done.stdout.strip() == "stopped", (done.stdout, done.stderr)


def test_the_handling_runs_on_its_own_thread_with_the_signals_number():
    seen: list[tuple[int, str]] = []
    handled = threading.Event()

    def on_signal(signum: int) -> None:
        seen.append((signum, threading.current_thread().name))
        handled.set()

    with Interrupts(on_signal):
        signal.raise_signal(signal.SIGTERM)
        assert handled.wait(5.0)
    assert seen == [(signal.SIGTERM, "interrupts")]


def test_the_handlers_that_were_in_place_come_back_or_what_then_makes_of_them():
    before = signal.getsignal(signal.SIGTERM)
    with Interrupts(lambda signum: None):
        assert signal.getsignal(signal.SIGTERM) != before
    assert signal.getsignal(signal.SIGTERM) == before

    def quiet(signum: int, frame: object) -> None:
        return None

    with Interrupts(lambda signum: None, then=lambda handler: quiet):
        pass
    try:
        assert signal.getsignal(signal.SIGTERM) is quiet
    finally:
        signal.signal(signal.SIGTERM, before)


def test_from_another_thread_nothing_is_installed():
    installed: list[dict] = []

    def elsewhere() -> None:
        with Interrupts(lambda signum: None) as caught:
            installed.append(caught.previous)

    worker = threading.Thread(target=elsewhere)
    worker.start()
    worker.join(5.0)
    assert installed == [{}]
