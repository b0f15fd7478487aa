"""Fake G1 vendor services on DDS, for tests: the robot's side of every call the unitree daemons make.

Run as a helper process (``python tests/fakes/unitree_services.py --domain N``): it joins DDS on
the loopback interface only, serves "sport" (and "loco", the older firmware's name), "voice",
"arm" and "slam_operate" with the SDK's own RPC server classes, publishes the relocation
odometry and the navigation arrival flags, listens to ``rt/arm_sdk`` and the Dex3 hand topics,
and behaves like the robot: a velocity command moves it for its duration, a navigation goal
walks it there in a straight line and raises ``is_arrived``, a holding arm action refuses the
next one with 7401 until "release arm" (99).

Every request and every arm/hand sample is printed to stdout as one JSON line (``kind`` rpc or
topic) for the test to assert on. stdin takes JSON lines that script faults::

    {"fault": {"service": "arm", "api": 7106, "code": 7400, "times": 1}}   # answer with an error
    {"fault": {"service": "slam_operate", "api": 1102, "silent": true}}    # no answer: a timeout
    {"arrive": false}                                                      # navigation gives up
    {"ping": 7}                                                            # answered with a "pong" record
"""

from __future__ import annotations

import argparse
import contextlib
import ctypes
import json
import math
import os
import signal
import sys
import threading
import time
from typing import Any

from unitree_sdk2py.core.channel import ChannelFactory, ChannelPublisher, ChannelSubscriber
from unitree_sdk2py.idl.default import (
    nav_msgs_msg_dds__Odometry_,
    std_msgs_msg_dds__String_,
)
from unitree_sdk2py.idl.nav_msgs.msg.dds_ import Odometry_
from unitree_sdk2py.idl.std_msgs.msg.dds_ import String_
from unitree_sdk2py.idl.unitree_api.msg.dds_ import Response_, ResponseHeader_, ResponseStatus_
from unitree_sdk2py.idl.unitree_hg.msg.dds_ import HandCmd_, LowCmd_
from unitree_sdk2py.rpc.client import Client
from unitree_sdk2py.rpc.server_base import ServerBase
from unitree_sdk2py.utils.crc import CRC

from stuart_bt.skills.vendor import join_dds

VERSIONS = {"sport": "1.0.0.0", "loco": "1.0.0.0", "voice": "1.0.0.0", "arm": "1.0.0.14", "slam_operate": "1.0.0.1"}
HOLDING_ACTIONS = {15, 18, 19, 20, 21, 23, 27}
KNOWN_ACTIONS = {99, 11, 12, 13, 15, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27}
ACTION_SECONDS = 0.1  # the fake plays every arm action this long (the daemon waits longer)
WEIGHT_MOTOR = 29
PROBE_SECONDS = 20.0  # how long the fake asks its own services before it gives up starting
PR_SET_PDEATHSIG = 1

# cyclonedds' Python binding creates a topic holding the GIL, and may need the GIL again inside
# its topic lock (freeing a duplicate type): two threads creating topics at once can deadlock,
# each holding what the other waits for. Every DDS reader and writer in this process is created
# under this one lock, so at most one thread is ever inside topic creation.
_DDS_CREATION = threading.Lock()


def _one_creator_at_a_time(create: Any) -> Any:
    def serialised(*args: Any, **kwargs: Any) -> Any:
        with _DDS_CREATION:
            return create(*args, **kwargs)
    return serialised


ChannelFactory.CreateSendChannel = _one_creator_at_a_time(ChannelFactory.CreateSendChannel)
ChannelFactory.CreateRecvChannel = _one_creator_at_a_time(ChannelFactory.CreateRecvChannel)


