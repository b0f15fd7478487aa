"""The stdlib floor for a JSON-lines round trip: a child that answers each request line.

It does the least a daemon must (parse the request, build a reply naming its id, write one line,
flush) with blocking reads and nothing else: no selector, no heartbeats, no stuart_bt import.
Whatever stuart_bt's daemon round trip costs above this is the price of its own machinery.

Run as ``python bench/echo_child.py``; exits at end of input.
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


if __name__ == "__main__":
    serve(sys.stdin.buffer, sys.stdout.buffer)
