"""A flood of speech on ``/audio_msg``, from another process, as a crowded room or a babbling
recogniser would send it: ``python -m bench.ros_flood SECONDS [RATE]``.

It publishes std_msgs/String at RATE messages per second (default 500, about the rate of the
flood that once delayed a good command by 57 s) for SECONDS, cycling through chatter the
bridge must answer (questions to the robot), text without the wake phrase, nonsense after the
wake phrase and over-long text, then prints one JSON line ``{"sent": N, "seconds": S}`` and
exits. Nothing in it moves the robot: the soak benchmark checks that a good command said right
after the flood still starts its mission at once. ROS_DOMAIN_ID and the discovery range come
from the environment (bench/soak.py sets them like the tests do).
"""

from __future__ import annotations

import json
import sys
import time

CHATTER = (
    "Hey Stuart, how are you today?",
    "Hey Stuart, what is your favourite colour?",
    "and then we went to the shops",
    "Hey Stuart, blorf the snarkle quickly",
    "Hey Stuart, tell me about the lab",
    "x" * 5000,
)
DISCOVERY_WAIT = 20.0  # seconds for the bridge's subscription to be matched


def main(argv: list[str]) -> int:
    import rclpy
    from rclpy.node import Node
    from rclpy.qos import QoSProfile, ReliabilityPolicy
    from std_msgs.msg import String

    seconds = float(argv[0]) if argv else 30.0
    rate = float(argv[1]) if len(argv) > 1 else 500.0
    rclpy.init()
    node = Node("soak_flood")
    reliable = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)
    publisher = node.create_publisher(String, "audio_msg", reliable)
    deadline = time.monotonic() + DISCOVERY_WAIT
    while publisher.get_subscription_count() == 0 and time.monotonic() < deadline:
        time.sleep(0.01)
    sent, start = 0, time.monotonic()
    while (now := time.monotonic() - start) < seconds:
        if sent > now * rate:  # ahead of the pace: wait for it
            time.sleep(min(0.005, sent / rate - now))
            continue
        publisher.publish(String(data=CHATTER[sent % len(CHATTER)]))
        sent += 1
    took = time.monotonic() - start
    print(json.dumps({"sent": sent, "seconds": round(took, 3)}), flush=True)
    node.destroy_node()
    rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