class Robot:
    """The robot's state and its answers; every service thread calls in here."""

    def __init__(self, nav_speed: float, out: Any) -> None:
        self.lock = threading.Lock()
        self.out = out
        self.nav_speed = nav_speed
        self.x = self.y = self.yaw = 0.0
        self.localised = True  # SLAM already localised (at 0, 0, 0) unless a relocalisation moves it
        self.velocity = (0.0, 0.0, 0.0)
        self.velocity_until = 0.0
        self.goal: tuple[float, float, float] | None = None
        self.paused = False
        self.arrive = True
        self.holding: int | None = None
        self.action_until = 0.0
        self.faults: list[dict[str, Any]] = []
        self.arrivals: list[bool] = []  # flags to publish on rt/slam_key_info
        self.crc = CRC()
        self.subscribers: list[Any] = []  # kept alive as long as the fake runs

    def record(self, **fields: Any) -> None:
        line = json.dumps({"t": round(time.monotonic(), 4), **fields})
        with self.lock:
            self.out.write(line + "\n")
            self.out.flush()

    # -- RPC ------------------------------------------------------------------------------------
    def answer(self, service: str, api: int, parameter: str, binary: list[int]) -> tuple[int | None, str]:
        try:
            payload: Any = json.loads(parameter) if parameter else {}
        except ValueError:
            payload = parameter
        fault = self._fault(service, api)
        code: int | None
        if fault is not None:
            code, data = (None if fault.get("silent") else int(fault.get("code", 0))), ""
        else:
            code, data = self._serve(service, api, payload)
        self.record(kind="rpc", service=service, api=api, parameter=payload, binary=len(binary),
                    code=code if code is not None else "silent")
        return code, data

    def _fault(self, service: str, api: int) -> dict[str, Any] | None:
        with self.lock:
            for fault in self.faults:
                if fault.get("service") == service and fault.get("api", api) == api:
                    fault["times"] = fault.get("times", 1) - 1
                    if fault["times"] <= 0:
                        self.faults.remove(fault)
                    return fault
        return None

    def _serve(self, service: str, api: int, p: Any) -> tuple[int, str]:
        """(vendor code, JSON data) for one request; an unknown service: 3203 (the SDK's 'no api')."""
        handler = {"sport": self._sport, "loco": self._sport, "arm": self._arm, "voice": self._voice,
                   "slam_operate": self._slam}.get(service)
        return handler(api, p, time.monotonic()) if handler else (3203, "")

    def _sport(self, api: int, p: Any, now: float) -> tuple[int, str]:
        if api == 7105:
            vx, vy, w = p["velocity"]
            with self.lock:
                self.velocity, self.velocity_until = (vx, vy, w), now + float(p["duration"])
        return 0, ""

    def _arm(self, api: int, p: Any, now: float) -> tuple[int, str]:
        if api == 7107:
            return 0, json.dumps(sorted(KNOWN_ACTIONS))
        action = int(p["data"])
        with self.lock:
            if action not in KNOWN_ACTIONS:
                return 7402, ""
            if now < self.action_until:
                return 7400, ""
            if self.holding is not None and action != 99:
                return 7401, ""
            self.holding = action if action in HOLDING_ACTIONS else None
            self.action_until = now + ACTION_SECONDS
        return 0, ""

    def _voice(self, api: int, p: Any, now: float) -> tuple[int, str]:
        return (0, json.dumps({"volume": 80})) if api == 1005 else (0, "")

    def _slam(self, api: int, p: Any, now: float) -> tuple[int, str]:
        data = p.get("data", {}) if isinstance(p, dict) else {}
        with self.lock:
            if api == 1804:
                if str(data.get("address", "")).endswith("missing.pcd"):
                    return 507, ""
                self.x, self.y = float(data.get("x", 0.0)), float(data.get("y", 0.0))
                self.yaw = 2.0 * math.atan2(float(data.get("q_z", 0.0)), float(data.get("q_w", 1.0)))
                self.localised = True
            elif api == 1102:
                pose = data["targetPose"]
                yaw = 2.0 * math.atan2(float(pose["q_z"]), float(pose["q_w"]))
                self.goal = (float(pose["x"]), float(pose["y"]), yaw)
                self.paused = False
            elif api in (1201, 1202):
                self.paused = api == 1201
            elif api == 1901:
                self.goal = None
        return 0, ""

    # -- the body -------------------------------------------------------------------------------
    def step(self, dt: float) -> None:
        now = time.monotonic()
        with self.lock:
            if now < self.velocity_until:
                vx, vy, w = self.velocity
                c, s = math.cos(self.yaw), math.sin(self.yaw)
                self.x += (vx * c - vy * s) * dt
                self.y += (vx * s + vy * c) * dt
                self.yaw = math.atan2(math.sin(self.yaw + w * dt), math.cos(self.yaw + w * dt))
            if self.goal is not None and not self.paused:
                gx, gy, gyaw = self.goal
                d = math.hypot(gx - self.x, gy - self.y)
                step = self.nav_speed * dt
                if d <= step:
                    self.x, self.y, self.yaw = gx, gy, gyaw
                    self.goal = None
                    self.arrivals.append(self.arrive)
                else:
                    self.x += (gx - self.x) / d * step
                    self.y += (gy - self.y) / d * step
                    self.yaw = math.atan2(gy - self.y, gx - self.x)

    def on_arm(self, msg: LowCmd_) -> None:
        crc_ok = self.crc.Crc(msg) == msg.crc
        q = {i: round(msg.motor_cmd[i].q, 5) for i in range(12, 29)}
        kp = {i: round(msg.motor_cmd[i].kp, 3) for i in range(12, 29)}
        self.record(kind="topic", topic="rt/arm_sdk", weight=round(msg.motor_cmd[WEIGHT_MOTOR].q, 5), crc_ok=crc_ok,
                    q=q, kp=kp)

    def on_hand(self, side: str, msg: HandCmd_) -> None:
        self.record(kind="topic", topic=f"rt/dex3/{side}/cmd", q=[round(m.q, 5) for m in msg.motor_cmd])


