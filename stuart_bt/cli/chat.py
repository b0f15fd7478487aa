"""``stuart-bt chat``: talk to a long-running robot, one line of stdin per utterance.

Each line is what the speech recogniser would have heard; it goes to one
:class:`~.executor.MissionExecutor` that stays up (daemons and all) for the whole chat, and the
event stream is printed as it happens: what was heard and how it parsed, the plan's
decomposition, mission phases, what the robot says, replies and failures.

It is meant to be driven by programs as much as by people: every line is flushed as soon as it
is printed, and a few console commands make scripts deterministic without a microphone:

- ``:tree``: the tree of the mission running now (or the last one), with node statuses;
- ``:queue``: the running mission, the ones waiting behind it, and a halted one to continue;
- ``:wait [S]``: block until the robot is idle (at most S wall seconds), so a script can say
  the next thing after the last one is done;
- ``:sleep S``: wait S wall seconds (say "stop" while something is running);
- ``:quit``: end now (the running mission halts, every daemon stops).

End of input finishes what was asked first (so ``printf '...' | stuart-bt chat`` does all of
it), then ends like ``:quit``; Ctrl-C ends at once (exit 130).
"""

from __future__ import annotations

import argparse
import queue
import signal
import sys
import threading
import time
from collections.abc import Callable
from typing import Any, TextIO

from ..core.errors import StuartError
from ..core.events import Event
from ..mission.executor import Mission, MissionOptions
from ..tree.render import render
from ..tree.spec import TreeSpec
from .hear import add_hearing_arguments, make_listener
from .main import _daemon_options
from .mission import add_llm_arguments, llm_options
from .plans import TreeWatchingExecutor, plan_line
from .speed import add_speed_argument, speed_for

EXIT_OK, EXIT_FAILED, EXIT_INTERRUPTED = 0, 1, 130
EOF_WAIT = 600.0  # wall seconds to let the missions asked for finish after the input ends
PROMPT = "> "
SLICE = 0.1  # wall seconds the main thread blocks at most, so it can take signals
CLOSE_WAIT = 10.0  # wall seconds to wait for the running tree to halt when the chat ends


class ChatExecutor(TreeWatchingExecutor):
    """A mission executor that remembers the tree it runs, so ``:tree`` can draw it and the
    plan line can be printed as a mission starts."""

    def __init__(self, options: MissionOptions, on_tree: Callable[[TreeSpec, Mission], None]) -> None:
        self.tree: TreeSpec | None = None
        self._show_tree = on_tree
        super().__init__(options, self._remember)

    def _remember(self, spec: TreeSpec, mission: Mission) -> None:
        self.tree = spec
        self._show_tree(spec, mission)

    def close(self) -> None:
        """Stop the running tree before the base close. The base asks the executor running at
        that instant to stop, and misses one the worker is still building (Ctrl-C right after a
        mission started): that tree then runs to its end while close waits. So keep asking
        until the worker is out."""
        jobs = self.jobs
        with jobs.cond:
            jobs.closing = True
            jobs.cond.notify_all()
        deadline = time.monotonic() + CLOSE_WAIT
        while jobs.worker is not None and jobs.worker.is_alive() and time.monotonic() < deadline:
            with jobs.cond:
                if jobs.executor is not None:
                    jobs.executor.request_stop("shutting down")
            jobs.worker.join(0.02)
        super().close()


class ChatPrinter:
    """Prints the event stream, one flushed line per interesting event; keeps node statuses of
    the current mission tree for ``:tree``. Thread-safe: events come from the mission worker,
    the conversation thread and the input thread."""

    def __init__(self, out: TextIO) -> None:
        self.out = out
        self.statuses: dict[str, str] = {}
        self._lock = threading.Lock()

    def line(self, text: str, t: float | None = None) -> None:
        stamp = f"{t:8.2f}  " if t is not None else " " * 10
        with self._lock:
            self.out.write(stamp + text + "\n")
            self.out.flush()

    def block(self, text: str) -> None:
        with self._lock:
            self.out.write(text if text.endswith("\n") else text + "\n")
            self.out.flush()

    def snapshot(self) -> dict[str, str]:
        """The node statuses of the current mission tree, copied."""
        with self._lock:
            return dict(self.statuses)

    def on_tree(self, spec: TreeSpec, mission: Mission) -> None:
        with self._lock:
            self.statuses = {}
        self.line(plan_line(spec, mission))

    def on_event(self, event: Event) -> None:
        if event.kind == "status" and event.path is not None:
            with self._lock:
                self.statuses[event.path] = event.data.get("new", "")
            return
        text = describe(event)
        if text:
            self.line(text, event.t)


