"""Where to stand to see something: a fixed camera on a walking base, and a map.

Looking needs a different spot from reaching. The G1's head camera cannot tilt: it looks
forward and down at a fixed pitch, so a point is in view only inside a band of distances that
depends on its height (a table top from roughly 0.3 to 0.8 m, the floor from 0.6 to 1.6 m), and
only while nothing on the map stands between the camera and the point.

:class:`CameraView` says what the camera sees from a base pose (field of view, range, with a
margin so the whole object and not only its centre is in the picture). :func:`line_of_sight`
asks the map whether an obstacle hides the point; the map has no heights, so whatever the point
stands on (the run of occupied cells the point itself is in: a table under a cup) cannot hide
it, and any other obstacle on the way does. :func:`find_viewpoint` searches spots all round the
point, at the distances the camera sees it from, keeps those the robot can stand on and reach,
and takes the nearest on foot; when there is none, :class:`NoViewpoint` says why and names what
was in the way (the furniture's names, when the map knows them).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field

from ..core.errors import StuartError
from .furniture import Furniture, FurnitureCells, ranked
from .grid import Grid
from .nearest import nearest_goal

Point = tuple[float, float]
HEADING_STEP = math.radians(15.0)  # spots round the point, as the approach search uses
DISTANCE_STEP = 0.05  # metres between two distances tried along one heading
PREFERENCE = 2.0  # metres of walking one metre off the camera's centred distance is worth


@dataclass(frozen=True)
class CameraView:
    """A camera fixed on the robot's torso: its optical centre ``height`` above the floor,
    ``ahead`` and ``left`` of the base centre, pitched ``pitch`` radians down, with full fields of
    view ``hfov`` x ``vfov`` (radians). A point is seen between ``near`` and ``far`` metres (depth
    starts ~0.3 m from a RealSense; past ``far`` a small object is too few pixels for the
    detector) and within ``margin`` of the picture's half-widths."""

    height: float
    ahead: float
    left: float
    pitch: float
    hfov: float
    vfov: float
    near: float = 0.3
    far: float = 2.0
    margin: float = 0.8

    def eye(self, x: float, y: float, yaw: float) -> Point:
        """Where the optical centre is, on the floor plan, for a base at (x, y, yaw)."""
        c, s = math.cos(yaw), math.sin(yaw)
        return x + c * self.ahead - s * self.left, y + s * self.ahead + c * self.left

    def miss(self, base: tuple[float, float, float], target: tuple[float, float, float]) -> str | None:
        """Why the camera of a base at ``base`` (x, y, yaw) does not see ``target`` (x, y, z), or
        None when it does (the map is not asked: see :func:`line_of_sight`)."""
        ex, ey = self.eye(*base)
        c, s = math.cos(base[2]), math.sin(base[2])
        dx, dy, up = target[0] - ex, target[1] - ey, target[2] - self.height
        forward, left = c * dx + s * dy, -s * dx + c * dy
        depth = forward * math.cos(self.pitch) - up * math.sin(self.pitch)  # along the optical axis
        down = -forward * math.sin(self.pitch) - up * math.cos(self.pitch)  # picture rows grow downwards
        distance = math.sqrt(forward * forward + left * left + up * up)
        if depth <= 0.0:
            return "behind the camera"
        if abs(left) > depth * self.margin * math.tan(self.hfov / 2):
            return "left of the picture" if left > 0 else "right of the picture"
        if abs(down) > depth * self.margin * math.tan(self.vfov / 2):
            return "below the picture" if down > 0 else "above the picture"
        if distance > self.far:
            return f"{distance:.2f} m away, further than {self.far:g} m"
        if distance < self.near:
            return f"{distance:.2f} m away, closer than {self.near:g} m"
        return None

    def band(self, z: float) -> tuple[float, float] | None:
        """The horizontal distances from the camera at which a point at height ``z``, straight
        ahead, is in the picture and in range; None when no distance is (the point is too high
        for a camera looking down)."""
        half = math.atan(self.margin * math.tan(self.vfov / 2))
        drop = self.height - z
        lo, hi = self.pitch - half, self.pitch + half  # depression angles the picture spans
        steepest = math.radians(89.9)
        if drop > 0.0:  # looking down at it: depressions in (0, 90) degrees
            if hi <= 0.0:
                return None
            lo_d = drop / math.tan(min(hi, steepest))
            hi_d = math.inf if lo <= 0.0 else drop / math.tan(lo)
        elif drop < 0.0:  # looking up at it: depressions in (-90, 0) degrees
            if lo >= 0.0:
                return None
            lo_d = drop / math.tan(max(lo, -steepest))
            hi_d = math.inf if hi >= 0.0 else drop / math.tan(hi)
        elif lo <= 0.0 <= hi:
            lo_d, hi_d = 0.0, math.inf
        else:
            return None
        lo_d = max(lo_d, math.sqrt(max(0.0, self.near ** 2 - drop ** 2)))
        hi_d = min(hi_d, math.sqrt(max(0.0, self.far ** 2 - drop ** 2)))
        return (lo_d, hi_d) if lo_d <= hi_d else None

    def centred(self, z: float) -> float | None:
        """The horizontal distance at which a point at height ``z`` is in the middle of the
        picture (clamped into :meth:`band`); None when no distance sees it."""
        band = self.band(z)
        if band is None:
            return None
        drop = self.height - z
        middle = drop / math.tan(self.pitch) if self.pitch > 0 and drop > 0 else band[0]
        return min(max(middle, band[0]), band[1])