class FakeService(ServerBase):
    """One vendor service on the SDK's server base: it sees whole requests (the binary part of
    PlayStream too) and may stay silent, which the SDK's ``Server`` cannot."""

    def __init__(self, name: str, robot: Robot) -> None:
        super().__init__(name)
        self.robot = robot
        self._SetServerRequestHandler(self._handle)

    def _handle(self, request: Any) -> None:
        identity = request.header.identity
        if identity.api_id == 1:  # the SDK's api-version request: the daemons' start-up probe
            fault = self.robot._fault(self.GetName(), 1)
            if fault is not None and fault.get("silent"):
                return
            code, data = 0, VERSIONS[self.GetName()]
        else:
            code, data = self.robot.answer(self.GetName(), identity.api_id, request.parameter, list(request.binary))
        if code is None or request.header.policy.noreply:
            return
        self._SendResponse(Response_(ResponseHeader_(identity, ResponseStatus_(code)), data if code == 0 else "", []))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--domain", type=int, required=True)
    parser.add_argument("--interface", default="lo")
    parser.add_argument("--nav-speed", type=float, default=4.0, help="m/s the fake walks a navigation goal")
    parser.add_argument("--silent", default="", help="comma-separated services that never answer")
    args = parser.parse_args(argv)
    _die_with_parent()
    out = sys.stdout
    sys.stdout = sys.stderr  # the SDK prints; keep stdout for records
    robot = Robot(args.nav_speed, out)
    silent = set(filter(None, args.silent.split(",")))
    for service in silent:
        robot.faults.append({"service": service, "silent": True, "times": 10**9})
    # first, before anything can hang: the end of the test's input ends the fake, whatever it is doing
    threading.Thread(target=_control, args=(sys.stdin, robot), daemon=True).start()
    join_dds(args.domain, args.interface)
    _start_services(robot)
    odom, key_info = _start_topics(robot)
    unanswered = _probe(sorted(set(VERSIONS) - silent))
    if unanswered:
        print(f"fake robot: services {unanswered} did not answer their own probe within {PROBE_SECONDS:g} s",
              file=sys.stderr)
        os._exit(3)
    robot.record(kind="ready")
    _run(robot, odom, key_info)
    return 0


