"""A daemon that says READY and then mixes garbage into its output between good heartbeats.

Real daemons cannot be made to do this (their stdout is private to the protocol), so this is
the only way to show the framework ignores such lines with a warning and carries on.
"""

import json
import os
import select
import sys

out = sys.stdout.buffer
out.write(json.dumps({"type": "ready", "family": "loco", "backend": "garbage", "pid": os.getpid(),
                      "protocol": 1, "commands": ["ping"]}).encode() + b"\n")
out.write(b"Vendor SDK 1.0 initialised\n[1, 2, 3]\n{\"type\": \"mystery\"}\n\xff\xfe not utf-8\n")
out.flush()
seq = 0
while True:
    readable, _, _ = select.select([sys.stdin], [], [], 0.05)
    if readable and not os.read(sys.stdin.fileno(), 4096):
        break
    seq += 1
    out.write(json.dumps({"type": "heartbeat", "seq": seq, "state": {"seq": seq}}).encode() + b"\n")
    out.flush()
