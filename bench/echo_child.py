"""The stdlib floor for a JSON-lines round trip: a child that answers each request line.

It does the least a daemon must (parse the request, build a reply naming its id, write one line,
flush) with blocking reads and nothing else: no selector, no heartbeats, no stuart_bt import.
Whatever stuart_bt's daemon round trip costs above this is the price of its own machinery.

Run as ``python bench/echo_child.py [--orjson]``; exits at end of input. ``--orjson`` uses the
codec stuart_bt's protocol uses instead of the stdlib's (the same floor with a faster codec).
"""

from __future__ import annotations

import json
import sys
from typing import BinaryIO


def serve(stdin: BinaryIO, stdout: BinaryIO) -> None:
    for line in iter(stdin.readline, b""):
        request = json.loads(line)
        reply = {"id": request.get("id"), "type": "done", "result": {}}
        stdout.write(json.dumps(reply, separators=(",", ":")).encode() + b"\n")
        stdout.flush()


def serve_orjson(stdin: BinaryIO, stdout: BinaryIO) -> None:
    import orjson

    for line in iter(stdin.readline, b""):
        request = orjson.loads(line)
        stdout.write(orjson.dumps({"id": request.get("id"), "type": "done", "result": {}},
                                  option=orjson.OPT_APPEND_NEWLINE))
        stdout.flush()


if __name__ == "__main__":
    (serve_orjson if "--orjson" in sys.argv[1:] else serve)(sys.stdin.buffer, sys.stdout.buffer)