def _die_with_parent() -> None:
    """SIGKILL this fake when the process that started it dies, however it dies."""
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
    if os.getppid() == 1:  # the parent was already gone before the request took effect
        os._exit(0)


def _start_services(robot: Robot) -> None:
    """Start every service; each start sleeps half a second after creating its channels, so they
    start on threads side by side (their channel creation is serialised, see _DDS_CREATION)."""
    _side_by_side(lambda name: FakeService(name, robot)._Start(False), list(VERSIONS))


def _side_by_side(start: Any, names: list[str]) -> None:
    """``start(name)`` for every name, each on its own thread, and wait for all of them."""
    threads = [threading.Thread(target=start, args=(name,)) for name in names]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()


def _start_topics(robot: Robot) -> tuple[ChannelPublisher, ChannelPublisher]:
    odom = ChannelPublisher("rt/unitree/slam_relocation/odom", Odometry_)
    odom.Init()
    key_info = ChannelPublisher("rt/slam_key_info", String_)
    key_info.Init()
    robot.subscribers = [ChannelSubscriber("rt/arm_sdk", LowCmd_)]
    robot.subscribers[0].Init(robot.on_arm, 10)
    for side in ("left", "right"):
        sub = ChannelSubscriber(f"rt/dex3/{side}/cmd", HandCmd_)
        sub.Init(lambda msg, side=side: robot.on_hand(side, msg), 10)
        robot.subscribers.append(sub)
    return odom, key_info


def _probe(services: list[str]) -> list[str]:
    """Ask each service for its api version, as the daemons do, until each has answered; the
    ones that never did. "Ready" then means answering, not only started."""
    clients: dict[str, Client] = {}
    _side_by_side(lambda name: clients.__setitem__(name, Client(name)), services)  # each sleeps 0.5 s
    deadline = time.monotonic() + PROBE_SECONDS
    waiting = list(services)
    for client in clients.values():
        client.SetTimeout(0.5)
    while waiting and time.monotonic() < deadline:
        waiting = [name for name in waiting if clients[name].GetServerApiVersion()[0] != 0]
    return waiting


def _run(robot: Robot, odom: ChannelPublisher, key_info: ChannelPublisher) -> None:
    period, last_odom = 0.01, 0.0
    while True:
        time.sleep(period)
        robot.step(period)
        now = time.monotonic()
        if robot.localised and now - last_odom >= 0.05:
            last_odom = now
            odom.Write(_odometry(robot))
        while robot.arrivals:
            arrived = robot.arrivals.pop(0)
            msg = std_msgs_msg_dds__String_()
            msg.data = json.dumps({"type": "task_result", "data": {"is_arrived": arrived}})
            key_info.Write(msg)


def _odometry(robot: Robot) -> Odometry_:
    msg = nav_msgs_msg_dds__Odometry_()
    with robot.lock:
        msg.pose.pose.position.x, msg.pose.pose.position.y = robot.x, robot.y
        msg.pose.pose.orientation.z, msg.pose.pose.orientation.w = math.sin(robot.yaw / 2), math.cos(robot.yaw / 2)
    msg.header.frame_id = "map"
    return msg


def _control(stream: Any, robot: Robot) -> None:
    for line in stream:
        try:
            order = json.loads(line)
        except ValueError:
            continue
        if "ping" in order:  # every request the fake answered before this is already recorded
            robot.record(kind="pong", n=order["ping"])
        with robot.lock:
            if "fault" in order:
                robot.faults.append(dict(order["fault"]))
            if "arrive" in order:
                robot.arrive = bool(order["arrive"])
    os._exit(0)  # the test went away: so does the fake robot


if __name__ == "__main__":
    sys.exit(main())
