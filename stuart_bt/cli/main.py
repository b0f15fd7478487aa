"""``stuart-bt``: validate, draw and run behaviour trees; gesture library; the voice commands.
(The benchmarks live in the repository, not the package: ``make bench``.)

Every command prints one clear message per problem and exits non-zero on bad input; a Python
traceback only appears with ``--debug``.
"""

from __future__ import annotations

import argparse
import importlib
import os
import signal
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from .. import __version__
from ..core.errors import StuartError
from ..core.interrupts import Interrupts
from ..tree.layout import DIRECTIONS
from . import gesture
from .speed import add_speed_argument

EXIT_OK, EXIT_FAILED, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 130


class UserError(StuartError):
    """A problem the user can fix; printed as one line without a traceback."""


# -- commands ----------------------------------------------------------------------------------------
def cmd_validate(args: argparse.Namespace) -> int:
    from ..tree.errors import TreeLoadError
    from ..tree.lint import tree_warnings
    from ..tree.loader import load_tree

    status = EXIT_OK
    for file in args.files:
        try:
            spec = load_tree(file, markers_file=args.markers)
        except TreeLoadError as e:
            for error in e.errors:
                print(error, file=sys.stderr)
            status = EXIT_FAILED
            continue
        warnings = tree_warnings(spec)
        for warning in warnings:
            print(warning, file=sys.stderr)
        if not args.quiet:
            print(f"{file}: ok" + (f" ({len(warnings)} warning{'s' if len(warnings) > 1 else ''})" if warnings else ""))
    return status


def cmd_show(args: argparse.Namespace) -> int:
    from ..tree.render import render

    spec = _load(args.file, args.markers)
    fmt = args.format
    if fmt is None:
        fmt = Path(args.output).suffix.lstrip(".") if args.output else "unicode"
        if fmt not in SHOW_FORMATS:
            raise UserError(f"cannot tell the format from {args.output!r}; pass --format")
    if fmt == "yaml":  # paths inside must stay right from where the file is written
        from ..tree.export import to_yaml

        out: str | bytes = to_yaml(spec, Path(args.output).parent if args.output else Path.cwd())
    else:
        out = render(spec, fmt, direction=args.direction)
    if args.output:
        Path(args.output).parent.mkdir(parents=True, exist_ok=True)
        if isinstance(out, bytes):
            Path(args.output).write_bytes(out)
        else:
            Path(args.output).write_text(out, encoding="utf-8")
        print(f"wrote {args.output}", file=sys.stderr)
    elif isinstance(out, bytes):
        if sys.stdout.isatty():
            raise UserError(f"{fmt} is binary: pass -o FILE")
        sys.stdout.buffer.write(out)
    else:
        sys.stdout.write(out if out.endswith("\n") else out + "\n")
    return EXIT_OK


def cmd_run(args: argparse.Namespace) -> int:
    from ..run.session import RunOptions, Session
    from ..run.view import make_view

    spec = _load(args.file, args.markers)
    if args.rate <= 0 or (args.speed is not None and args.speed < 0):
        raise UserError("--rate must be positive and --speed not negative")
    if args.backend != "sim" and (args.record or args.viewer or args.map_out):
        raise UserError("--record, --viewer and --map-out need --backend sim")
    options = RunOptions(
        backend=args.backend, rate=args.rate, speed=args.speed, start=args.start,
        report=Path(args.report) if args.report else None, log=Path(args.log) if args.log else None,
        max_duration=args.max_duration, seed=args.seed, viewer=args.viewer,
        record=Path(args.record) if args.record else None, map_out=Path(args.map_out) if args.map_out else None,
        daemon_options=_daemon_options(args.daemon_options),
    )
    session = Session(spec, options)
    view = make_view(args.view, spec, session.events)
    interrupted: list[int] = []

    def on_signal(signum: int) -> None:
        # On the interrupts' own thread (stuart_bt.core.interrupts), never inside the handler.
        # Never raise here: the daemons must still be stopped and reaped. A second signal only
        # shortens the waiting for their acknowledgements.
        if interrupted:
            session.hurry()
            return
        interrupted.append(signum)
        session.request_stop(f"interrupted ({signal.Signals(signum).name})")

    # Everything is stopped and reaped when the block ends. A standalone CLI then keeps a handler
    # that exits quietly (no KeyboardInterrupt traceback while it prints the summary); an
    # in-process caller gets its own handlers back.
    with Interrupts(on_signal, then=lambda handler: handler if args.restore_signals else _exit_quietly), session:
        talk = _listen_to_typing(session) if args.talk else None
        view.start()
        try:
            outcome = session.run()
        finally:
            view.stop()
            if talk is not None:
                talk.close()
    report = session.report()
    view.summary(report)
    if args.report:
        print(f"report: {args.report}", file=sys.stderr)
    if outcome.status == "ERROR":  # the run could not go on: one sentence, no traceback
        print(f"stuart-bt: {outcome.reason}; the run was stopped", file=sys.stderr)
    if outcome.status == "SUCCESS":
        return EXIT_OK
    return 128 + interrupted[0] if interrupted else EXIT_FAILED


