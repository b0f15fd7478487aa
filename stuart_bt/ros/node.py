"""The bridge's rclpy node: subscriptions feed the mission executor, events become messages.

Threads: the event stream publishes on whatever thread did something (tick, conversation, input),
and a subscriber must not block, so :meth:`Bridge.on_event` only queues the event and triggers a
guard condition; the ROS thread (one executor spinning in :meth:`Bridge.spin`) translates and
publishes. ``/bt/status`` is published from a timer when the snapshot changed, at most
``status_rate`` times a second. Input callbacks call :meth:`MissionExecutor.submit`, which
returns at once. A callback that fails is logged and the bridge carries on.
"""

from __future__ import annotations

import contextlib
import math
import queue
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import Any

from .guard import forbid_vendor_sdk

forbid_vendor_sdk()  # before rclpy loads its DDS

import rclpy  # noqa: E402
from geometry_msgs.msg import PoseStamped  # noqa: E402
from rclpy.context import Context  # noqa: E402
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor  # noqa: E402
from rclpy.node import Node  # noqa: E402
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy  # noqa: E402
from rclpy.signals import SignalHandlerOptions  # noqa: E402
from std_msgs.msg import String  # noqa: E402

from ..core.events import Event  # noqa: E402
from ..mission.commands import clean_utterance  # noqa: E402
from ..run.snapshot import TreeSnapshot  # noqa: E402
from . import topics as t  # noqa: E402

try:  # markers need visualization_msgs (in the ros extra); without it they are not published
    from visualization_msgs.msg import Marker, MarkerArray
except ImportError:  # pragma: no cover - the extra installs it
    Marker = MarkerArray = None

NODE_NAME = "stuart_bridge"
QUEUE_DEPTH = 10
OWN_SPEECH_S = 10.0  # s: how long an utterance this node published on AUDIO_IN may take to come back to it
SPIN_SLICE = 0.1  # s: the spinning thread checks for shutdown this often


