"""A daemon that says READY and then sends everything a broken or hostile program could: a line
nested 300,000 deep, NaN and infinite numbers, a pose of strings, and a stream of garbage, with
good heartbeats in between. No real daemon can be made to (their stdout is private to the
protocol), so this is how the framework's edge is shown to refuse it all and carry on.
"""

import json
import os
import select
import sys

out = sys.stdout.buffer
out.write(json.dumps({"type": "ready", "family": "loco", "backend": "hostile", "pid": os.getpid(),
                      "protocol": 1, "commands": ["ping"]}).encode() + b"\n")
out.write(b"[" * 300_000 + b"]" * 300_000 + b"\n")
out.write(b'{"type": "heartbeat", "seq": 0, "state": {"pose": {"x": NaN, "y": 0, "yaw": 0}}}\n')
out.write(b'{"type": "heartbeat", "seq": 0, "state": {"pose": {"x": 1e999, "y": 0, "yaw": 0}}}\n')
out.write(b'{"type": "heartbeat", "seq": 0, "state": {"pose": {"x": Infinity, "y": 0, "yaw": 0}}}\n')
out.write(b'{"type": "heartbeat", "seq": 0, "state": {"pose": {"x": "abc", "y": 0, "yaw": 0}}}\n')
for k in range(150):  # under the flood bound (stuart_bt.daemon.limits.FAULTY_LINES): refused, not restarted
    out.write(b"garbage line %d from a babbling vendor library\n" % k)
out.flush()
seq = 0
while True:
    readable, _, _ = select.select([sys.stdin], [], [], 0.05)
    if readable and not os.read(sys.stdin.fileno(), 4096):
        break
    seq += 1
    out.write(json.dumps({"type": "heartbeat", "seq": seq, "state": {"seq": seq, "pose": {"x": 1.0, "y": 2.0,
                                                                                          "yaw": 0.5}}}).encode()
              + b"\n")
    out.flush()