def _listen_to_typing(session: Any) -> Any:
    """``run --talk``: utterances typed on standard input, each a line, go to the running tree
    (:class:`~stuart_bt.mission.tour_talk.TourTalk`) from a reader thread that ends with the input."""
    import threading

    from ..language import Parser, Resolver
    from ..mission.tour_talk import TourTalk

    talk = TourTalk(session, session.executor, Parser(), Resolver.from_files(session.spec.markers_file))

    def read() -> None:
        for line in sys.stdin:
            if line.strip():
                talk.submit(line.strip())

    threading.Thread(target=read, name="talk-input", daemon=True).start()
    return talk


def cmd_schema(args: argparse.Namespace) -> int:
    import json

    from ..tree.schema import tree_schema

    text = json.dumps(tree_schema(), indent=2, ensure_ascii=False) + "\n"
    if args.output:
        Path(args.output).write_text(text, encoding="utf-8")
    else:
        sys.stdout.write(text)
    return EXIT_OK


# -- plumbing ----------------------------------------------------------------------------------------
def _daemon_options(file: str | None, also: tuple[str, ...] = ()) -> dict[str, dict[str, Any]]:
    """``--daemon-options FILE``: per-family daemon options (YAML is a superset of JSON);
    ``also``: families beyond the skill families that the command starts (``ears``)."""
    if not file:
        return {}
    import yaml

    from ..core.catalogue import FAMILIES
    from ..core.suggest import did_you_mean

    try:
        data = yaml.safe_load(Path(file).read_text(encoding="utf-8")) or {}
    except (OSError, yaml.YAMLError) as e:
        raise UserError(f"--daemon-options {file}: {e}") from None
    if not isinstance(data, dict) or not all(isinstance(v, dict) for v in data.values()):
        raise UserError(f"--daemon-options {file}: expected {{family: {{option: value}}}}, got {data!r}")
    known = (*FAMILIES, *also)
    for family in data:
        if family not in known:
            raise UserError(f"--daemon-options {file}: unknown family {family!r}{did_you_mean(str(family), known)}; "
                            f"families: {', '.join(known)}")
    return data


def _stacks_on_sigusr1() -> None:
    """``kill -USR1 PID`` prints every thread's stack on stderr and the program goes on: what a
    command that seems stuck is waiting for, without a debugger (tests use it when a run does
    not end in time)."""
    import faulthandler

    if hasattr(signal, "SIGUSR1"):
        faulthandler.register(signal.SIGUSR1, all_threads=True, chain=False)


def _exit_quietly(signum: int, _frame: Any) -> None:
    sys.stdout.flush()
    os._exit(128 + signum)


SHOW_FORMATS = ("unicode", "ascii", "dot", "svg", "png", "yaml")


def _load(file: str, markers: str | None) -> Any:
    from ..tree.errors import TreeLoadError
    from ..tree.loader import load_tree

    try:
        return load_tree(file, markers_file=markers)
    except TreeLoadError as e:
        raise UserError("\n".join(str(err) for err in e.errors)) from None


# Commands whose modules take a noticeable time to import: defined in full only when chosen, so
# validate, show and run start fast. name -> (module with add_command(subparsers), one-line summary)
VOICE_COMMANDS = {
    "parse": ("stuart_bt.cli.parse", "parse what was said into intents (JSON)"),
    "hear": ("stuart_bt.cli.hear", "hear audio files: transcript, confidence, intents (JSON lines)"),
    "listen": ("stuart_bt.cli.listen", "hear a microphone or a recording and run missions from it"),
    "plan": ("stuart_bt.cli.plan", "plan a task or an utterance with the HTN domain"),
    "mission": ("stuart_bt.cli.mission", "run an utterance end to end"),
    "chat": ("stuart_bt.cli.chat", "talk to the robot, one utterance per line"),
    "ros": ("stuart_bt.cli.ros", "a ROS 2 bridge node in front of the mission pipeline"),
    "perceive": ("stuart_bt.cli.perceive", "look once: detections, positions, a picture"),
    "map": ("stuart_bt.cli.map",
            "robot SLAM maps (unitree): start mapping, save, relocalise, pose, close"),
    "serve": ("stuart_bt.cli.serve", "the live web view: tree, mission console, map, gestures"),
}