class Bridge:
    """One node in its own context, wired to one mission executor (anything with ``submit``,
    ``daemon_request`` and ``events``)."""

    def __init__(self, robot: Any, namespace: str = "/", domain_id: int | None = None,
                 status_rate: float = 10.0) -> None:
        self.robot = robot
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id, signal_handler_options=SignalHandlerOptions.NO)
        self.node = Node(NODE_NAME, namespace=namespace, context=self.context)
        self.log = self.node.get_logger()
        self.translator = t.EventTranslator()
        self._events: queue.SimpleQueue[Event] = queue.SimpleQueue()
        self._stopping = threading.Event()
        self._thread: threading.Thread | None = None
        self._ros_thread: int | None = None  # ident of the spinning thread
        self.ignored = 0  # malformed input messages logged and dropped

        reliable = QoSProfile(depth=QUEUE_DEPTH, reliability=ReliabilityPolicy.RELIABLE)
        latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                             durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.publishers: dict[str, Any] = {
            key: self.node.create_publisher(String, key, reliable)
            for key in (t.TASK_INTENT, t.RESPONSE, t.EVENTS, t.MEMORY_SUMMARY, t.AUDIO_IN)}
        self._own_speech: deque[tuple[str, float]] = deque(maxlen=32)  # what this node said on AUDIO_IN
        self.publishers[t.STATUS] = self.node.create_publisher(String, t.STATUS, latched)
        self.publishers[t.POSE] = self.node.create_publisher(PoseStamped, t.POSE, reliable)
        if MarkerArray is not None:
            self.publishers[t.MEMORY_MARKERS] = self.node.create_publisher(MarkerArray, t.MEMORY_MARKERS, reliable)
        self._marker_ids: dict[str, int] = {}

        for topic, handler in ((t.AUDIO_IN, self._utterance(t.AUDIO_IN, woken=False)),
                               (t.LLM_INPUT, self._utterance(t.LLM_INPUT, woken=True)),
                               (t.MISSION_IN, self._utterance(t.MISSION_IN, woken=True)),
                               (t.PICK_TARGET, self._on_pick_target)):
            self.node.create_subscription(String, topic, self._guarded(topic, handler), reliable)

        self._wake = self.node.create_guard_condition(self._guarded("events", self._drain))
        self.snapshot = TreeSnapshot(robot.events)
        self._status_seq = -1
        self.node.create_timer(1.0 / status_rate, self._guarded("status", self._publish_status))
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self._unsubscribe: Callable[[], None] | None = robot.events.subscribe(self.on_event)

    # -- life cycle ---------------------------------------------------------------------------------
    def start(self) -> Bridge:
        self._thread = threading.Thread(target=self.spin, name="ros-bridge", daemon=True)
        self._thread.start()
        return self

    def spin(self) -> None:
        self._ros_thread = threading.get_ident()
        while not self._stopping.is_set() and self.context.ok():
            try:
                self.executor.spin_once(timeout_sec=SPIN_SLICE)
            except ExternalShutdownException:
                return

    def close(self) -> None:
        """Stop listening to events, flush what is queued, stop the ROS thread, destroy the node."""
        if self._unsubscribe is not None:
            self._unsubscribe()
            self._unsubscribe = None
        self.snapshot.close()
        self._stopping.set()
        if self._thread is not None:
            self._thread.join(timeout=5)
            self._thread = None
        try:
            self._drain()
            self._publish_status()
        except Exception:  # noqa: BLE001 - shutting down: a publish that fails changes nothing
            pass
        self.executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        if self.context.ok():
            rclpy.shutdown(context=self.context)

    @property
    def full_name(self) -> str:
        return self.node.get_fully_qualified_name()

    def resolve(self, key: str) -> str:
        """The full name of a topic (namespace applied)."""
        return self.node.resolve_topic_name(key)

    # -- events -> ROS ------------------------------------------------------------------------------
    def on_event(self, event: Event) -> None:
        """Event stream subscriber: never blocks (a queue put and a trigger). An event published
        by the ROS thread itself (``submit`` from an input callback publishes the ``utterance``)
        is sent at once, after what was queued before it: the intent then leaves before the
        mission is even accepted, and order is kept."""
        self._events.put(event)
        if threading.get_ident() == self._ros_thread:
            self._drain()
        elif not self._stopping.is_set():
            with contextlib.suppress(Exception):  # destroyed under a late publisher: close() drains the queue
                self._wake.trigger()

    def _drain(self) -> None:
        while True:
            try:
                event = self._events.get_nowait()
            except queue.Empty:
                return
            for out in self.translator.translate(event):
                self._publish(out)

    def _publish(self, out: t.Outgoing) -> None:
        publisher = self.publishers.get(out.topic)
        if publisher is None:
            return
        if out.topic == t.POSE:
            publisher.publish(self._pose(out.payload))
        elif out.topic == t.MEMORY_MARKERS:
            publisher.publish(self._markers(out.payload))
        else:
            if out.topic == t.AUDIO_IN:  # heard here: our own subscription will get it back
                self._own_speech.append((clean_utterance(out.payload) or "", time.monotonic()))
            publisher.publish(String(data=out.payload))

    def _is_own_speech(self, text: str) -> bool:
        """Was ``text`` published on AUDIO_IN by this node (what it heard itself) lately? Then
        it was already acted on; every other node on the topic still gets it."""
        now = time.monotonic()
        for k, (said, at) in enumerate(self._own_speech):
            if said == text and now - at < OWN_SPEECH_S:
                del self._own_speech[k]
                return True
        return False

    def _publish_status(self) -> None:
        if self.snapshot.seq != self._status_seq:
            self._status_seq = self.snapshot.seq
            self.publishers[t.STATUS].publish(String(data=self.snapshot.to_json()))

    def _pose(self, p: dict[str, float]) -> PoseStamped:
        msg = PoseStamped()
        msg.header.frame_id = t.MAP_FRAME
        msg.header.stamp = self.node.get_clock().now().to_msg()
        msg.pose.position.x, msg.pose.position.y = p["x"], p["y"]
        msg.pose.orientation.z, msg.pose.orientation.w = math.sin(p["yaw"] / 2), math.cos(p["yaw"] / 2)
        return msg

    def _markers(self, objects: list[dict[str, Any]]) -> Any:
        """A sphere and a label per remembered object; DELETEALL first, so forgotten ones vanish."""
        stamp = self.node.get_clock().now().to_msg()
        clear = Marker(action=Marker.DELETEALL)
        clear.header.frame_id = t.MAP_FRAME
        markers = [clear]
        for obj in objects:
            ident = self._marker_ids.setdefault(obj["id"], len(self._marker_ids))  # stable per object
            for kind, offset in ((Marker.SPHERE, 0.0), (Marker.TEXT_VIEW_FACING, 0.15)):
                m = Marker(ns="spatial_memory", id=2 * ident + (kind == Marker.TEXT_VIEW_FACING), type=kind,
                           action=Marker.ADD, text=obj["id"] if kind == Marker.TEXT_VIEW_FACING else "")
                m.header.frame_id, m.header.stamp = t.MAP_FRAME, stamp
                m.pose.position.x, m.pose.position.y = float(obj["x"]), float(obj["y"])
                m.pose.position.z = obj["z"] + offset
                m.pose.orientation.w = 1.0
                m.scale.x = m.scale.y = m.scale.z = 0.08
                m.color.r, m.color.g, m.color.a = 0.1, 0.8, 1.0
                markers.append(m)
        return MarkerArray(markers=markers)

    # -- ROS -> the mission executor ----------------------------------------------------------------
    def _guarded(self, what: str, fn: Callable[..., None]) -> Callable[..., None]:
        """A callback that logs its failure instead of ending the ROS thread."""
        def callback(*args: Any) -> None:
            try:
                fn(*args)
            except Exception as e:  # noqa: BLE001 - one bad message must not deafen the robot
                self.log.error(f"{what}: {type(e).__name__}: {e}")
        return callback

    def _text(self, topic: str, msg: Any) -> str | None:
        text = clean_utterance(getattr(msg, "data", None))
        if text is None:
            self.ignored += 1
            raw = getattr(msg, "data", "")
            self.log.warning(f"ignored a malformed message on {self.resolve(topic)}: "
                             f"{len(raw) if isinstance(raw, str) else 0} characters, no speech in it")
            self.robot.events.publish("warning", message=f"ros: ignored a malformed message on {topic}")
        return text

    def _utterance(self, topic: str, woken: bool) -> Callable[[String], None]:
        """The callback of a text input: ``woken`` when that topic's text passed a wake filter."""
        def on_message(msg: String) -> None:
            text = self._text(topic, msg)
            if text is not None and not (topic == t.AUDIO_IN and self._is_own_speech(text)):
                self.robot.submit(text, woken=woken, source=f"ros:{topic}")
        return on_message

    def _on_pick_target(self, msg: String) -> None:
        text = self._text(t.PICK_TARGET, msg)
        if text is None:
            return
        if text.lower().strip(" .!") in t.CONFIRM_WORDS:
            if not self.robot.daemon_request("pick", "confirm"):
                self.log.warning("confirm on pick_target: nothing is running, so no pick waits for it")
                self.robot.events.publish("warning", message="ros: confirm received but no pick is waiting")
            return
        self.robot.submit(f"pick up the {text}", woken=True, source=f"ros:{t.PICK_TARGET}")
