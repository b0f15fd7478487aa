"""The robot's base as the vendor walking controller and navigation service present it.

The G1's walking controller takes a body-frame velocity, ramps to it under acceleration limits,
ignores linear commands slower than ~0.3 m/s (its dead band: the reason the thesis's Nav2 setup
stalled near goals) and stops when commands stop arriving. :class:`BaseController` models that,
and :class:`PathFollower` plays the robot's navigation service on top of it: turn toward the
path, pure pursuit along it at a speed the dead band allows, brake from full speed at exactly
the distance the deceleration limit needs, then turn in place to the final heading. It stops
for a person in the way and goes on by itself once they have left.

Everything here is plain 2-D kinematics (REP-103: x forward, y left, yaw CCW), stepped by the
world server once per physics step; it knows nothing about MuJoCo.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from itertools import pairwise

Point = tuple[float, float]


def wrap(angle: float) -> float:
    """An angle in (-pi, pi]."""
    return math.atan2(math.sin(angle), math.cos(angle))


@dataclass(frozen=True)
class BaseLimits:
    max_speed: float = 0.8  # m/s, linear
    max_yaw_rate: float = 1.0  # rad/s
    accel: float = 1.0  # m/s^2
    yaw_accel: float = 2.0  # rad/s^2
    dead_band: float = 0.3  # m/s: slower linear commands are ignored (treated as 0)


@dataclass(frozen=True)
class PersonCheck:
    """Where the person is this step, and where the robot's lidar is (both map frame)."""

    person: Point | None
    lidar: Point
    person_radius: float = 0.25


STOP_DISTANCE = 0.8  # metres from the lidar to the person's surface that stops the base
CLEAR_DISTANCE = 0.95  # hysteresis: the person must be this far (or out of the way) to resume
CLEAR_HOLD = 0.5  # sim seconds the way must stay clear before moving again
CONE = math.radians(30.0)  # half-angle of the forward cone the lidar watches
PATH_HALF_WIDTH = 0.35  # the robot's half width: a person this close to the path ahead blocks it
LOOKAHEAD = 0.5  # pure-pursuit lookahead (m)
SHARP_CORNER = math.radians(30.0)  # corners sharper than this are taken by stopping and turning
ALIGN_DONE = 0.08  # rad: heading error at which the turn toward the path hands over to pursuit
REALIGN = math.radians(60.0)  # heading error during pursuit that makes it stop and turn again
MAX_RETRIES = 3  # approaches after a stop outside the tolerance


REVERSE_MAX = 0.6  # m: a leg this short that lies behind the robot is walked backwards
REVERSE_ANGLE = math.radians(120)  # "behind": the leg's direction this far from the heading
REVERSE_SPEED = 0.3  # m/s: stepping backwards, at the controller's dead band


