"""Locomotion on the G1 through the vendor SDK: the SLAM navigation service for map goals, the
walking controller's velocity command under closed-loop odometry for body-relative moves.

Map goals go to ``slam_operate`` (api 1102) as legs of at most ``max_leg`` metres, because the
service walks straight lines and refuses goals beyond 10 m: the route comes from A* on the saved
occupancy map when one is given (``nav_map``), else the straight line is cut into equal legs. A
leg is done when the service raises ``is_arrived`` on ``rt/slam_key_info`` *and* the relocation
odometry puts the robot within ``arrival_tolerance`` of it; a false flag fails the walk.

Body-relative moves and turns stream ``SetVelocity`` (api 7105) every ``control_period`` with a
duration of ``command_duration``: the robot stops by itself unless the daemon keeps talking, so a
hung or killed daemon means a stopped robot. Speeds stay between the controller's dead band
(``min_speed``, ~0.3 m/s: below it the G1 does not step) and the configured limits.

Options (besides the link settings in :mod:`stuart_bt.skills.vendor`): ``start_pose`` (from the
run: the relocalisation's initial pose), ``map`` (the robot's .pcd map: relocalise on it at
start-up), ``nav_map`` (occupancy map YAML for waypoints), ``robot_radius`` (0.3 m), ``max_leg``
(10 m), ``max_speed`` (0.5 m/s), ``min_speed`` (0.3 m/s), ``max_lateral_speed`` (0.3 m/s),
``max_turn_rate`` (0.6 rad/s), ``min_turn_rate`` (0.25 rad/s), ``control_period`` (0.05 s),
``command_duration`` (0.3 s), ``odom_timeout`` (1.0 s), ``arrival_tolerance`` (0.5 m),
``leg_timeout`` (60 s), ``stand_up`` (false: send Start FSM 500/200 at start-up), ``slam``
(true: require the navigation service).
"""

from __future__ import annotations

import json
import math
import threading
import time
from itertools import pairwise
from typing import Any

from unitree_sdk2py.g1.loco.g1_loco_client import LocoClient
from unitree_sdk2py.idl.nav_msgs.msg.dds_ import Odometry_
from unitree_sdk2py.idl.std_msgs.msg.dds_ import String_
from unitree_sdk2py.rpc.client import Client

from stuart_bt.core.clock import Clock
from stuart_bt.core.world import Pose
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, DaemonError, Done, Handler, Progress
from stuart_bt.maps.furniture import Furniture, FurnitureFileError, furniture_for_map
from stuart_bt.skills import vendor

from .backend import LocoBackend, MapGoal, NavigateGoal, RelativeGoal, goal_pose, unreachable_data
from .dry import wrap

ODOM_TOPIC = "rt/unitree/slam_relocation/odom"
ARRIVAL_TOPIC = "rt/slam_key_info"
SLAM = "slam_operate"
SLAM_VERSION = "1.0.0.1"
API_START_MAPPING, API_END_MAPPING, API_RELOCALISE = 1801, 1802, 1804
API_NAVIGATE, API_PAUSE, API_RESUME, API_CLOSE = 1102, 1201, 1202, 1901
SLAM_APIS = (API_START_MAPPING, API_END_MAPPING, API_RELOCALISE, API_NAVIGATE, API_PAUSE, API_RESUME, API_CLOSE)
VELOCITY_GAIN = 1.0  # 1/s: speed asked per metre of remaining distance (then clamped)
TURN_GAIN = 1.5  # 1/s

OWN_OPTIONS = ("start_pose", "map", "nav_map", "robot_radius", "max_leg", "max_speed", "min_speed",
               "max_lateral_speed", "max_turn_rate", "min_turn_rate", "control_period", "command_duration",
               "odom_timeout", "arrival_tolerance", "leg_timeout", "stand_up", "slam")


def pose_payload(x: float, y: float, yaw: float) -> dict[str, float]:
    """A map pose as the SLAM service writes it: position and a yaw-only quaternion."""
    return {"x": round(x, 4), "y": round(y, 4), "z": 0.0, "q_x": 0.0, "q_y": 0.0,
            "q_z": round(math.sin(yaw / 2.0), 6), "q_w": round(math.cos(yaw / 2.0), 6)}


