"""Simulated locomotion: plan on the lab's occupancy map, let the world's path follower walk it.

The split mirrors the robot: the daemon plans a global path (A* on the saved map, smoothed to a
few straight legs) and hands it to the world's navigation service, which follows it under the
vendor controller's limits (including its ~0.3 m/s dead band) and stops for a person in the way.
The daemon watches the world's state: arrival ends the walk, a block that lasts longer than
``blocked_timeout`` sim seconds fails it with ``blocked``, stop and cancel brake at once.

Options: ``world`` (socket path, required), ``map`` (map YAML, default the lab's),
``robot_radius`` (0.3 m), ``relative_clearance`` (0.15 m: margin for body-relative moves, which
are driven straight without a global plan, like the robot's odometry moves, and for docking),
``max_speed`` (0.6 m/s), ``blocked_timeout`` (20 s), ``poll`` (0.1 s), ``approach_slack`` (0.1 m:
how much further than asked an approach may stand when furniture blocks every closer spot),
``view_range`` (2.0 m: the farthest the head camera is trusted to see an object from).

A goal it cannot reach fails ``unreachable`` before the base moves, with data saying which kind
of goal it was and the names of the furniture in the way (the map's furniture file), so the
robot can say "the kitchen table is in the way" instead of coordinates.
"""

from __future__ import annotations

import contextlib
import math
from importlib import resources
from typing import Any

from stuart_bt.core.clock import Clock
from stuart_bt.core.world import Pose
from stuart_bt.daemon.backend import Activity, DaemonError, Done, Progress
from stuart_bt.maps.files import read_map
from stuart_bt.maps.furniture import furniture_for_map, ranked
from stuart_bt.maps.grid import Grid
from stuart_bt.maps.paths import PlanningError, path_length, plan
from stuart_bt.maps.viewpoints import CameraView, NoViewpoint, StandingMap, find_viewpoint
from stuart_bt.sim.world.client import WorldClient, WorldError

from .backend import (
    ApproachGoal,
    LocoBackend,
    MapGoal,
    NavigateGoal,
    RelativeGoal,
    ViewGoal,
    approach_stand,
    goal_pose,
    standoff_on_line,
    unreachable_data,
)
from .dry import wrap


def default_map() -> str:
    return str(resources.files("stuart_bt.sim") / "maps" / "lab.yaml")


class SimWalk(Activity):
    """One base_path command followed to arrival, block timeout, stop or cancel."""

    resource = "motion"
    report_every = 0.5

    def __init__(self, backend: SimLoco, waypoints: list[tuple[float, float]], final_yaw: float | None,
                 goal: NavigateGoal | None) -> None:
        self.backend = backend
        self.waypoints = waypoints
        self.final_yaw = final_yaw
        self.goal = goal
        self.start_pose = backend.pose()
        self._next_poll = 0.0
        self._next_report = 0.0
        self._blocked_since: float | None = None

    def start(self, now: float) -> dict[str, Any]:
        goal = self.goal
        self.backend.call("base_path", waypoints=[list(p) for p in self.waypoints], final_yaw=self.final_yaw,
                          max_speed=self.backend.max_speed,
                          tolerance=goal.tolerance if goal else 0.10,
                          yaw_tolerance=goal.yaw_tolerance if goal else 0.0873)
        self._next_poll = now + self.backend.poll_period
        self._next_report = now + self.report_every
        return {"waypoints": [[round(x, 3), round(y, 3)] for x, y in self.waypoints],
                "length": round(path_length(self.waypoints), 3)}

    def next_due(self) -> float:
        return self._next_poll

    def poll(self, now: float) -> Progress | Done | None:
        if now < self._next_poll:
            return None
        self._next_poll = now + self.backend.poll_period
        state = self.backend.refresh()
        status = state.get("base_status")
        pose = self.backend.pose()
        if status == "arrived":
            return Done({"pose": pose.to_dict(), "marker": self.goal.marker if self.goal else None,
                         "distance": round(path_length(self.waypoints), 3),
                         "error": state.get("arrival_error")})
        if status == "blocked":
            if self._blocked_since is None:
                self._blocked_since = now
            elif now - self._blocked_since > self.backend.blocked_timeout:
                self.backend.call("base_stop")
                raise DaemonError("blocked", f"the path stayed blocked for {self.backend.blocked_timeout:g} s; "
                                  "stopped", data={"pose": pose.to_dict()})
        else:
            self._blocked_since = None
        if now >= self._next_report:
            self._next_report = now + self.report_every
            return Progress({"pose": pose.to_dict(), "status": status})
        return None

    def cancel(self, now: float) -> dict[str, Any]:
        self.backend.call("base_stop")
        return {"pose": self.backend.pose().to_dict()}


