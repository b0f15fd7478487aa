"""A daemon that starts but never sends READY (a backend stuck connecting to its robot).

Takes the real daemons' arguments and ignores them; exits when its stdin closes.
"""

import sys

print("never_ready: connecting to a robot that never answers", file=sys.stderr, flush=True)
while sys.stdin.buffer.read(4096):
    pass