def split_legs(points: list[tuple[float, float]], max_leg: float) -> list[tuple[float, float]]:
    """The route's corners, with straight pieces longer than ``max_leg`` cut into equal legs
    (the first point, the start, is dropped: every returned point is a goal)."""
    goals: list[tuple[float, float]] = []
    for (x0, y0), (x1, y1) in pairwise(points):
        pieces = max(1, math.ceil(math.hypot(x1 - x0, y1 - y0) / max_leg - 1e-9))
        goals += [(x0 + (x1 - x0) * k / pieces, y0 + (y1 - y0) * k / pieces) for k in range(1, pieces + 1)]
    return goals


class MapWalk(Activity):
    """A map goal walked by the navigation service, leg by leg."""

    resource = "motion"
    report_every = 0.5

    def __init__(self, backend: UnitreeLoco, legs: list[tuple[float, float, float]], goal: NavigateGoal,
                 length: float) -> None:
        self.backend = backend
        self.legs = legs
        self.goal = goal
        self.length = length
        self.index = 0
        self.paused = False
        self._arrivals_seen = 0
        self._leg_deadline = 0.0
        self._next_report = 0.0

    def start(self, now: float) -> dict[str, Any]:
        self.backend.walk = self
        self._send_leg(now)
        self._next_report = now + self.report_every
        return {"legs": [[round(x, 3), round(y, 3)] for x, y, _ in self.legs], "length": round(self.length, 3)}

    def _send_leg(self, now: float) -> None:
        x, y, yaw = self.legs[self.index]
        self._arrivals_seen = self.backend.arrival_count()
        goal = {"data": {"targetPose": pose_payload(x, y, yaw), "mode": 1}}
        code, _ = self.backend.slam_service().request(API_NAVIGATE, goal)
        vendor.check(code, SLAM, f"navigate (leg {self.index + 1} of {len(self.legs)})",
                     data={"pose": self.backend.pose().to_dict()})
        self._leg_deadline = now + self.backend.leg_timeout

    def next_due(self) -> float:
        return self.backend.clock.now() + self.backend.control_period * self.backend.clock.factor

    def poll(self, now: float) -> Progress | Done | None:
        pose = self.backend.pose()
        arrival = self.backend.arrival_after(self._arrivals_seen)
        if arrival is not None and self.backend.odometry_caught_up(arrival[1]):
            flag = arrival[0]
            self._arrivals_seen += 1
            self._arrived(flag, pose)
            if self.index == len(self.legs) - 1:
                self.backend.walk = None
                return Done({"pose": pose.to_dict(), "marker": self.goal.marker, "distance": round(self.length, 3)})
            self.index += 1
            self._send_leg(now)
            return Progress({"pose": pose.to_dict(), "leg": self.index + 1, "legs": len(self.legs)})
        if not self.paused and now > self._leg_deadline:
            self.backend.halt()
            raise DaemonError("backend_error", f"leg {self.index + 1} of {len(self.legs)} did not arrive within "
                              f"{self.backend.leg_timeout:g} s; stopped", data={"pose": pose.to_dict()})
        if now >= self._next_report:
            self._next_report = now + self.report_every
            return Progress({"pose": pose.to_dict(), "leg": self.index + 1, "legs": len(self.legs),
                             "paused": self.paused})
        return None

    def _arrived(self, flag: bool, pose: Pose) -> None:
        """Check one arrival report against the odometry; failures stop the robot first."""
        x, y, _ = self.legs[self.index]
        off = math.hypot(pose.x - x, pose.y - y)
        where = f"leg {self.index + 1} of {len(self.legs)} to ({x:.2f}, {y:.2f})"
        if not flag:
            self.backend.halt()
            raise DaemonError("unreachable", f"the navigation service gave up on {where} (is_arrived false)",
                              data={"pose": pose.to_dict()})
        if off > max(self.backend.arrival_tolerance, self.goal.tolerance):
            self.backend.halt()
            raise DaemonError("backend_error", f"the navigation service reported arrival on {where}, but the "
                              f"odometry puts the robot {off:.2f} m away", data={"pose": pose.to_dict()})

    def set_paused(self, paused: bool, now: float) -> None:
        self.paused = paused
        if not paused:
            self._leg_deadline = now + self.backend.leg_timeout

    def cancel(self, now: float) -> dict[str, Any]:
        self.backend.walk = None
        self.backend.halt()
        return {"pose": self.backend.pose().to_dict()}