def describe(event: Event) -> str | None:
    """One line for the events a person talking to the robot cares about, else None."""
    d = event.data
    if event.kind == "utterance":
        intents = ", ".join(_intent(i) for i in d.get("intents") or [])
        extra = " instead" if d.get("replace") and d.get("kind") == "tasks" else ""
        return f"heard     {d.get('text')!r} -> {d.get('kind')}{extra}" + (f": {intents}" if intents else "")
    if event.kind == "heard":
        how = _how_heard(d)
        ignored = "" if d.get("acted") else "; ignored: the robot was speaking and it was no stop"
        return f"hearing   {d.get('text')!r} ({how}){ignored}"
    if event.kind == "mission":
        extra = d.get("reason") or d.get("status") or ", ".join(str(t) for t in d.get("tasks") or [])
        return f"mission {d.get('id')} {d.get('phase')}" + (f": {extra}" if extra else "")
    if event.kind == "reply":
        gestures = f" (gestures: {', '.join(d['gestures'])})" if d.get("gestures") else ""
        return f"reply     {d.get('text')!r}{gestures}"
    if event.kind == "command" and d.get("family") == "tts" and d.get("cmd") == "say":
        return f"says      {(d.get('args') or {}).get('text')!r}"
    if event.kind == "command" and d.get("cmd") == "play":
        args = d.get("args") or {}
        return f"gesture   {args.get('name') or args.get('sequence') or 'recorded'}"
    if event.kind == "leaf" and d.get("outcome") == "FAILURE" and d.get("skill") != "condition":
        return f"failed    {event.path}" + (f": {d['reason']}" if d.get("reason") else "")
    if event.kind == "warning":
        return f"warning   {d.get('message')}"
    if event.kind == "daemon_state" and d.get("state") not in ("ready", "starting", "stopped"):
        return f"daemon    {d.get('family')} {d.get('state')}" + (f": {d['reason']}" if d.get("reason") else "")
    return None


def _intent(intent: dict[str, Any]) -> str:
    args = ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in intent.items()
                     if k not in ("action", "raw_text", "confidence") and v not in (None, "", [], {}, 0))
    return f"{intent.get('action')}({args})"


class Chat:
    """One chat session: the executor, the printer, and the console commands."""

    def __init__(self, options: MissionOptions, out: TextIO) -> None:
        self.printer = ChatPrinter(out)
        self.robot = ChatExecutor(options, self.printer.on_tree)
        self.robot.events.subscribe(self.printer.on_event)

    def start(self) -> None:
        self.robot.start()
        supervisor = self.robot.session.supervisor
        if supervisor is not None:
            pids = ", ".join(f"{f} {supervisor.pid(f)}" for f in supervisor.families)
            self.printer.line(f"daemons   up: {pids}")
        self.printer.line("ready     say something (one line per utterance); :tree :queue :wait :quit")

    def close(self) -> None:
        self.robot.close()
        self.printer.line("bye       every daemon stopped")

    def wait_idle(self, timeout: float | None) -> bool:
        """Wait until the robot is idle, in short slices so Ctrl-C is handled meanwhile."""
        end = time.monotonic() + (timeout if timeout is not None else float("inf"))
        while not self.robot.wait_idle(min(SLICE, max(0.0, end - time.monotonic()))):
            if time.monotonic() >= end:
                return False
        return True

    def handle(self, line: str) -> bool:
        """Act on one input line; False when the chat should end."""
        text = line.strip()
        if not text:
            return True
        if not text.startswith(":"):
            self.robot.submit(text)
            return True
        word, _, arg = text[1:].partition(" ")
        if word in ("quit", "q", "exit"):
            return False
        try:
            self._console(word, arg.strip())
        except ValueError:
            self.printer.line(f"bad argument for :{word}: {arg.strip()!r} (seconds expected)")
        return True

    def _console(self, word: str, arg: str) -> None:
        if word == "tree":
            self.show_tree()
        elif word == "queue":
            self.show_queue()
        elif word == "wait":
            if not self.wait_idle(float(arg) if arg else None):
                self.printer.line("still busy")
        elif word == "sleep":
            end = time.monotonic() + float(arg or 1.0)
            while (left := end - time.monotonic()) > 0:
                time.sleep(min(left, SLICE))
        else:
            self.printer.line(f"unknown command :{word} (try :tree, :queue, :wait [S], :sleep S, :quit)")

    def show_tree(self) -> None:
        spec = self.robot.tree
        if spec is None:
            self.printer.line("no mission has run yet")
            return
        self.printer.block(str(render(spec, "unicode", self.printer.snapshot())))

    def show_queue(self) -> None:
        missions = list(self.robot.missions)
        running = [m for m in missions if m.status == "running"]
        queued = [m for m in missions if m.status == "queued"]
        if not running and not queued and self.robot.halted is None:
            self.printer.line("queue     empty" + (" (answering)" if self.robot.busy else ""))
        for m in running:
            self.printer.line(f"running   mission {m.id}: {_tasks(m)} ({m.done}/{len(m.calls)} done)")
        for m in queued:
            self.printer.line(f"queued    mission {m.id}: {_tasks(m)}")
        if self.robot.halted is not None:
            m = self.robot.halted
            self.printer.line(f"halted    mission {m.id}: {_tasks(m)} ({m.done}/{len(m.calls)} done; say continue)")


