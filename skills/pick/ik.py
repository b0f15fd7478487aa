"""Arm inverse kinematics for the G1: one interface, two solvers, and a reachability pre-check.

Targets are hand-point positions (``{arm}_hand_point``, the grasp point 5 cm past the wrist yaw
joint) in the torso_link frame, so the answer does not depend on where the base or waist is.
Only the seven joints of the chosen arm move; every other joint is held.

- :func:`check_reachable` says, in words, why a target can never be reached (too far from the
  shoulder, by how much; inside the body; behind the back on the other arm's side). Callers run
  it before any motion, and both solvers run it first too.
- ``make_solver("pin")``: Pinocchio damped least squares with joint limits enforced by
  projection (``ik_pin.py``); ``make_solver("placo")``: PlaCo's QP kinematics solver
  (``ik_placo.py``). Both are verified by the same forward kinematics (``ik_arm.py``): a result
  is a success only if its joints are within limits and its hand point within tolerance.

``orientation`` is a soft wish, never a condition of success: ``"down"`` turns the palm to face
the floor (grasps from above), ``"forward"`` points the fingers along +x.
"""

from __future__ import annotations

import functools
import time
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from stuart_bt.core.suggest import did_you_mean
from stuart_bt.sim.robot import description as desc

Arm = Literal["left", "right"]
Orientation = Literal["down", "forward"] | None
ARMS: tuple[Arm, Arm] = ("left", "right")
ORIENTATIONS = (None, "down", "forward")
SOLVERS = ("pin", "placo")
POSITION_TOLERANCE = 1e-3  # m: a result is a success within this
CONVERGED = 5e-5  # m: solvers iterate until this (well inside the tolerance)
LIMIT_SLACK = 1e-9  # rad: rounding allowed at a joint limit

# Orientation wishes: (axis in the hand-point frame, where it should point in torso_link)
TARGET_AXES: dict[str, dict[str, tuple[np.ndarray, np.ndarray]]] = {
    arm: {"down": (np.array(desc.HAND_PALM_NORMAL[arm]), np.array([0.0, 0.0, -1.0])),
          "forward": (np.array(desc.HAND_FINGER_AXIS), np.array([1.0, 0.0, 0.0]))}
    for arm in ARMS
}


def as_arm(side: str) -> Arm:
    """``side`` as an :data:`Arm`, checked: the daemons take arm names from requests as plain
    strings ("auto" already resolved), and the solvers and joint tables take only these two."""
    if side == "left":
        return "left"
    if side == "right":
        return "right"
    raise ValueError(f"no arm {side!r}; arms are {' and '.join(ARMS)}")


@dataclass(frozen=True)
class IKResult:
    success: bool
    q: dict[str, float]  # the arm's seven joints (the best found, even on failure)
    position_error: float  # m, hand point to target
    iterations: int  # over all attempts
    seconds: float
    reason: str = ""  # why not, when not a success
    orientation_error: float | None = field(default=None, compare=False)  # rad, when one was asked for


class IKSolver(ABC):
    """Solves for one arm's joints so that its hand point reaches a target in torso_link."""

    name: str = ""
    restarts: int = 6  # random starts tried after the seed
    seed: int = 0  # of the random starts: the same target gives the same answer

    def solve(self, arm: Arm, target_xyz_torso: np.ndarray, q_init: dict[str, float] | None = None,
              orientation: Orientation = None) -> IKResult:
        """Pre-check, then the solver's own iterations, then an independent verification."""
        started = time.perf_counter()
        if arm not in ARMS:
            raise ValueError(f"arm must be 'left' or 'right', got {arm!r}{did_you_mean(str(arm), ARMS)}")
        if orientation not in ORIENTATIONS:
            raise ValueError(f"orientation must be None, 'down' or 'forward', got {orientation!r}")
        target = np.asarray(target_xyz_torso, dtype=float).reshape(3)
        chain = self.chain(arm)
        seed = chain.vector(q_init)
        reason = check_reachable(arm, target)
        if reason is not None:
            q = chain.named(seed)
            return IKResult(False, q, float(np.linalg.norm(chain.position(seed) - target)), 0,
                            time.perf_counter() - started, reason)
        q, iterations, note = self._solve(arm, target, seed, orientation)
        return self._verdict(arm, target, q, iterations, note, orientation, started)

    @abstractmethod
    def chain(self, arm: Arm):  # -> ik_arm.ArmChain
        """The arm's kinematic chain (for seeds and verification)."""

    @abstractmethod
    def _solve(self, arm: Arm, target: np.ndarray, seed: np.ndarray,
               orientation: Orientation) -> tuple[np.ndarray, int, str]:
        """(best joint vector, iterations used, a note on failure)."""

    def _best_of_restarts(self, chain, seed: np.ndarray,
                          descend: Callable[[np.ndarray, bool], tuple[np.ndarray, float, int]],
                          oriented: bool) -> tuple[np.ndarray, int, str]:
        """Descend from the seed, then from random starts, keeping the closest result. An
        oriented descent that misses is followed by a position-only one from where it stopped:
        the orientation wish fought the joint limits, and position comes first."""
        rng = np.random.default_rng(self.seed)
        best_q, best_error, total = chain.clip(seed), np.inf, 0
        attempt = 0
        for attempt in range(1 + self.restarts):
            start = chain.clip(seed) if attempt == 0 else chain.random(rng)
            q, error, iterations = descend(start, oriented)
            total += iterations
            if oriented and error > CONVERGED:
                q, error, iterations = descend(q, False)
                total += iterations
            if error < best_error:
                best_q, best_error = q, error
            if error <= CONVERGED:
                break
        note = "" if best_error <= POSITION_TOLERANCE else (
            f"did not converge in {attempt + 1} starts: the closest hand point was {best_error * 1000:.1f} mm "
            "from the target (joint limits)")
        return best_q, total, note

    def _verdict(self, arm: Arm, target: np.ndarray, q: np.ndarray, iterations: int, note: str,
                 orientation: Orientation, started: float) -> IKResult:
        chain = self.chain(arm)
        error = float(np.linalg.norm(chain.position(q) - target))
        outside = chain.outside_limits(q, LIMIT_SLACK)
        orientation_error = chain.axis_error(q, *TARGET_AXES[arm][orientation]) if orientation else None
        if outside:
            success, reason = False, f"joint limits violated: {', '.join(outside)}"
        elif error > POSITION_TOLERANCE:
            success = False
            reason = note or f"did not converge: hand point {error * 1000:.1f} mm from the target"
        else:
            success, reason = True, ""
        return IKResult(success, chain.named(q), error, iterations, time.perf_counter() - started, reason,
                        orientation_error)


