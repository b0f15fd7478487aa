"""A plain rclpy client in its own process, as someone else's ROS 2 program would be.

It knows nothing of stuart_bt: only topic names and message types. Commands arrive on stdin,
one JSON object per line; everything it receives is printed on stdout, one JSON object per line
(flushed), with its own monotonic time ``t`` so latencies are measured on one clock:

- ``{"pub": "audio_msg", "data": "Hey Stuart, go to the kitchen"}``: publish a std_msgs/String
  (after the bridge's subscription is matched); prints ``{"sent": "/audio_msg", "t": ...}``;
- ``{"pub_int": "audio_msg", "data": 7}``: publish a std_msgs/Int32 on that topic (a wrong type);
- ``{"sub": "audio_msg"}``: also print the Strings on that topic, from now on; prints
  ``{"subscribed": "/audio_msg"}`` once a publisher (the bridge's) is matched. (Not for a topic
  this client also publishes on: its own subscription would count as the bridge's.)
- ``{"quit": true}`` or end of input: exit.

Printed: ``{"ready": true}`` once the bridge's publishers are seen; ``{"topic", "data", "t"}`` per
String received; ``{"topic", "x", "y", "yaw", "frame", "t"}`` per pose; ``{"topic", "markers", "t"}``
per MarkerArray.
Usage: ``python tests/ros_client.py [NAMESPACE]`` (ROS_DOMAIN_ID and the discovery range from the
environment).
"""

from __future__ import annotations

import json
import math
import sys
import threading
import time

import rclpy
from geometry_msgs.msg import PoseStamped
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import Int32, String
from visualization_msgs.msg import MarkerArray

STRING_TOPICS = ("llm/task_intent", "llm/response", "bt/events", "bt/status", "spatial_memory/summary")
INPUT_TOPICS = ("audio_msg", "llm/input", "stuart/mission", "pick_target")
DISCOVERY_WAIT = 20.0  # s


def main() -> int:
    namespace = sys.argv[1] if len(sys.argv) > 1 else "/"
    rclpy.init()
    node = Node("someone_elses_client", namespace=namespace)
    lock = threading.Lock()

    def emit(obj: dict) -> None:
        with lock:
            sys.stdout.write(json.dumps(obj) + "\n")
            sys.stdout.flush()

    qos = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)
    subscriptions = {}
    for topic in STRING_TOPICS:
        sub_qos = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE,
                             durability=DurabilityPolicy.TRANSIENT_LOCAL) if topic == "bt/status" else qos
        full = node.resolve_topic_name(topic)
        subscriptions[topic] = node.create_subscription(String, topic, lambda m, full=full: emit(
            {"topic": full, "data": m.data, "t": time.monotonic()}), sub_qos)
    pose_topic = node.resolve_topic_name("robot_pose")

    def on_pose(m: PoseStamped) -> None:
        q = m.pose.orientation
        emit({"topic": pose_topic, "x": m.pose.position.x, "y": m.pose.position.y,
              "yaw": 2 * math.atan2(q.z, q.w), "frame": m.header.frame_id, "t": time.monotonic()})

    node.create_subscription(PoseStamped, "robot_pose", on_pose, qos)
    markers_topic = node.resolve_topic_name("spatial_memory/markers")
    node.create_subscription(MarkerArray, "spatial_memory/markers", lambda m: emit(
        {"topic": markers_topic, "markers": [{"action": k.action, "type": k.type, "text": k.text, "frame":
                                              k.header.frame_id, "x": k.pose.position.x, "y": k.pose.position.y}
                                             for k in m.markers], "t": time.monotonic()}), qos)
    publishers = {topic: node.create_publisher(String, topic, qos) for topic in INPUT_TOPICS}
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    stopping = threading.Event()

    def spin() -> None:
        while not stopping.is_set():
            executor.spin_once(timeout_sec=0.05)

    spinner = threading.Thread(target=spin, daemon=True)
    spinner.start()

    deadline = time.monotonic() + DISCOVERY_WAIT
    while time.monotonic() < deadline and not all(  # matched, not only seen in the graph
            subscriptions[t].get_publisher_count() for t in ("llm/task_intent", "llm/response", "bt/events")):
        time.sleep(0.02)
    emit({"ready": True})
    for line in sys.stdin:
        if not line.strip():
            continue
        cmd = json.loads(line)
        if cmd.get("quit"):
            break
        if "sub" in cmd:
            full = node.resolve_topic_name(cmd["sub"])
            sub = node.create_subscription(String, cmd["sub"], lambda m, full=full: emit(
                {"topic": full, "data": m.data, "t": time.monotonic()}), qos)
            end = time.monotonic() + DISCOVERY_WAIT
            while sub.get_publisher_count() == 0 and time.monotonic() < end:
                time.sleep(0.01)
            emit({"subscribed": full})
        elif "pub" in cmd:
            pub = publishers.get(cmd["pub"]) or node.create_publisher(String, cmd["pub"], qos)
            end = time.monotonic() + DISCOVERY_WAIT
            while pub.get_subscription_count() == 0 and time.monotonic() < end:
                time.sleep(0.01)
            t = time.monotonic()
            pub.publish(String(data=cmd["data"]))
            emit({"sent": pub.topic_name, "t": t})
        elif "pub_int" in cmd:
            # DDS allows one type per topic in a participant: the wrong-typed writer gets its own
            other = Context()
            rclpy.init(context=other)
            wrong = Node("wrong_type_publisher", namespace=namespace, context=other)
            pub = wrong.create_publisher(Int32, cmd["pub_int"], qos)
            time.sleep(0.5)  # give discovery a chance to see (and refuse) the wrong type
            pub.publish(Int32(data=int(cmd["data"])))
            emit({"sent": pub.topic_name, "t": time.monotonic(), "type": "std_msgs/Int32"})
            wrong.destroy_node()
            rclpy.shutdown(context=other)
    stopping.set()
    spinner.join()
    executor.shutdown()
    node.destroy_node()
    rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