class PathFollower:
    """The navigation service: one path, followed leg by leg.

    A *leg* is a stretch of the path without sharp corners. Each leg is driven as: turn in
    place toward it (``align``), pure pursuit at full speed (``track``), and a brake to a stop
    at its end. The speed command is always either >= the dead band or zero, never in between.
    A short leg behind the robot (stepping back from a table) is walked backwards at the dead
    band speed instead of turning around twice; the person check then looks backwards.
    """

    def __init__(self, start: Point, waypoints: Sequence[Point], final_yaw: float | None, max_speed: float,
                 tolerance: float, yaw_tolerance: float, limits: BaseLimits, dt: float) -> None:
        self.limits = limits
        self.max_speed = min(max(max_speed, limits.dead_band), limits.max_speed)
        self.tolerance = tolerance
        self.yaw_tolerance = yaw_tolerance
        self.final_yaw = None if final_yaw is None else wrap(final_yaw)
        self.dt = dt
        points = [start]
        for p in waypoints:
            if math.hypot(p[0] - points[-1][0], p[1] - points[-1][1]) > 0.05:
                points.append((float(p[0]), float(p[1])))
        if len(points) > 1 and math.hypot(waypoints[-1][0] - points[-1][0], waypoints[-1][1] - points[-1][1]) > 1e-9:
            points[-1] = (float(waypoints[-1][0]), float(waypoints[-1][1]))  # the goal is exact
        self.goal: Point = (float(waypoints[-1][0]), float(waypoints[-1][1])) if waypoints else start
        self.legs = _split_legs(points)
        self.leg = 0
        self.s = 0.0  # progress along the current leg
        self.phase = "align" if self.legs else "final_yaw"
        self.retries = 0
        self.reverse = False  # walking the current leg backwards
        self.blocked = False
        self._clear_since: float | None = None
        self._after_brake = "leg_end"  # what a brake leads to: the leg's end, or a new turn
        self.error: dict[str, float | None] | None = None

    # -- one control step -----------------------------------------------------------------

    def command(self, x: float, y: float, yaw: float, v: float, w: float, now: float,
                check: PersonCheck | None) -> tuple[float, float, bool]:
        """The (vx, wz) to command this step and whether the path is finished."""
        if self.phase == "done":
            return 0.0, 0.0, True
        if self.phase in ("align", "track") and self._update_block(x, y, yaw, now, check):
            return 0.0, 0.0, False
        if self.phase == "align":
            return self._align(x, y, yaw, w)
        if self.phase == "track":
            return self._track(x, y, yaw, v)
        if self.phase == "brake":
            if abs(v) < 1e-9:
                self._leg_finished(x, y)
            return 0.0, 0.0, False
        if self.phase == "final_yaw":
            return self._final_yaw(x, y, yaw, w)
        raise AssertionError(self.phase)

    def _align(self, x: float, y: float, yaw: float, w: float) -> tuple[float, float, bool]:
        leg = self.legs[self.leg]
        self.s = leg.project(x, y, self.s)
        tx, ty = leg.point_at(self.s + LOOKAHEAD)
        direction = math.atan2(ty - y, tx - x)
        if self.s == 0.0:  # decide once per leg, before moving along it
            self.reverse = leg.length <= REVERSE_MAX and abs(wrap(direction - yaw)) > REVERSE_ANGLE
        error = wrap(direction - self._facing(yaw))
        if abs(error) <= ALIGN_DONE:
            self.phase = "track"
            return 0.0, self._turn_rate(error), False
        return 0.0, self._turn_rate(error), False

    def _track(self, x: float, y: float, yaw: float, v: float) -> tuple[float, float, bool]:
        leg = self.legs[self.leg]
        self.s = leg.project(x, y, self.s)
        remaining = leg.length - self.s
        tx, ty = leg.point_at(self.s + LOOKAHEAD)
        dx, dy = tx - x, ty - y
        alpha = wrap(math.atan2(dy, dx) - self._facing(yaw))
        if abs(alpha) > REALIGN:  # far off the path's heading: stop and turn again
            self.phase = "brake"
            self._after_brake = "align"
            return 0.0, 0.0, False
        a = self.limits.accel
        if remaining <= v * v / (2.0 * a) + 0.5 * v * self.dt:
            self.phase = "brake"
            self._after_brake = "leg_end"
            return 0.0, 0.0, False
        curvature = 2.0 * math.sin(alpha) / max(math.hypot(dx, dy), 1e-3)
        w = curvature * max(v, self.limits.dead_band)  # the heading of travel turns by curvature x speed
        if self.reverse:
            return -max(REVERSE_SPEED, self.limits.dead_band), w, False
        return self.max_speed, w, False

    def _facing(self, yaw: float) -> float:
        """The direction of travel: the heading, or behind it while walking backwards."""
        return wrap(yaw + math.pi) if self.reverse else yaw

    def _final_yaw(self, x: float, y: float, yaw: float, w: float) -> tuple[float, float, bool]:
        if self.final_yaw is None:
            return self._arrive(x, y, yaw)
        error = wrap(self.final_yaw - yaw)
        settled = abs(w) <= 2.0 * self.limits.yaw_accel * self.dt
        if abs(error) <= 0.25 * self.yaw_tolerance and settled or abs(error) <= 0.002:
            return self._arrive(x, y, yaw)
        return 0.0, self._turn_rate(error), False

    def _turn_rate(self, error: float) -> float:
        """The yaw rate that brakes to zero exactly at zero error (no dead band on turning)."""
        rate = min(self.limits.max_yaw_rate, math.sqrt(2.0 * self.limits.yaw_accel * abs(error)))
        return math.copysign(rate, error)

    def _leg_finished(self, x: float, y: float) -> None:
        if self._after_brake == "align":
            self.phase = "align"
            return
        if self.leg + 1 < len(self.legs):
            self.leg += 1
            self.s = 0.0
            self.phase = "align"
            return
        miss = math.hypot(self.goal[0] - x, self.goal[1] - y)
        if miss > self.tolerance and self.retries < MAX_RETRIES:  # approach again from here
            self.retries += 1
            self.legs = [_Leg([(x, y), self.goal])]
            self.leg = 0
            self.s = 0.0
            self.phase = "align"
            return
        self.phase = "final_yaw"

    def _arrive(self, x: float, y: float, yaw: float) -> tuple[float, float, bool]:
        self.phase = "done"
        position = math.hypot(self.goal[0] - x, self.goal[1] - y)
        yaw_error = None if self.final_yaw is None else wrap(yaw - self.final_yaw)
        self.error = {"position": round(position, 4), "yaw": None if yaw_error is None else round(yaw_error, 5),
                      "within_tolerance": position <= self.tolerance
                      and (yaw_error is None or abs(yaw_error) <= self.yaw_tolerance)}
        return 0.0, 0.0, True

    # -- people ----------------------------------------------------------------------------

    def _update_block(self, x: float, y: float, yaw: float, now: float, check: PersonCheck | None) -> bool:
        limit = CLEAR_DISTANCE if self.blocked else STOP_DISTANCE
        in_way = check is not None and check.person is not None and self._in_way(x, y, yaw, check, limit)
        if in_way:
            self.blocked = True
            self._clear_since = None
            return True
        if self.blocked:
            if self._clear_since is None:
                self._clear_since = now
            if now - self._clear_since < CLEAR_HOLD:
                return True
            self.blocked = False
            self.phase = "align"  # resume: face the path again first
        return False

    def _in_way(self, x: float, y: float, yaw: float, check: PersonCheck, limit: float) -> bool:
        px, py = check.person  # type: ignore[misc]
        lx, ly = check.lidar
        dx, dy = px - lx, py - ly
        distance = math.hypot(dx, dy) - check.person_radius
        if distance > limit:
            return False
        leg = self.legs[self.leg]
        if self.phase == "align":  # the way it is about to go, not the way it faces
            tx, ty = leg.point_at(self.s + LOOKAHEAD)
            heading = math.atan2(ty - y, tx - x)
        else:
            heading = self._facing(yaw)  # backwards while walking backwards
        if abs(wrap(math.atan2(dy, dx) - heading)) <= CONE:
            return True
        # A person standing on the path ahead, even outside the cone.
        ahead = [leg.point_at(self.s + k * 0.1) for k in range(int((limit + 0.6) / 0.1) + 1)]
        return any(math.hypot(px - ax, py - ay) <= check.person_radius + PATH_HALF_WIDTH for ax, ay in ahead) \
            and (dx * math.cos(heading) + dy * math.sin(heading)) > 0.0


