"""A fake of the G1's own recogniser: every line read on stdin is published as one std_msgs
String on DDS topic ``rt/audio_msg``, on loopback only (``--domain`` keeps it private).

``ready`` is printed once the publisher exists, ``sent N`` after each sample.
"""

from __future__ import annotations

import argparse
import sys

from unitree_sdk2py.core.channel import ChannelPublisher
from unitree_sdk2py.idl.std_msgs.msg.dds_ import String_

from stuart_bt.skills.vendor import join_dds


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--domain", type=int, required=True)
    domain = parser.parse_args().domain
    join_dds(domain, "lo")
    publisher = ChannelPublisher("rt/audio_msg", String_)
    publisher.Init()
    print("ready", flush=True)
    for n, line in enumerate(sys.stdin, 1):
        publisher.Write(String_(line.rstrip("\n")))
        print(f"sent {n}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