class OdometryMove(Activity):
    """A body-relative move or turn: velocity commands closed around the odometry.

    First the translation (body-frame velocity toward the target, heading held), then the turn;
    each command lasts ``command_duration`` so a silent daemon stops the robot."""

    resource = "motion"
    report_every = 0.5

    def __init__(self, backend: UnitreeLoco, goal: RelativeGoal | None, angle: float | None,
                 tolerance: float, yaw_tolerance: float, marker: str | None) -> None:
        self.backend = backend
        self.goal = goal
        self.angle = angle
        self.tolerance = tolerance
        self.yaw_tolerance = yaw_tolerance
        self.marker = marker
        self.start_pose = Pose()
        self.target = (0.0, 0.0)
        self.turn_left = 0.0  # radians still to turn (unwrapped: a turn may exceed pi)
        self.phase = "walk"
        self._last_yaw = 0.0
        self._next_report = 0.0

    def start(self, now: float) -> dict[str, Any]:
        self.start_pose = self.backend.fresh_pose("move")
        if self.goal is not None:
            gx, gy, _ = goal_pose(self.start_pose, self.goal)
            self.target = (gx, gy)
            self.turn_left = self.goal.dyaw
        else:
            self.target = (self.start_pose.x, self.start_pose.y)
            self.turn_left = self.angle or 0.0
        self._last_yaw = self.start_pose.yaw
        if math.hypot(self.target[0] - self.start_pose.x, self.target[1] - self.start_pose.y) <= self.tolerance:
            self.phase = "turn"
        self._next_report = now + self.report_every
        self.backend.walk = None
        return {"target": {"x": round(self.target[0], 4), "y": round(self.target[1], 4)},
                "turn": round(self.turn_left, 4)}

    def next_due(self) -> float:
        return self.backend.clock.now() + self.backend.control_period * self.backend.clock.factor

    def poll(self, now: float) -> Progress | Done | None:
        pose = self.backend.fresh_pose("move")
        self.turn_left -= wrap(pose.yaw - self._last_yaw)
        self._last_yaw = pose.yaw
        b = self.backend
        if self.phase == "walk":
            dx, dy = self.target[0] - pose.x, self.target[1] - pose.y
            distance = math.hypot(dx, dy)
            if distance <= self.tolerance:
                self.phase = "turn"
            else:
                c, s = math.cos(pose.yaw), math.sin(pose.yaw)
                bx, by = c * dx + s * dy, -s * dx + c * dy  # the remaining offset in the body frame
                speed = min(max(VELOCITY_GAIN * distance, b.min_speed), b.max_speed)
                vx, vy = bx / distance * speed, by / distance * speed
                if abs(vy) > b.max_lateral_speed:  # keep the direction, slow both
                    vx, vy = vx * b.max_lateral_speed / abs(vy), math.copysign(b.max_lateral_speed, vy)
                b.send_velocity(vx, vy, 0.0)
        if self.phase == "turn":
            if abs(self.turn_left) <= self.yaw_tolerance:
                b.halt()
                if self.angle is not None:
                    return Done({"pose": pose.to_dict(), "angle": self.angle, "distance": 0.0})
                return Done({"pose": pose.to_dict(), "marker": self.marker,
                             "distance": round(self.start_pose.distance_to(pose), 4)})
            rate = min(max(TURN_GAIN * abs(self.turn_left), b.min_turn_rate), b.max_turn_rate)
            b.send_velocity(0.0, 0.0, math.copysign(rate, self.turn_left))
        if now >= self._next_report:
            self._next_report = now + self.report_every
            return Progress({"pose": pose.to_dict(), "phase": self.phase})
        return None

    def cancel(self, now: float) -> dict[str, Any]:
        self.backend.halt()
        return {"pose": self.backend.pose().to_dict()}


class SlamCall(Activity):
    """One request to the SLAM service (mapping, relocalising, pause, resume), done at once."""

    resource = None

    def __init__(self, backend: UnitreeLoco, what: str, api: int, data: dict[str, Any],
                 result: dict[str, Any], error: str = "backend_error") -> None:
        self.backend, self.what, self.api, self.data, self.result, self.error = backend, what, api, data, result, error

    def start(self, now: float) -> None:
        code, _ = self.backend.slam_service().request(self.api, {"data": self.data})
        vendor.check(code, SLAM, self.what, self.error)

    def poll(self, now: float) -> Done:
        return Done(self.result)

    def cancel(self, now: float) -> None:
        return None