def build_parser(selected: str | None = None) -> argparse.ArgumentParser:
    """The whole CLI; with ``selected``, only that command's module among VOICE_COMMANDS loads."""
    parser = argparse.ArgumentParser(
        prog="stuart-bt",
        description="Behaviour trees for the Unitree G1 'Stuart': validate, draw and run YAML trees.",
    )
    parser.add_argument("--version", action="version", version=f"stuart-bt {__version__}")
    parser.add_argument("--debug", action="store_true", help="show Python tracebacks for internal errors")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    p = sub.add_parser("validate", help="check tree files; print every problem as file:line:col: message")
    p.add_argument("files", nargs="+", metavar="FILE")
    p.add_argument("--markers", metavar="FILE", help="marker file (overrides the tree's 'markers:')")
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing for valid files")
    p.set_defaults(func=cmd_validate)

    p = sub.add_parser("show", help="draw a tree (text, Graphviz dot, SVG, PNG) or export it as YAML")
    p.add_argument("file", metavar="FILE")
    p.add_argument("--format", choices=SHOW_FORMATS, help="default: from -o's extension, else unicode")
    p.add_argument("-o", "--output", metavar="OUT", help="write to a file instead of stdout")
    p.add_argument("--markers", metavar="FILE", help="marker file (overrides the tree's 'markers:')")
    p.add_argument("--direction", choices=DIRECTIONS, default="auto",
                   help="dot, svg, png: lr draws the tree left to right, tb top to bottom; auto (default) "
                        "picks from the tree's shape (wide and shallow: left to right)")
    p.set_defaults(func=cmd_show)

    p = sub.add_parser("run", help="run a tree against a backend with a live view; Ctrl-C stops cleanly")
    p.add_argument("file", metavar="FILE")
    p.add_argument("--backend", choices=("dry", "sim", "unitree"), default="dry",
                   help="dry: symbolic, no world (default); sim: MuJoCo; unitree: the robot")
    p.add_argument("--rate", type=float, default=20.0, metavar="HZ", help="tick rate (default 20)")
    add_speed_argument(p, ("dry", "sim", "unitree"), interactive=False, sim_note="; 1 with --viewer")
    p.add_argument("--seed", type=int, default=0, help="sim: seed that makes a run repeatable")
    p.add_argument("--record", metavar="OUT.mp4|OUT.gif", help="sim: record the chase camera")
    p.add_argument("--map-out", metavar="OUT.png", help="sim: draw the map with the path driven")
    p.add_argument("--viewer", action="store_true", help="sim: open the interactive MuJoCo viewer")
    p.add_argument("--start", metavar="MARKER", help="marker the robot starts at (default: entrance)")
    p.add_argument("--report", metavar="OUT.json", help="write the run report")
    p.add_argument("--log", metavar="OUT.jsonl", help="write every event as JSON lines")
    p.add_argument("--view", choices=("auto", "live", "log", "none"), default="auto",
                   help="live: redrawn tree (default on a terminal); log: one line per event; none")
    p.add_argument("--max-duration", type=float, metavar="S", help="halt the run after S clock seconds")
    p.add_argument("--markers", metavar="FILE", help="marker file (overrides the tree's 'markers:')")
    p.add_argument("--daemon-options", metavar="FILE",
                   help="JSON or YAML: {family: {option: value}} for the daemons (docs/robot.md)")
    p.add_argument("--talk", action="store_true",
                   help="take utterances typed on standard input while the tree runs, one a line: a question "
                        "is answered at the next pause in speech and the tree goes on; 'Hey Stuart, stop' holds "
                        "it (motion stopped) until 'Hey Stuart, continue'")
    p.set_defaults(func=cmd_run)

    gesture.add_command(sub)
    for name, (where, summary) in VOICE_COMMANDS.items():
        if selected is None or selected == name:
            importlib.import_module(where).add_command(sub)
        else:  # listed in the help; its module (grammar, planner, executor) loads only when chosen
            sub.add_parser(name, help=summary, add_help=False)

    p = sub.add_parser("schema", help="print the JSON Schema of tree files (for editors)")
    p.add_argument("-o", "--output", metavar="FILE")
    p.set_defaults(func=cmd_schema)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    words = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(next((w for w in words if not w.startswith("-")), ""))
    args = parser.parse_args(words)
    args.restore_signals = argv is not None  # called from Python rather than as the stuart-bt program
    if not args.restore_signals:
        _stacks_on_sigusr1()
    func: Callable[[argparse.Namespace], int] = args.func
    try:
        return func(args)
    except KeyboardInterrupt:
        print("stuart-bt: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        return EXIT_OK
    except (StuartError, OSError, ValueError) as e:  # expected: the message is written for people
        if args.debug and not isinstance(e, UserError):
            raise
        text = str(e)
        print(text if "\n" in text else f"stuart-bt: {text}", file=sys.stderr)  # a list: one problem a line
        return EXIT_FAILED
    except Exception as e:
        if args.debug:
            raise
        print(f"stuart-bt: internal error: {type(e).__name__}: {e} (run with --debug for details)", file=sys.stderr)
        return EXIT_FAILED


if __name__ == "__main__":
    sys.exit(main())