def _tasks(m: Mission) -> str:
    return ", ".join(str(c) for c in m.calls)


def add_command(subparsers: Any) -> argparse.ArgumentParser:
    """Register ``stuart-bt chat`` on an argparse sub-parser set."""
    p = subparsers.add_parser(
        "chat", help="talk to the robot: one utterance per stdin line, events printed as they happen",
        description="An interactive robot: each stdin line is an utterance for one long-running mission "
                    "executor. Console commands: :tree, :queue, :wait [S], :sleep S, :quit. End of input "
                    "finishes what was asked, then stops every daemon.")
    _arguments(p)
    p.set_defaults(func=cmd_chat)
    return p


def _how_heard(d: dict[str, Any]) -> str:
    """Confidence and latency of an utterance heard, where its recogniser gave them (the robot's
    own recogniser gives only text)."""
    confidence, latency = d.get("confidence"), d.get("latency_s")
    how = [f"confidence {confidence:.2f}" if isinstance(confidence, (int, float)) else f"{d.get('engine')} recogniser",
           f"{latency:.1f} s after the speech ended" if isinstance(latency, (int, float)) and latency else ""]
    return ", ".join(h for h in how if h)


def _arguments(p: argparse.ArgumentParser, listening: bool = False) -> None:
    """The chat's options; ``listening`` (``stuart-bt listen``): the sound source is required."""
    p.add_argument("--backend", choices=("dry", "sim"), default="dry", help="skill backend (default dry)")
    add_speed_argument(p, ("dry", "sim"), interactive=True)
    p.add_argument("--no-wake", action="store_true", help="no 'Hey Stuart' needed (a typed console)")
    p.add_argument("--start", metavar="MARKER", help="where the robot starts (default entrance)")
    p.add_argument("--max-repairs", type=int, default=2, metavar="N", help="repairs per mission (default 2)")
    sources = ("mic, mic:DEVICE, file:PATH, - for raw 16 kHz PCM on stdin, robot (the G1's microphones) or "
               "robot:asr (the G1's own recogniser)")
    if listening:
        p.add_argument("--source", dest="hear", required=True, metavar="SOURCE", help=f"what to hear: {sources}")
    else:
        p.add_argument("--hear", metavar="SOURCE", help=f"also hear SOURCE ({sources}): what is heard is said "
                                                         "like a typed line")
    p.add_argument("--daemon-options", metavar="FILE",
                   help="YAML/JSON {family: {option: value}}; 'ears' configures --source robot (docs/hearing.md)")
    add_hearing_arguments(p)
    add_llm_arguments(p)


def mission_options(args: argparse.Namespace, daemon_options: dict[str, Any]) -> MissionOptions:
    """The robot a chat (or ``listen``) talks to, from its options: a person is talking, so the
    simulator runs at real time unless ``--speed`` says otherwise. ``daemon_options`` may hold
    ``ears`` (the listener's, not a daemon the executor starts)."""
    return MissionOptions(backend=args.backend, speed=speed_for(args.backend, args.speed, interactive=True),
                          start=args.start, require_wake=not args.no_wake, max_repairs=args.max_repairs,
                          conversation=args.llm, conversation_options=llm_options(args), propose_tasks=args.propose,
                          daemon_options={k: v for k, v in daemon_options.items() if k != "ears"})