class SimLoco(LocoBackend):
    name = "sim"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        if "world" not in options:
            raise ValueError("the sim loco backend needs the world's socket path (option 'world')")
        self.world = WorldClient(options["world"])
        map_file = options.get("map") or default_map()
        occupancy = read_map(map_file, float(options.get("robot_radius", 0.3)))
        self.grid = occupancy.planning_grid()
        # body-relative moves are odometry moves (no global plan), checked against a thinner margin
        self.near_grid = occupancy.planning_grid(float(options.get("relative_clearance", 0.15)))
        self.space = StandingMap(Grid(occupancy.occupied, occupancy.resolution, occupancy.origin), self.grid,
                                 self.near_grid, furniture=furniture_for_map(map_file))
        self.view_range = float(options.get("view_range", 2.0))
        self.max_speed = float(options.get("max_speed", 0.6))
        self.blocked_timeout = float(options.get("blocked_timeout", 20.0))
        self.approach_slack = float(options.get("approach_slack", 0.10))
        self.poll_period = float(options.get("poll", 0.1))
        self._state: dict[str, Any] = {}
        self.refresh()

    def call(self, cmd: str, **args: Any) -> dict[str, Any]:
        try:
            return self.world.call(cmd, **args)
        except WorldError as e:
            raise DaemonError("backend_error", f"world {cmd}: {e}") from None

    def refresh(self) -> dict[str, Any]:
        self._state = self.call("state")
        return self._state

    def pose(self) -> Pose:
        return Pose.from_dict(self._state.get("base", {}))

    def navigate(self, goal: NavigateGoal) -> Activity:
        start = Pose.from_dict(self.refresh()["base"])
        gx, gy, gyaw = goal_pose(start, goal.target)
        if math.hypot(gx - start.x, gy - start.y) <= goal.tolerance:
            waypoints = [(start.x, start.y)]
        elif isinstance(goal.target, RelativeGoal):
            hit = self.near_grid.first_blocked((start.x, start.y), (gx, gy))
            if hit is not None:
                raise DaemonError("unreachable", f"moving by ({goal.target.dx:g}, {goal.target.dy:g}) m would hit "
                                  "an obstacle", data=unreachable_data("relative", gx, gy, self._named_near(*hit)))
            waypoints = [(start.x, start.y), (gx, gy)]
        else:
            try:
                waypoints = self._plan_with_final_approach(start, gx, gy)
            except PlanningError as e:
                where = f" ({goal.marker})" if goal.marker else ""
                raise DaemonError("unreachable", f"cannot plan to ({gx:.2f}, {gy:.2f}){where}: {e}",
                                  data=unreachable_data("pose", gx, gy, self._named_near(gx, gy),
                                                        marker=goal.marker)) from None
        return SimWalk(self, waypoints, None if gyaw is None else wrap(gyaw), goal)

    def _plan_with_final_approach(self, start: Pose, gx: float, gy: float) -> list[tuple[float, float]]:
        """A* to the goal; a goal closer to furniture than the planning margin (standing at a
        table to pick) is reached by planning to the nearest roomy spot and then a short straight
        final approach checked against the thinner margin, as a robot docks."""
        try:
            return plan(self.grid, (start.x, start.y), (gx, gy), snap=0.0)
        except PlanningError:
            if not self.near_grid.cell_is_free(*self.near_grid.world_to_cell(gx, gy)):
                raise
        waypoints = plan(self.grid, (start.x, start.y), (gx, gy))  # snaps the goal onto free space
        free = self.grid.nearest_free(*self.grid.world_to_cell(gx, gy), int(0.3 / self.grid.resolution))
        if free is None:
            raise PlanningError(f"({gx:.2f}, {gy:.2f}) has no free space within 0.3 m")
        snapped = self.grid.cell_to_world(*free)
        if not self.near_grid.segment_free(snapped, (gx, gy)):
            raise PlanningError(f"({gx:.2f}, {gy:.2f}) is too close to an obstacle to approach")
        return [*waypoints[:-1], snapped, (gx, gy)]

    def approach_pose(self, goal: ApproachGoal) -> MapGoal:
        """A free spot to stand at for an approach, that the robot can walk to.

        Furniture decides the side: headings are tried from the one looking straight from the
        robot at the point, then further round it, alternating sides, in 15 degree steps; at each,
        the point in front of the asked shoulder first, then of the other one. A spot must leave the
        docking clearance free and have a plan from here. Only when every heading is blocked does
        the stand-off grow, in 5 cm steps up to ``approach_slack`` metres, before the approach fails."""
        start = Pose.from_dict(self.refresh()["base"])
        facing = standoff_on_line(start, goal).yaw
        assert facing is not None  # a stand-off always faces its point
        headings = [facing + math.radians(15.0 * k * sign) for k in range(13) for sign in ((1,) if k == 0 else (1, -1))]
        sides = (goal.lateral, -goal.lateral) if goal.lateral else (0.0,)
        extra = 0.0
        in_the_way: list[str | None] = []
        while extra <= self.approach_slack + 1e-9:
            wider = ApproachGoal(goal.x, goal.y, goal.standoff + extra, goal.lateral)
            for heading in headings:
                for side in sides:
                    spot = approach_stand(wider, heading, side)
                    if not self.near_grid.cell_is_free(*self.near_grid.world_to_cell(spot.x, spot.y)):
                        in_the_way.append(self._name_near(spot.x, spot.y))
                        continue
                    try:
                        self._plan_with_final_approach(start, spot.x, spot.y)
                    except PlanningError:
                        in_the_way.append(self._name_near(spot.x, spot.y))
                        continue
                    return MapGoal(spot.x, spot.y, wrap(heading))
            extra += 0.05
        within = goal.standoff + self.approach_slack
        raise DaemonError("unreachable", f"no free spot to stand within {within:.2f} m "
                          f"of ({goal.x:.2f}, {goal.y:.2f})",
                          data=unreachable_data("reach", goal.x, goal.y, ranked(in_the_way), within=within))

    def view_pose(self, goal: ViewGoal) -> MapGoal:
        """A spot the robot can walk to from which the head camera sees the point with nothing
        on the map in between, nearest on foot (:func:`stuart_bt.maps.viewpoints.find_viewpoint`);
        here, or a turn in place, when that already sees it."""
        start = Pose.from_dict(self.refresh()["base"])
        try:
            spot = find_viewpoint(self.space, self.camera, (goal.x, goal.y, goal.z), (start.x, start.y, start.yaw))
        except NoViewpoint as e:
            raise DaemonError("unreachable", e.reason, data=unreachable_data(
                "view", goal.x, goal.y, e.blocked_by, z=goal.z, spots=e.counts)) from None
        return MapGoal(spot.x, spot.y, wrap(spot.yaw))

    @property
    def camera(self) -> CameraView:
        from stuart_bt.perception.projection import head_camera_view

        return head_camera_view(far=self.view_range)

    def _name_near(self, x: float, y: float) -> str | None:
        """The named furniture whose margin a spot at (x, y) is in (the robot's radius and a cell)."""
        return self.space.name_at(x, y, self.space.dock + self.grid.resolution)

    def _named_near(self, x: float, y: float) -> list[str]:
        name = self._name_near(x, y)
        return [name] if name else []

    def turn(self, angle: float) -> Activity:
        start = Pose.from_dict(self.refresh()["base"])
        return SimWalk(self, [(start.x, start.y)], wrap(start.yaw + angle), None)

    def stop(self) -> None:
        self.call("base_stop")

    def state(self) -> dict[str, Any]:
        with contextlib.suppress(DaemonError):  # the heartbeat still goes out; the next command says why
            self.refresh()
        return {"pose": self.pose().to_dict(), "status": self._state.get("base_status")}

    def close(self) -> None:
        self.world.close()