def check_reachable(arm: Arm, target: np.ndarray) -> str | None:
    """Why no configuration of ``arm`` can put its hand point at ``target`` (torso_link), or
    ``None`` if it may be reachable. Only sure cases are reported, so a ``None`` can still fail
    in the solver (joint limits)."""
    target = np.asarray(target, dtype=float).reshape(3)
    shoulder = desc.shoulder_xyz(arm)
    distance = float(np.linalg.norm(target - shoulder))
    if distance > desc.REACH:
        return (f"target is {distance - desc.REACH:.3f} m beyond the {arm} arm's reach "
                f"({distance:.3f} m from the shoulder, reach {desc.REACH:.3f} m)")
    inside = _inside_body(arm, target)
    if inside:
        return f"target is inside the robot's {inside}"
    back, top = _chest_back_and_top()
    side = 1.0 if arm == "left" else -1.0
    if target[0] < back and side * target[1] < 0 and target[2] < top:
        return (f"target is behind the back on the {'right' if arm == 'left' else 'left'} side "
                f"(x {target[0]:.3f} m < {back:.3f} m): the {arm} arm cannot reach around the body")
    return None


# --- the body as keep-out volumes, in torso_link at waist zero --------------------------------

@functools.lru_cache(maxsize=2)
def _keep_out(arm: Arm) -> tuple[tuple[str, desc.Geom, np.ndarray], ...]:
    """(label, geom, link origin in torso_link) for the trunk, head and this arm's shoulder."""
    robot = desc.g1()
    offsets = {"pelvis": np.array([0.0, 0.0, -desc.WAIST_HEIGHT]), "torso_link": np.zeros(3),
               "head_link": np.asarray(robot.joint("head_joint").xyz),
               f"{arm}_shoulder_pitch_link": desc.shoulder_xyz(arm)}
    out = []
    for link, origin in offsets.items():
        for g in robot.links[link].geoms:
            out.append((g.name.replace("_", " "), g, origin))
    return tuple(out)


def _inside_body(arm: Arm, p: np.ndarray) -> str | None:
    for label, g, origin in _keep_out(arm):
        local = desc.rpy_matrix(g.rpy).T @ (p - origin - np.asarray(g.pos))
        if g.type == "box":
            hit = bool(np.all(np.abs(local) <= np.asarray(g.size)))
        elif g.type == "sphere":
            hit = float(np.linalg.norm(local)) <= g.size[0]
        else:
            r, h = g.size
            along = float(np.clip(local[2], -h, h))
            radial = float(np.hypot(local[0], local[1]))
            hit = (abs(local[2]) <= h and radial <= r) if g.type == "cylinder" else \
                float(np.linalg.norm(local - np.array([0.0, 0.0, along]))) <= r
        if hit:
            return label
    return None


@functools.lru_cache(maxsize=1)
def _chest_back_and_top() -> tuple[float, float]:
    """The chest's back face (x) and top (z): behind it and below that top is the trunk's far side."""
    chest = next(g for g in desc.g1().links["torso_link"].geoms if g.name == "chest")
    return chest.pos[0] - chest.size[0], chest.pos[2] + chest.size[2]