def cmd_chat(args: argparse.Namespace, stdin: TextIO | None = None, out: TextIO | None = None) -> int:
    """Run the chat until :quit, end of input or Ctrl-C; daemons are always shut down. With
    ``--hear``, what is heard is said too; when the sound comes on stdin (``-``), or for
    ``stuart-bt listen``, the chat ends when the sound does."""
    stdin, out = stdin or sys.stdin, out or sys.stdout
    try:
        daemon_options = _daemon_options(getattr(args, "daemon_options", None), also=("ears",))
        chat = Chat(mission_options(args, daemon_options), out)
        listener = make_listener(args.hear, chat.robot, args, daemon_options.get("ears", {}))
    except (StuartError, ValueError, RuntimeError) as e:  # bad options, a missing model file, no microphone
        print(f"stuart-bt: {e}", file=sys.stderr)
        return EXIT_FAILED
    status = EXIT_OK
    previous = _interrupt_handlers()
    try:
        chat.start()
        if listener is not None:
            listener.start()
        if listener is not None and (args.hear == "-" or getattr(args, "listen_only", False)):
            _until_heard(chat, listener)
        else:
            _converse(chat, stdin, out)
    except KeyboardInterrupt:
        status = EXIT_INTERRUPTED
    finally:
        try:
            if listener is not None:
                listener.close()
            chat.close()
        finally:
            for signum, handler in previous.items():
                signal.signal(signum, handler)
    if status == EXIT_OK and listener is not None and listener.error:
        status = EXIT_FAILED
    return status


def _converse(chat: Chat, stdin: TextIO, out: TextIO) -> None:
    """Typed lines until :quit or the end of input (then what was asked is finished)."""
    interactive = stdin.isatty()
    lines = _lines(stdin)
    while True:
        if interactive:
            out.write(PROMPT)
            out.flush()
        line = _next(lines)
        if line is None:  # end of input: finish what was asked
            chat.wait_idle(EOF_WAIT)
            return
        if not chat.handle(line):
            return


def _until_heard(chat: Chat, listener: Any) -> None:
    """Hear until the sound ends (a file, a closed pipe) or Ctrl-C, then finish what was asked."""
    while not listener.done.wait(SLICE):
        pass
    chat.wait_idle(EOF_WAIT)


def _lines(stdin: TextIO) -> queue.Queue[str | None]:
    """Stdin lines, read on their own thread (None at the end). The main thread must never
    block in ``read``: a signal delivered to another thread (any of the executor's) would not
    interrupt it, and Ctrl-C would wait for the next line."""
    lines: queue.Queue[str | None] = queue.Queue()

    def read() -> None:
        try:
            for line in iter(stdin.readline, ""):
                lines.put(line)
        finally:
            lines.put(None)

    threading.Thread(target=read, name="chat-stdin", daemon=True).start()
    return lines


def _next(lines: queue.Queue[str | None]) -> str | None:
    """The next line, waking every ``SLICE`` seconds so pending signals are handled."""
    while True:
        try:
            return lines.get(timeout=SLICE)
        except queue.Empty:
            continue


def _interrupt_handlers() -> dict[int, Any]:
    """Ctrl-C, and SIGTERM (a parent program ending the chat), end it through KeyboardInterrupt,
    so daemons are shut down. SIGINT is set explicitly because a chat started from a background
    job inherits it ignored, and then could not be interrupted. Returns the handlers to restore."""
    def handler(signum: int, frame: Any) -> None:
        raise KeyboardInterrupt

    if threading.current_thread() is not threading.main_thread():
        return {}  # only the main thread may set handlers (tests calling cmd_chat from threads)
    return {signal.SIGINT: signal.signal(signal.SIGINT, signal.default_int_handler),
            signal.SIGTERM: signal.signal(signal.SIGTERM, handler)}


def main(argv: list[str] | None = None) -> int:
    """``python -m stuart_bt.cli.chat``: the same command without the stuart-bt wrapper."""
    parser = argparse.ArgumentParser(prog="stuart-bt chat", description=__doc__.split("\n\n")[0])
    _arguments(parser)
    return cmd_chat(parser.parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
