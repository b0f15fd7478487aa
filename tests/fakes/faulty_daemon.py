"""A daemon that says READY, heartbeats, and then misbehaves on its output in one chosen way.

Run as ``python faulty_daemon.py FAULT <the real daemons' arguments>``; FAULT is one of

- ``flood``: thousands of garbage lines a second, heartbeats in between (a library printing
  into the protocol stream);
- ``huge``: one 10 MB line, then normal service;
- ``deep``: one line of 300 000 nested brackets, then normal service;
- ``mute``: heartbeats on time but never answers a command (a loop stuck past its reader);
- ``bad_numbers``: answers every command with a done whose pose holds a string, a NaN, an
  Infinity (non-standard JSON) or a 400-digit exponent.

Requests are answered with ``done`` (except in ``mute``) so a test can see the daemon go on.
Exits when its stdin closes.
"""

import json
import os
import select
import sys
import time

fault = sys.argv[1]
heartbeat = float(sys.argv[sys.argv.index("--heartbeat") + 1]) if "--heartbeat" in sys.argv else 0.1
out = os.dup(1)
BAD_POSES = [b'{"x": "abc", "y": 0, "yaw": 0}', b'{"x": NaN, "y": 0, "yaw": 0}', b'{"x": 1, "y": Infinity}',
             b'{"x": 1e400, "y": 0, "yaw": 0}']


def write(data: bytes) -> None:
    view = memoryview(data)
    while view:
        select.select([], [out], [])
        view = view[os.write(out, view):]


write(json.dumps({"type": "ready", "family": "loco", "backend": "faulty", "pid": os.getpid(), "protocol": 1,
                  "commands": ["ping"]}).encode() + b"\n")
if fault == "huge":
    write(b'{"type": "log", "level": "info", "message": "' + b"a" * 10_000_000 + b'"}\n')
elif fault == "deep":
    write(b"[" * 300_000 + b"\n")
seq, pending, answered, next_beat = 0, b"", 0, 0.0
while True:
    readable, _, _ = select.select([0], [], [], 0.001 if fault == "flood" else heartbeat / 2)
    if readable:
        chunk = os.read(0, 65536)
        if not chunk:
            break
        pending += chunk
    while b"\n" in pending:
        line, pending = pending.split(b"\n", 1)
        request = json.loads(line)
        if fault == "mute" or "id" not in request:
            continue
        if fault == "bad_numbers":
            pose = BAD_POSES[answered % len(BAD_POSES)]
            write(b'{"id": "' + request["id"].encode() + b'", "type": "done", "result": {"pose": ' + pose + b"}}\n")
        else:
            write(json.dumps({"id": request["id"], "type": "done", "result": {}}).encode() + b"\n")
        answered += 1
    if fault == "flood":
        write(b"garbage from a library that printed into the protocol\n" * 50)
    if time.monotonic() >= next_beat:
        next_beat = time.monotonic() + heartbeat
        seq += 1
        write(json.dumps({"type": "heartbeat", "seq": seq, "t": seq * heartbeat, "state": {"seq": seq}}).encode()
              + b"\n")
