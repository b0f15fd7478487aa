"""``stuart-bt parse``: utterances in, one JSON object per utterance out.

Other programs script against this (a speech-recogniser bridge pipes its text in, a test harness
feeds a corpus), so the rules are strict:

- ``stuart-bt parse "UTTERANCE"`` (or the words unquoted) prints one JSON object on one line;
- ``stuart-bt parse --jsonl`` reads one utterance per line from stdin and prints one object per
  line, in the same order, flushed after each line. It never stops early and never prints a
  traceback: an empty line, binary garbage, invalid UTF-8 (decoded with U+FFFD), a line longer
  than 64 KiB (the first 64 KiB are parsed, ``"truncated": true`` is added) each still give one
  object; an internal error on a line gives an object with ``"error"``.

Each object: ``{"utterance", "wake", "command", "intents", "conversational"}`` (see
:mod:`stuart_bt.language.parse`), plus ``"resolution"`` (one entry per intent) with ``--markers``
or ``--objects``.

Like every module of :mod:`stuart_bt.cli`, it registers itself with ``add_command(subparsers)``.
Standalone: ``python -m stuart_bt.cli.parse [options] UTTERANCE``.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable, Iterator, Sequence
from typing import Any, BinaryIO

from ..core.jsonfile import to_json

MAX_LINE_BYTES = 64 * 1024
EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2
HELP = "parse what was said: wake phrase, intents (JSON; --jsonl for one utterance per line)"


def add_command(subparsers: Any) -> argparse.ArgumentParser:
    """Add ``parse`` to an argparse sub-command set (the main ``stuart-bt`` parser's)."""
    p = subparsers.add_parser("parse", help=HELP, description=__doc__.split("\n\n")[0])
    add_arguments(p)
    p.set_defaults(func=cmd_parse)
    return p


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("utterance", nargs="*", metavar="UTTERANCE", help="what was said (quoted, or as separate words)")
    p.add_argument("--jsonl", action="store_true", help="read one utterance per line on stdin, print one JSON "
                                                        "object per line")
    p.add_argument("--name", default="Stuart", help="the robot's name in the wake phrase (default: %(default)s)")
    p.add_argument("--greeting", action="append", metavar="WORD",
                   help="a greeting that opens the wake phrase (repeatable; replaces hey/hi/hello/ok/okay/...)")
    p.add_argument("--no-wake", action="store_true", help="parse every utterance as a command (a typed console)")
    p.add_argument("--markers", metavar="FILE", help="marker file: add 'resolution' of each target to the output")
    p.add_argument("--objects", metavar="FILE", help="object labels (skills/objects.json, a JSON list or a scene "
                                                     ".xml) for resolving pick and find targets")
    p.add_argument("--pretty", action="store_true", help="indent the JSON (not with --jsonl)")


def cmd_parse(args: argparse.Namespace) -> int:
    from ..language.parse import Parser
    from ..language.resolve import Resolver
    from ..language.wake import GREETINGS

    if args.jsonl and args.utterance:
        print("stuart-bt parse: give UTTERANCE or --jsonl, not both", file=sys.stderr)
        return EXIT_USAGE
    if not args.jsonl and not args.utterance:
        print("stuart-bt parse: give an UTTERANCE, or --jsonl to read lines from stdin", file=sys.stderr)
        return EXIT_USAGE
    parser = Parser(args.name, args.greeting or GREETINGS, require_wake=not args.no_wake)
    resolver = Resolver.from_files(args.markers, args.objects) if (args.markers or args.objects) else None

    def one(text: str, truncated: bool = False) -> dict[str, Any]:
        try:
            result = parser.parse(text)
            out = result.to_dict()
            if resolver is not None:
                out["resolution"] = [None if r is None else r.to_dict() for r in resolver.resolve_all(result.intents)]
        except Exception as e:  # noqa: BLE001 - one bad line must not end the stream
            out = {"utterance": text, "wake": False, "command": "", "intents": [], "conversational": False,
                   "error": f"{type(e).__name__}: {e}"}
        if truncated:
            out["truncated"] = True
        return out

    write = _writer()
    try:
        if args.jsonl:
            for text, truncated in read_lines(sys.stdin.buffer):
                write(to_json(one(text, truncated), ensure_ascii=False))
        else:
            text = clean(" ".join(args.utterance))
            write(to_json(one(text), ensure_ascii=False, indent=2 if args.pretty else None))
    except BrokenPipeError:  # the reader went away: nothing left to say to it
        _silence_stdout()
    return EXIT_OK


def read_lines(stream: BinaryIO, limit: int = MAX_LINE_BYTES) -> Iterator[tuple[str, bool]]:
    """(text, truncated) per line of a byte stream: the line ending removed, invalid UTF-8
    replaced, at most ``limit`` bytes kept of a longer line (the rest is read and dropped)."""
    while True:
        line = stream.readline(limit + 1)
        if not line:
            return
        truncated = False
        if len(line) > limit and not line.endswith(b"\n"):
            truncated = True
            line = line[:limit]
            while True:  # drop the rest of the line, a bounded chunk at a time
                more = stream.readline(limit)
                if not more or more.endswith(b"\n"):
                    break
        elif len(line) > limit:
            line = line[:limit]
            truncated = True
        yield line.rstrip(b"\r\n").decode("utf-8", "replace"), truncated


def clean(text: str) -> str:
    """``text`` as valid Unicode: bytes the shell passed that were not UTF-8 (surrogate escapes)
    become U+FFFD, so the JSON can always be written."""
    try:
        text.encode("utf-8")
        return text
    except UnicodeEncodeError:
        return text.encode("utf-8", "surrogateescape" if _escapes_only(text) else "replace").decode("utf-8", "replace")


def _escapes_only(text: str) -> bool:
    return all(not ("\ud800" <= c <= "\udfff") or "\udc80" <= c <= "\udcff" for c in text)


def _writer() -> Callable[[str], None]:
    """A line writer that sends UTF-8 whatever the locale says, and flushes each line."""
    buffer = getattr(sys.stdout, "buffer", None)
    if buffer is not None:
        def write(line: str) -> None:
            buffer.write(line.encode("utf-8", "replace") + b"\n")
            buffer.flush()
    else:
        def write(line: str) -> None:
            sys.stdout.write(line + "\n")
            sys.stdout.flush()
    return write


def _silence_stdout() -> None:
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m stuart_bt.cli.parse``: the same command without the main CLI."""
    p = argparse.ArgumentParser(prog="stuart-bt parse", description=__doc__.split("\n\n")[0])
    add_arguments(p)
    args = p.parse_args(argv)
    try:
        return cmd_parse(args)
    except (OSError, ValueError) as e:  # a bad --markers/--objects file: one line, no traceback
        print(f"stuart-bt parse: {e}", file=sys.stderr)
        return EXIT_FAILED
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(main())