@dataclass(frozen=True)
class StandingMap:
    """What the search needs of a map: the raw ``obstacles`` (lines of sight), the ``roomy``
    grid the robot walks on (obstacles grown by its radius), the ``tight`` one it may stand on
    when docked at furniture (a thinner margin), how far a spot may be from roomy space for the
    last straight ``dock`` step, and the names of the ``furniture``."""

    obstacles: Grid
    roomy: Grid
    tight: Grid
    dock: float = 0.3
    furniture: Furniture = field(default_factory=Furniture)
    named: FurnitureCells = field(init=False, repr=False)

    def __post_init__(self) -> None:
        reach = self.dock + 2 * self.obstacles.resolution  # a spot in a margin, or a blocked cell's neighbour
        object.__setattr__(self, "named", FurnitureCells(self.furniture, self.obstacles, reach))

    def docking_cell(self, x: float, y: float) -> tuple[tuple[int, int], float] | None:
        """The roomy cell a walk to (x, y) ends in and the straight step from it onto the spot,
        metres; None when the spot needs a longer or blocked step."""
        cell = self.roomy.world_to_cell(x, y)
        if self.roomy.cell_is_free(*cell):
            return cell, 0.0
        free = self.roomy.nearest_free(*cell, int(self.dock / self.roomy.resolution))
        if free is None:
            return None
        fx, fy = self.roomy.cell_to_world(*free)
        if not self.tight.segment_free((fx, fy), (x, y)):
            return None
        return free, math.hypot(x - fx, y - fy)

    def name_at(self, x: float, y: float, within: float) -> str | None:
        """The named furniture at (x, y) or within ``within`` metres of it (up to ``dock`` plus two cells)."""
        return self.named.at(x, y, within)


@dataclass(frozen=True)
class Viewpoint:
    """A base pose to stand at, the camera's horizontal distance to the point from there, and
    the estimated walk to it (metres; 0: the robot sees it from where it stands)."""

    x: float
    y: float
    yaw: float
    distance: float
    walk: float


class NoViewpoint(StuartError):
    """No spot the robot can reach sees the point. ``blocked_by`` names what was in the way
    most often (named furniture only), ``counts`` says how many spots failed for which cause."""

    def __init__(self, reason: str, blocked_by: list[str], counts: dict[str, int]) -> None:
        super().__init__(reason)
        self.reason = reason
        self.blocked_by = blocked_by
        self.counts = counts


def line_of_sight(obstacles: Grid, eye: Point, target: Point) -> Point | None:
    """The first place on the map that hides ``target`` from ``eye``, or None when nothing does.

    Walked from the target towards the eye in quarter cells: the occupied cells the target is in
    are what it stands on (they cannot hide it: the map has no heights, and the camera looks
    down); past the first free cell, any occupied cell (or the edge of the map) is in the way."""
    length = math.hypot(eye[0] - target[0], eye[1] - target[1])
    steps = max(1, int(length / (obstacles.resolution * 0.25)))
    on_support = True
    for i in range(steps + 1):
        t = i / steps
        x, y = target[0] + (eye[0] - target[0]) * t, target[1] + (eye[1] - target[1]) * t
        free = obstacles.cell_is_free(*obstacles.world_to_cell(x, y))
        if free:
            on_support = False
        elif not on_support:
            return x, y
    return None


