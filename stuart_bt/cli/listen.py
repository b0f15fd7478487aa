"""``stuart-bt listen``: a robot with ears. Hear a source and run missions from what is said,
until the sound ends or Ctrl-C (which stops every daemon, as everywhere).

It is ``stuart-bt chat --hear SOURCE`` without typed lines: the same executor, the same printed
events (``hearing`` lines show each utterance heard, its confidence and latency). Sources:
``mic`` / ``mic:DEVICE`` (a local microphone), ``file:PATH`` (a recording, or a folder of them),
``-`` (raw 16 kHz mono int16 PCM on stdin), ``robot`` / ``robot:asr`` (the G1's microphone
array or its own recogniser, heard in the ``ears`` daemon). docs/hearing.md.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from .chat import _arguments, cmd_chat


def add_command(subparsers: Any) -> argparse.ArgumentParser:
    """Register ``stuart-bt listen`` on an argparse sub-parser set."""
    p = subparsers.add_parser("listen", help="hear a microphone, a recording or PCM on stdin and run missions",
                              description=__doc__.split("\n\n")[0])
    _arguments(p, listening=True)
    p.set_defaults(func=cmd_listen, listen_only=True)
    return p


def cmd_listen(args: argparse.Namespace) -> int:
    return cmd_chat(args)


def main(argv: list[str] | None = None) -> int:
    """``python -m stuart_bt.cli.listen``."""
    parser = argparse.ArgumentParser(prog="stuart-bt listen", description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers()
    add_command(sub)
    return cmd_listen(parser.parse_args(["listen", *(argv or sys.argv[1:])]))


if __name__ == "__main__":
    sys.exit(main())