class _Leg:
    """A polyline with arc-length lookups; the point beyond its end continues straight on."""

    def __init__(self, points: list[Point]) -> None:
        self.points = points
        self.cumulative = [0.0]
        for a, b in pairwise(points):
            self.cumulative.append(self.cumulative[-1] + math.hypot(b[0] - a[0], b[1] - a[1]))
        self.length = self.cumulative[-1]

    def point_at(self, s: float) -> Point:
        pts, cum = self.points, self.cumulative
        if s <= 0.0:
            return pts[0]
        for i in range(len(pts) - 1):
            if s <= cum[i + 1] or i == len(pts) - 2:
                seg = cum[i + 1] - cum[i]
                t = (s - cum[i]) / seg if seg > 0 else 0.0
                return (pts[i][0] + (pts[i + 1][0] - pts[i][0]) * t, pts[i][1] + (pts[i + 1][1] - pts[i][1]) * t)
        return pts[-1]

    def project(self, x: float, y: float, s_hint: float) -> float:
        """Arc length of the closest point, never more than a little behind ``s_hint``
        (progress is monotonic, so a path that doubles back cannot snap backwards). Past the
        end it keeps counting along the last segment's direction, so an overshoot shows up as
        negative remaining distance."""
        best_s, best_d = s_hint, math.inf
        pts, cum = self.points, self.cumulative
        for i in range(len(pts) - 1):
            if cum[i + 1] < s_hint - 0.2:
                continue
            ax, ay = pts[i]
            bx, by = pts[i + 1]
            sx, sy = bx - ax, by - ay
            seg2 = sx * sx + sy * sy
            t = ((x - ax) * sx + (y - ay) * sy) / seg2 if seg2 > 0 else 0.0
            last = i == len(pts) - 2
            t = max(0.0, t) if last else min(max(t, 0.0), 1.0)
            cx, cy = ax + sx * t, ay + sy * t
            d = math.hypot(x - cx, y - cy)
            if d < best_d:
                best_d, best_s = d, cum[i] + t * math.sqrt(seg2)
        return best_s


def _split_legs(points: list[Point]) -> list[_Leg]:
    """Cut the path at corners sharper than :data:`SHARP_CORNER`."""
    if len(points) < 2:
        return []
    legs: list[_Leg] = []
    current = [points[0], points[1]]
    for p in points[2:]:
        a, b = current[-2], current[-1]
        turn = abs(wrap(math.atan2(p[1] - b[1], p[0] - b[0]) - math.atan2(b[1] - a[1], b[0] - a[0])))
        if turn > SHARP_CORNER:
            legs.append(_Leg(current))
            current = [b, p]
        else:
            current.append(p)
    legs.append(_Leg(current))
    return legs