class PauseWalk(Activity):
    resource = None

    def __init__(self, backend: UnitreeLoco, pause: bool) -> None:
        self.backend, self.pause = backend, pause

    def start(self, now: float) -> None:
        walk = self.backend.walk
        if walk is None:
            raise DaemonError("not_found", f"no navigation is running to {'pause' if self.pause else 'resume'}")
        code, _ = self.backend.slam_service().request(API_PAUSE if self.pause else API_RESUME, {"data": {}})
        vendor.check(code, SLAM, "pause" if self.pause else "resume")
        if self.pause:
            self.backend.loco.StopMove()
        walk.set_paused(self.pause, now)

    def poll(self, now: float) -> Done:
        return Done({"paused": self.pause})

    def cancel(self, now: float) -> None:
        return None


class UnitreeLoco(LocoBackend):
    name = "unitree"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        self.link = vendor.link_from(options, "loco", OWN_OPTIONS)
        where = "loco unitree options"

        def num(key: str, default: float, minimum: float = 0.0) -> float:
            return vendor.startup_option(lambda: a.number(options, key, where, default=default, minimum=minimum))

        self.max_leg = num("max_leg", 10.0, 0.5)
        self.max_speed, self.min_speed = num("max_speed", 0.5, 0.05), num("min_speed", 0.3, 0.0)
        self.max_lateral_speed = num("max_lateral_speed", 0.3, 0.05)
        self.max_turn_rate, self.min_turn_rate = num("max_turn_rate", 0.6, 0.05), num("min_turn_rate", 0.25, 0.0)
        self.control_period = num("control_period", 0.05, 0.01)
        self.command_duration = num("command_duration", 0.3, 0.05)
        self.odom_timeout, self.arrival_tolerance = num("odom_timeout", 1.0, 0.05), num("arrival_tolerance", 0.5, 0.0)
        self.leg_timeout = num("leg_timeout", 60.0, 1.0)
        if not self.min_speed <= min(self.max_speed, self.max_lateral_speed) or self.min_turn_rate > self.max_turn_rate:
            raise vendor.StartupError(f"{where}: min_speed must not exceed max_speed or max_lateral_speed, nor "
                                      "min_turn_rate max_turn_rate (below the dead band the robot does not move)")
        self._start_pose = vendor.startup_option(lambda: a.pose(options, "start_pose", where)) \
            if "start_pose" in options else Pose()
        self.grid = None
        self.furniture = Furniture()
        if options.get("nav_map"):
            from stuart_bt.maps.files import read_map

            self.grid = read_map(str(options["nav_map"]), float(options.get("robot_radius", 0.3))).planning_grid()
            try:
                self.furniture = furniture_for_map(str(options["nav_map"]))
            except FurnitureFileError as e:
                raise vendor.StartupError(str(e)) from None
        self._pose: Pose | None = None
        self._pose_wall = 0.0
        self._arrivals: list[tuple[bool, float]] = []  # (is_arrived, wall time heard)
        self._lock = threading.Lock()
        self.walk: MapWalk | None = None
        self._last_command: tuple[float, float, float] = (0.0, 0.0, 0.0)

        vendor.connect(self.link)
        self.loco = vendor.ready_client(FirmwareLocoClient(self.link.loco_service), self.link.loco_service, self.link)
        self.slam: vendor.ServiceClient | None = None
        self._subscribers = [vendor.subscribe(ODOM_TOPIC, Odometry_, self._on_odometry),
                             vendor.subscribe(ARRIVAL_TOPIC, String_, self._on_key_info)]
        if options.get("slam", True):
            self.slam = vendor.ready_client(vendor.ServiceClient(SLAM, SLAM_VERSION, SLAM_APIS), SLAM, self.link)
        if options.get("stand_up"):
            code = self.loco.SetFsmId(self.link.start_fsm)
            if code != 0:
                raise vendor.StartupError(f"Start (FSM {self.link.start_fsm}) failed: vendor code {code} "
                                          f"({vendor.describe(code)}) from {self.link.loco_service} "
                                          f"on {self.link.where()}")
        if options.get("map"):
            self._relocalise_at_start(str(options["map"]))

    def slam_service(self) -> vendor.ServiceClient:
        """The SLAM navigation service; a clear error when the daemon runs without it."""
        if self.slam is None:
            raise DaemonError("backend_error", "map goals need the SLAM navigation service (option slam: true)")
        return self.slam

    def _relocalise_at_start(self, map_path: str) -> None:
        if self.slam is None:
            raise vendor.StartupError("loco unitree: relocalising on a map needs the SLAM service (slam: true)")
        p = self._start_pose
        code, _ = self.slam.request(API_RELOCALISE, {"data": {**pose_payload(p.x, p.y, p.yaw), "address": map_path}})
        if code != 0:
            raise vendor.StartupError(f"relocalising on {map_path} failed: vendor code {code} "
                                      f"({vendor.describe(code)}) from {SLAM} on {self.link.where()}")
        with self._lock:
            self._pose = None  # a sample from before the relocalisation is not where we are
        deadline = time.monotonic() + self.odom_timeout  # READY with a pose, when the robot gives one
        while self._pose is None and time.monotonic() < deadline:
            time.sleep(0.01)

    # -- topics (DDS threads) -------------------------------------------------------------------
    def _on_odometry(self, msg: Odometry_) -> None:
        q = msg.pose.pose.orientation
        yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
        pose = Pose(float(msg.pose.pose.position.x), float(msg.pose.pose.position.y), yaw)
        with self._lock:
            self._pose, self._pose_wall = pose, time.monotonic()

    def _on_key_info(self, msg: String_) -> None:
        try:
            info = json.loads(msg.data)
        except ValueError:
            return
        if isinstance(info, dict) and info.get("type") == "task_result":
            with self._lock:
                self._arrivals.append((bool(info.get("data", {}).get("is_arrived")), time.monotonic()))

    def arrival_count(self) -> int:
        with self._lock:
            return len(self._arrivals)

    def odometry_caught_up(self, heard: float) -> bool:
        """An odometry sample newer than ``heard`` came in (or waiting longer would not help), so
        an arrival flag is judged against where the robot really stopped."""
        with self._lock:
            return self._pose_wall > heard or time.monotonic() - heard > self.odom_timeout

    def arrival_after(self, seen: int) -> tuple[bool, float] | None:
        """The first arrival report after ``seen`` earlier ones, if any."""
        with self._lock:
            return self._arrivals[seen] if len(self._arrivals) > seen else None

    # -- motion ----------------------------------------------------------------------------------
    def pose(self) -> Pose:
        with self._lock:
            return self._pose if self._pose is not None else self._start_pose

    def odometry_problem(self, what: str) -> str | None:
        """Why the odometry cannot be trusted to ``what`` (missing or stale), or None."""
        with self._lock:
            pose, age = self._pose, time.monotonic() - self._pose_wall
        if pose is None:
            return (f"cannot {what}: no odometry on {ODOM_TOPIC} yet (relocalise first: "
                    "stuart-bt map relocalise, or the loco 'map' option)")
        if age > self.odom_timeout:
            return f"cannot {what}: the odometry on {ODOM_TOPIC} is {age:.1f} s old"
        return None

    def fresh_pose(self, what: str) -> Pose:
        """The odometry pose, or a stop and an error when it is missing or stale."""
        problem = self.odometry_problem(what)
        if problem is not None:
            self.halt()
            raise DaemonError("backend_error", f"{problem}; stopped", data={"pose": self.pose().to_dict()})
        return self.pose()

    def send_velocity(self, vx: float, vy: float, omega: float) -> None:
        vendor.check(self.loco.SetVelocity(round(vx, 4), round(vy, 4), round(omega, 4), self.command_duration),
                     self.link.loco_service, "SetVelocity", data={"pose": self.pose().to_dict()})
        self._last_command = (vx, vy, omega)

    def halt(self) -> None:
        """Stop walking now: pause a running navigation and command zero velocity."""
        if self.walk is not None and self.slam is not None:
            self.slam.request(API_PAUSE, {"data": {}})
        self.loco.StopMove()
        self._last_command = (0.0, 0.0, 0.0)

    def navigate(self, goal: NavigateGoal) -> Activity:
        if isinstance(goal.target, RelativeGoal):
            return OdometryMove(self, goal.target, None, goal.tolerance, goal.yaw_tolerance, goal.marker)
        if self.slam is None:
            raise DaemonError("backend_error", "map goals need the SLAM navigation service (option slam: true)")
        return self._map_walk(goal)

    def _map_walk(self, goal: NavigateGoal) -> MapWalk:
        assert isinstance(goal.target, MapGoal)
        problem = self.odometry_problem("navigate")
        if problem is not None:
            raise DaemonError("backend_error", problem, data={"pose": self.pose().to_dict()})
        start = self.pose()
        gx, gy, gyaw = goal_pose(start, goal.target)
        route = [(start.x, start.y), (gx, gy)]
        if self.grid is not None:
            from stuart_bt.maps.paths import PlanningError, plan

            try:
                route = plan(self.grid, (start.x, start.y), (gx, gy))
            except PlanningError as e:
                where = f" ({goal.marker})" if goal.marker else ""
                named = self.furniture.at(gx, gy, within=0.35)  # the goal is in (or at) furniture
                raise DaemonError("unreachable", f"cannot plan to ({gx:.2f}, {gy:.2f}){where}: {e}",
                                  data=unreachable_data("pose", gx, gy, [named] if named else [],
                                                        marker=goal.marker)) from None
        points = split_legs(route, self.max_leg)
        legs: list[tuple[float, float, float]] = []
        previous = (start.x, start.y)
        for i, (x, y) in enumerate(points):
            heading = math.atan2(y - previous[1], x - previous[0]) if (x, y) != previous else start.yaw
            yaw = gyaw if i == len(points) - 1 and gyaw is not None else heading
            legs.append((x, y, wrap(yaw)))
            previous = (x, y)
        length = sum(math.hypot(b[0] - a_[0], b[1] - a_[1]) for a_, b in pairwise(route))
        return MapWalk(self, legs, goal, length)

    def turn(self, angle: float) -> Activity:
        return OdometryMove(self, None, angle, 0.0, 0.0873, None)

    def stop(self) -> None:
        self.halt()

    def state(self) -> dict[str, Any]:
        moving = self.walk is not None or any(self._last_command)
        return {"pose": self.pose().to_dict(), "moving": moving}

    # -- SLAM commands ---------------------------------------------------------------------------
    def commands(self) -> dict[str, Handler]:
        return {**super().commands(), "pause": lambda args: self._pause(args, True),
                "resume": lambda args: self._pause(args, False), "map_start": self._map_start,
                "map_save": self._map_save, "relocalise": self._relocalise, "slam_close": self._slam_close}

    def _need_slam(self, cmd: str) -> None:
        if self.slam is None:
            raise DaemonError("backend_error", f"{cmd} needs the SLAM service (option slam: true)")

    def _pause(self, args: dict[str, Any], pause: bool) -> Activity:
        a.only_known(args, (), "pause" if pause else "resume")
        self._need_slam("pause")
        return PauseWalk(self, pause)

    def _map_start(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, (), "map_start")
        self._need_slam("map_start")
        return SlamCall(self, "start mapping", API_START_MAPPING, {"slam_type": "indoor"}, {"mapping": True})

    def _map_save(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("path",), "map_save")
        path = _pcd_path(args, "map_save")
        self._need_slam("map_save")
        return SlamCall(self, "end mapping and save", API_END_MAPPING, {"address": path}, {"saved": path})

    def _relocalise(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("path", "pose"), "relocalise")
        path = _pcd_path(args, "relocalise")
        p = a.pose(args, "pose", "relocalise") if "pose" in args else self.pose()
        self._need_slam("relocalise")
        return SlamCall(self, f"relocalise on {path}", API_RELOCALISE,
                        {**pose_payload(p.x, p.y, p.yaw), "address": path}, {"map": path, "pose": p.to_dict()})

    def _slam_close(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, (), "slam_close")
        self._need_slam("slam_close")
        return SlamCall(self, "close", API_CLOSE, {}, {"closed": True})


def _pcd_path(args: dict[str, Any], cmd: str) -> str:
    path = a.string(args, "path", cmd).strip()
    if not path.endswith(".pcd") or not path.startswith("/"):
        raise a.bad(cmd, f"'path' must be an absolute .pcd path on the robot, got {path!r}")
    return path


class FirmwareLocoClient(LocoClient):
    """The SDK's LocoClient on the service name the firmware uses ("sport" now, "loco" on older
    firmware; the SDK fixes it to "sport")."""

    def __init__(self, service: str) -> None:
        Client.__init__(self, service, False)
        self.first_shake_hand_stage_ = -1
