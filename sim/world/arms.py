"""Arms and hands: joint trajectories played in sim time, Dex3-1 hands, grasping.

The robot is kinematic in the world (its joints are set, not simulated), so an arm is exactly
where its trajectory says at every step: what a pick behaviour tests is its planning and timing,
not a joint controller's tuning. A grasp is a kinematic carry: closing a hand whose point is
within :data:`GRASP_RADIUS` of a free object fixes the object's pose relative to the hand until
the hand opens, when the object is released to physics and falls onto whatever is below.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import mujoco
import numpy as np

from .errors import WorldError

HAND_JOINTS = ("thumb_0", "thumb_1", "thumb_2", "index_0", "index_1", "middle_0", "middle_1")
SIDES = ("left", "right")
HAND_TIME = 0.5  # sim seconds to open or close a hand
CLOSED_FRACTION = 0.8  # a closed finger joint sits at this fraction of its range's far end
GRASP_RADIUS = 0.06  # metres from the hand point to an object's centre that a closing hand catches


def side_of(joint: str) -> str | None:
    for side in SIDES:
        if joint.startswith(side + "_"):
            return side
    return None


def hand_joint_names(side: str) -> list[str]:
    return [f"{side}_hand_{j}_joint" for j in HAND_JOINTS]


@dataclass
class _Trajectory:
    """Keyframes for some joints: ``times`` (K+1, from 0 = now) and ``values`` (K+1, J)."""

    traj_id: str
    joints: np.ndarray  # indices into the player's joint vector
    start: float
    times: np.ndarray
    values: np.ndarray
    smooth: bool

    @property
    def end(self) -> float:
        return self.start + float(self.times[-1])

    def sample(self, now: float) -> np.ndarray:
        t = now - self.start
        if t >= self.times[-1]:
            return self.values[-1]
        k = int(np.searchsorted(self.times, t, side="right")) - 1
        k = min(max(k, 0), len(self.times) - 2)
        span = self.times[k + 1] - self.times[k]
        a = 1.0 if span <= 0 else (t - self.times[k]) / span
        if self.smooth:
            a = a * a * (3.0 - 2.0 * a)
        return self.values[k] + (self.values[k + 1] - self.values[k]) * a

    def drop(self, indices: Iterable[int]) -> bool:
        """Give up ``indices`` (a newer trajectory took them); False when nothing is left."""
        keep = ~np.isin(self.joints, list(indices))
        self.joints = self.joints[keep]
        self.values = self.values[:, keep]
        return bool(self.joints.size)


class JointPlayer:
    """Plays joint trajectories on a named joint vector ``q`` (every joint but the base).

    A trajectory starts from the joints' current values; a new one takes over the joints it
    names from any older one, which keeps playing its other joints. :meth:`stop` holds the pose.
    """

    def __init__(self, names: list[str], lower: np.ndarray, upper: np.ndarray, q0: np.ndarray) -> None:
        self.names = list(names)
        self.index = {n: i for i, n in enumerate(self.names)}
        self.lower = np.asarray(lower, dtype=float)
        self.upper = np.asarray(upper, dtype=float)
        self.q = np.clip(np.asarray(q0, dtype=float), self.lower, self.upper)
        self.trajectories: list[_Trajectory] = []

    def start(self, points: object, traj_id: str, now: float, smooth: bool = False) -> dict[str, Any]:
        """Check and start a trajectory; raises :class:`WorldError` before anything moves."""
        if not isinstance(points, list) or not points:
            raise WorldError("bad_request", "'points' must be a non-empty list of {t, joints}")
        named: list[str] = []
        times = [0.0]
        rows: list[dict[str, float]] = []
        for n, point in enumerate(points):
            if not isinstance(point, dict) or not isinstance(point.get("joints"), dict):
                raise WorldError("bad_request", f"point {n} must be an object with 't' and 'joints'")
            t = point.get("t")
            if isinstance(t, bool) or not isinstance(t, (int, float)) or not np.isfinite(t):
                raise WorldError("bad_request", f"point {n}: 't' must be a number (sim seconds from now)")
            if t < 0 or (n > 0 and t <= times[-1]):
                raise WorldError("bad_request", f"point {n}: 't' must be >= 0 and increase from point to point")
            row: dict[str, float] = {}
            for name, value in point["joints"].items():
                if name not in self.index:
                    raise WorldError("not_found", f"point {n}: no joint {name!r}")
                if isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value):
                    raise WorldError("bad_request", f"point {n}: {name} must be a finite number")
                i = self.index[name]
                if not self.lower[i] - 1e-9 <= value <= self.upper[i] + 1e-9:
                    raise WorldError("out_of_range", f"point {n}: {name} = {value:.4f} is outside its limits "
                                   f"[{self.lower[i]:.4f}, {self.upper[i]:.4f}]")
                row[name] = float(value)
                if name not in named:
                    named.append(name)
            times.append(float(t))
            rows.append(row)
        indices = np.array([self.index[n] for n in named], dtype=int)
        values = np.empty((len(rows) + 1, len(indices)))
        values[0] = self.q[indices]
        for k, row in enumerate(rows, start=1):  # a joint missing from a point keeps its last value
            values[k] = [row.get(n, values[k - 1][j]) for j, n in enumerate(named)]
        self._release(indices)
        trajectory = _Trajectory(traj_id, indices, now, np.array(times), values, smooth)
        self.trajectories.append(trajectory)
        return {"id": traj_id, "joints": named, "ends_at": round(trajectory.end, 4)}

    def stop(self, joints: Iterable[str] | None = None) -> None:
        """Hold the current pose of ``joints`` (all when None)."""
        if joints is None:
            self.trajectories.clear()
        else:
            self._release(np.array([self.index[n] for n in joints if n in self.index], dtype=int))

    def _release(self, indices: np.ndarray) -> None:
        self.trajectories = [tr for tr in self.trajectories if tr.drop(indices)]

    def step(self, now: float) -> None:
        if not self.trajectories:
            return
        finished = []
        for tr in self.trajectories:
            self.q[tr.joints] = tr.sample(now)
            if now >= tr.end:
                finished.append(tr)
        if finished:
            self.trajectories = [tr for tr in self.trajectories if tr not in finished]

    def busy(self, side: str, hands: bool = False) -> bool:
        """Whether a trajectory moves an arm joint (hand joints only if ``hands``) of ``side``."""
        for tr in self.trajectories:
            for i in tr.joints:
                name = self.names[i]
                if side_of(name) == side and (hands or "_hand_" not in name):
                    return True
        return False

    def active_ids(self) -> list[str]:
        return [tr.traj_id for tr in self.trajectories]

    def joint_dict(self) -> dict[str, float]:
        return {n: round(float(v), 5) for n, v in zip(self.names, self.q, strict=True)}


def hand_poses(player: JointPlayer, side: str) -> tuple[dict[str, float], dict[str, float]]:
    """(open, closed) poses of one Dex3-1 hand from its joint limits.

    Open is zero (clipped into range). Closed bends each finger joint toward the end of its
    range that is farther from zero, which is the flexing direction on both hands whatever
    their mirrored signs; a joint with a symmetric range (the thumb's rotation) stays at zero.
    """
    open_pose: dict[str, float] = {}
    closed: dict[str, float] = {}
    for name in hand_joint_names(side):
        i = player.index.get(name)
        if i is None:
            continue
        lo, hi = player.lower[i], player.upper[i]
        open_pose[name] = float(np.clip(0.0, lo, hi))
        if abs(abs(lo) - abs(hi)) < 1e-3:
            closed[name] = open_pose[name]
        else:
            far = lo if abs(lo) > abs(hi) else hi
            closed[name] = float(CLOSED_FRACTION * far)
    return open_pose, closed


@dataclass
class Held:
    label: str
    body: int  # the hand body the object rides on
    rel_pos: np.ndarray
    rel_mat: np.ndarray


@dataclass
class FreeObject:
    label: str
    body: int
    qpos: int  # address of the free joint's 7 qpos values
    qvel: int  # address of its 6 qvel values


@dataclass
class Hands:
    """Opening, closing and what each hand holds. Grasping and carrying act on MuJoCo data."""

    player: JointPlayer
    model: mujoco.MjModel
    hand_sites: dict[str, int]  # side -> site id of the hand point
    objects: dict[str, FreeObject]
    state: dict[str, str] = field(default_factory=lambda: {s: "open" for s in SIDES})
    held: dict[str, Held | None] = field(default_factory=lambda: {s: None for s in SIDES})
    _until: dict[str, float] = field(default_factory=dict)

    def command(self, side: str, closed: bool, data: mujoco.MjData, now: float) -> dict[str, Any]:
        if side not in SIDES:
            raise WorldError("bad_request", f"side must be left or right, got {side!r}")
        open_pose, closed_pose = hand_poses(self.player, side)
        if not open_pose:
            raise WorldError("not_found", f"the robot has no {side} hand joints")
        target = closed_pose if closed else open_pose
        self.player.start([{"t": HAND_TIME, "joints": target}], f"{side}_hand", now, smooth=True)
        self.state[side] = "closing" if closed else "opening"
        self._until[side] = now + HAND_TIME
        if not closed:
            self.release(side, data)
        elif self.held[side] is None:
            self._try_grasp(side, data)
        return {"side": side, "state": self.state[side], "held": self.held_label(side)}

    def step(self, data: mujoco.MjData, now: float) -> None:
        """Finish hand motions, catch objects while closing, carry what is held."""
        for side in SIDES:
            state = self.state[side]
            if state in ("closing", "opening"):
                if state == "closing" and self.held[side] is None:
                    self._try_grasp(side, data)
                if now >= self._until.get(side, 0.0):
                    self.state[side] = "closed" if state == "closing" else "open"
            held = self.held[side]
            if held is not None:
                self._carry(held, data)

    def held_label(self, side: str) -> str | None:
        h = self.held[side]
        return None if h is None else h.label

    def holder(self, label: str) -> str | None:
        for side in SIDES:
            if self.held_label(side) == label:
                return side
        return None

    def release(self, side: str, data: mujoco.MjData) -> None:
        held = self.held[side]
        if held is None:
            return
        obj = self.objects[held.label]
        data.qvel[obj.qvel:obj.qvel + 6] = 0.0
        self.held[side] = None

    def _try_grasp(self, side: str, data: mujoco.MjData) -> None:
        site = self.hand_sites.get(side)
        if site is None:
            return
        point = data.site_xpos[site]
        taken = {h.label for h in self.held.values() if h is not None}
        best, best_d = None, GRASP_RADIUS
        for obj in self.objects.values():
            if obj.label in taken:
                continue
            d = float(np.linalg.norm(data.xpos[obj.body] - point))
            if d <= best_d:
                best, best_d = obj, d
        if best is None:
            return
        body = int(self.model.site_bodyid[site])
        hand_pos, hand_mat = data.xpos[body], data.xmat[body].reshape(3, 3)
        obj_mat = data.xmat[best.body].reshape(3, 3)
        self.held[side] = Held(best.label, body, hand_mat.T @ (data.xpos[best.body] - hand_pos), hand_mat.T @ obj_mat)

    def _carry(self, held: Held, data: mujoco.MjData) -> None:
        obj = self.objects[held.label]
        hand_pos, hand_mat = data.xpos[held.body], data.xmat[held.body].reshape(3, 3)
        pos = hand_pos + hand_mat @ held.rel_pos
        quat = np.empty(4)
        mujoco.mju_mat2Quat(quat, (hand_mat @ held.rel_mat).reshape(9))
        data.qpos[obj.qpos:obj.qpos + 3] = pos
        data.qpos[obj.qpos + 3:obj.qpos + 7] = quat
        data.qvel[obj.qvel:obj.qvel + 6] = 0.0