def find_viewpoint(space: StandingMap, camera: CameraView, target: tuple[float, float, float],
                   here: tuple[float, float, float]) -> Viewpoint:
    """The spot nearest on foot from which the camera sees ``target`` (x, y, z) with nothing on
    the map in the way. From where the robot stands (``here``: x, y, yaw) it does not move, or
    only turns, when that is enough. Raises :class:`NoViewpoint`."""
    stay = _from_here(space, camera, target, here)
    if stay is not None:
        return stay
    centred = camera.centred(target[2])
    band = camera.band(target[2])
    if band is None or centred is None:
        raise NoViewpoint(f"the camera sees no point at height {target[2]:.2f} m from any distance", [], {})
    counts = {"inside": 0, "hidden": 0, "out_of_view": 0, "tight": 0, "unreachable": 0}
    in_the_way: list[str | None] = []
    goals: dict[tuple[int, int], list[tuple[float, Viewpoint]]] = {}
    res = space.roomy.resolution
    for spot in _spots(camera, target, here, band, centred):
        cause, name = _unusable(space, camera, target, spot)
        if cause is not None:
            counts[cause] += 1
            in_the_way.append(name)
            continue
        docking = space.docking_cell(spot.x, spot.y)
        if docking is None:
            counts["tight"] += 1
            in_the_way.append(space.name_at(spot.x, spot.y, space.dock + res))
            continue
        cell, step = docking
        extra = (step + PREFERENCE * abs(spot.distance - centred)) / res
        goals.setdefault(cell, []).append((extra, spot))
    start = _start_cell(space, here)
    found = nearest_goal(space.roomy.occupied, start, goals) if goals and start is not None else None
    if found is None:
        counts["unreachable"] += sum(len(v) for v in goals.values())
        raise NoViewpoint(_no_view_reason(target, counts), ranked(in_the_way), counts)
    cost, spot = found
    return Viewpoint(spot.x, spot.y, spot.yaw, spot.distance, round(cost * res, 3))


def _from_here(space: StandingMap, camera: CameraView, target: tuple[float, float, float],
               here: tuple[float, float, float]) -> Viewpoint | None:
    """Standing still, or turning in place to face the point, when that already shows it."""
    facing = math.atan2(target[1] - here[1], target[0] - here[0])
    for yaw in (here[2], facing):
        pose = (here[0], here[1], yaw)
        eye = camera.eye(*pose)
        if camera.miss(pose, target) is None and line_of_sight(space.obstacles, eye, target[:2]) is None:
            return Viewpoint(here[0], here[1], yaw, math.hypot(target[0] - eye[0], target[1] - eye[1]), 0.0)
    return None


def _spots(camera: CameraView, target: tuple[float, float, float], here: tuple[float, float, float],
           band: tuple[float, float], centred: float) -> Iterator[Viewpoint]:
    """Base poses facing the point from every side (the robot's own side first), at every
    distance the camera sees it from (the centred one first)."""
    facing = math.atan2(target[1] - here[1], target[0] - here[0])
    turns = round(2 * math.pi / HEADING_STEP)
    headings = [facing + HEADING_STEP * k * sign for k in range(turns // 2 + 1)
                for sign in ((1,) if k in (0, turns // 2) else (1, -1))]
    steps = int(math.ceil((band[1] - band[0]) / DISTANCE_STEP))
    through = {round(min(band[0] + DISTANCE_STEP * k, band[1]), 3) for k in range(steps + 1)}
    distances = sorted(through | {round(centred, 3)}, key=lambda d: (abs(d - centred), d))
    for heading in headings:
        c, s = math.cos(heading), math.sin(heading)
        for d in distances:
            ex, ey = target[0] - d * c, target[1] - d * s  # the eye; the base is behind and right of it
            x = ex - c * camera.ahead + s * camera.left
            y = ey - s * camera.ahead - c * camera.left
            yield Viewpoint(x, y, math.atan2(s, c), d, 0.0)


def _unusable(space: StandingMap, camera: CameraView, target: tuple[float, float, float],
              spot: Viewpoint) -> tuple[str | None, str | None]:
    """Why the robot cannot look from ``spot`` (``inside``: furniture's margin; ``hidden``: the
    view is blocked; ``out_of_view``: just outside the picture), with the name of what is in the
    way; (None, None) when it can."""
    res = space.tight.resolution
    if not space.tight.cell_is_free(*space.tight.world_to_cell(spot.x, spot.y)):
        return "inside", space.name_at(spot.x, spot.y, space.dock + res)
    pose = (spot.x, spot.y, spot.yaw)
    if camera.miss(pose, target) is not None:  # at the band's very edge, or the camera's offset
        return "out_of_view", None
    blocked = line_of_sight(space.obstacles, camera.eye(*pose), target[:2])
    if blocked is not None:
        return "hidden", space.name_at(*blocked, res)
    return None, None


def _start_cell(space: StandingMap, here: tuple[float, float, float]) -> tuple[int, int] | None:
    row, col = space.roomy.world_to_cell(here[0], here[1])
    return space.roomy.nearest_free(row, col, int(space.dock / space.roomy.resolution))


def _no_view_reason(target: tuple[float, float, float], counts: dict[str, int]) -> str:
    parts = {"inside": "too close to furniture", "hidden": "with the view blocked", "out_of_view": "out of view",
             "tight": "with no straight step onto them", "unreachable": "with no path from here"}
    said = ", ".join(f"{n} {parts[k]}" for k, n in counts.items() if n)
    return (f"no spot to see ({target[0]:.2f}, {target[1]:.2f}, {target[2]:.2f}) from"
            + (f" ({said})" if said else ""))