class BaseController:
    """The base: pose, body-frame velocity, and whichever command drives it now.

    Commands: :meth:`velocity` (expires after ``duration``), :meth:`follow` (a path) and
    :meth:`stop`; a new command replaces the old one. :meth:`step` advances by ``dt``.
    """

    def __init__(self, dt: float, limits: BaseLimits = BaseLimits(), x: float = 0.0, y: float = 0.0,
                 yaw: float = 0.0) -> None:
        self.dt = dt
        self.limits = limits
        self.x, self.y, self.yaw = x, y, wrap(yaw)
        self.vx = self.vy = self.wz = 0.0
        self.mode = "idle"  # idle | velocity | path | stop
        self.status = "idle"  # idle | moving | blocked | arrived
        self._target = (0.0, 0.0, 0.0)
        self._commanding = False
        self._expires = 0.0
        self.path: PathFollower | None = None
        self.arrival_error: dict[str, float | None] | None = None

    # -- commands --------------------------------------------------------------------------

    def velocity(self, vx: float, vy: float, wz: float, duration: float, now: float) -> None:
        self.mode, self.path, self.arrival_error = "velocity", None, None
        self._target = (vx, vy, wz)
        self._expires = now + duration
        self.status = "moving"

    def follow(self, waypoints: Sequence[Point], final_yaw: float | None, max_speed: float, tolerance: float,
               yaw_tolerance: float) -> None:
        self.mode, self.arrival_error = "path", None
        self.path = PathFollower((self.x, self.y), waypoints, final_yaw, max_speed, tolerance, yaw_tolerance,
                                 self.limits, self.dt)
        self.status = "moving"

    def stop(self) -> None:
        self.mode, self.path, self.arrival_error = "stop", None, None
        self._target = (0.0, 0.0, 0.0)
        self.status = "moving" if self.moving else "idle"

    def teleport(self, x: float, y: float, yaw: float) -> None:
        self.x, self.y, self.yaw = x, y, wrap(yaw)
        self.vx = self.vy = self.wz = 0.0
        self.mode, self.path, self.status, self.arrival_error = "idle", None, "idle", None

    @property
    def moving(self) -> bool:
        return self.vx != 0.0 or self.vy != 0.0 or self.wz != 0.0

    # -- one step --------------------------------------------------------------------------

    def step(self, now: float, check: PersonCheck | None = None) -> None:
        vx_t, vy_t, wz_t = self._command(now, check)
        lim = self.limits
        if math.hypot(vx_t, vy_t) < lim.dead_band:  # the walking controller's dead band
            vx_t = vy_t = 0.0
        speed = math.hypot(vx_t, vy_t)
        if speed > lim.max_speed:
            vx_t, vy_t = vx_t * lim.max_speed / speed, vy_t * lim.max_speed / speed
        wz_t = min(max(wz_t, -lim.max_yaw_rate), lim.max_yaw_rate)
        self._commanding = vx_t != 0.0 or vy_t != 0.0 or wz_t != 0.0
        dvx, dvy = vx_t - self.vx, vy_t - self.vy
        dv = math.hypot(dvx, dvy)
        max_dv = lim.accel * self.dt
        if dv > max_dv:
            dvx, dvy = dvx * max_dv / dv, dvy * max_dv / dv
            self.vx += dvx
            self.vy += dvy
        else:
            self.vx, self.vy = vx_t, vy_t
        dw = wz_t - self.wz
        max_dw = lim.yaw_accel * self.dt
        self.wz = wz_t if abs(dw) <= max_dw else self.wz + math.copysign(max_dw, dw)
        mid = self.yaw + 0.5 * self.wz * self.dt
        c, s = math.cos(mid), math.sin(mid)
        self.x += (c * self.vx - s * self.vy) * self.dt
        self.y += (s * self.vx + c * self.vy) * self.dt
        self.yaw = wrap(self.yaw + self.wz * self.dt)
        self._update_status()

    def _command(self, now: float, check: PersonCheck | None) -> tuple[float, float, float]:
        if self.mode == "velocity":
            if now >= self._expires:
                self.mode, self._target = "stop", (0.0, 0.0, 0.0)  # a silent client means a stopped robot
            return self._target
        if self.mode == "path" and self.path is not None:
            v = math.hypot(self.vx, self.vy)
            vx, wz, done = self.path.command(self.x, self.y, self.yaw, v, self.wz, now, check)
            if done:
                self.arrival_error = self.path.error
                self.mode = "arrived"
                self.vx = self.vy = self.wz = 0.0  # the follower only finishes at rest
            return vx, 0.0, wz
        return 0.0, 0.0, 0.0

    def _update_status(self) -> None:
        if self.mode == "arrived":
            self.status = "arrived"
        elif self.mode == "path" and self.path is not None:
            self.status = "blocked" if self.path.blocked else "moving"
        elif self.moving or (self.mode == "velocity" and self._commanding):
            self.status = "moving"
        else:
            self.status = "idle"
            self.mode = "idle"
