"""Pinocchio IK: damped least squares on the seven arm joints, limits by projection.

Why this shape: a 3-D position target on a 7-joint arm is a small, well-conditioned problem
away from full stretch, so Gauss-Newton steps with a little damping converge in a handful of
iterations. Limits: a joint already at a limit whose step would push it further is dropped
from that step (an active set) and the rest is re-solved, then the result is clamped; a
plain clamp alone stalls when a limit blocks the direct path. When an attempt stalls, the
next starts from a random configuration inside the limits (seeded: same target, same answer).

The orientation wish is stacked under the position rows with a small weight (the same shape as
PlaCo's soft task); if the wish pulls the hand off the target, a position-only pass follows,
so it never costs position accuracy.
"""

from __future__ import annotations

import numpy as np

from .ik import CONVERGED, TARGET_AXES, Arm, IKSolver, Orientation
from .ik_arm import ArmChain, chain

ORIENTATION_WEIGHT = 0.25  # m per rad: in the stacked least squares a radian of tilt weighs like
# 25 cm of position error; where the two conflict, the position-only pass that follows settles it


class PinSolver(IKSolver):
    name = "pin"

    def __init__(self, max_iterations: int = 60, restarts: int = 6, damping: float = 0.01,
                 max_step: float = 0.5, seed: int = 0) -> None:
        self.max_iterations = max_iterations
        self.restarts = restarts
        self.damping2 = damping * damping  # m^2, added to J J^T
        self.max_step = max_step  # rad, largest joint change per iteration
        self.seed = seed

    def chain(self, arm: Arm) -> ArmChain:
        return chain(arm)

    def _solve(self, arm: Arm, target: np.ndarray, seed: np.ndarray,
               orientation: Orientation) -> tuple[np.ndarray, int, str]:
        ch = self.chain(arm)
        goal = ch.to_root(target)
        wish = None
        if orientation:
            local, torso_axis = TARGET_AXES[arm][orientation]
            wish = (local, ch.root_to_torso.rotation @ torso_axis)
        return self._best_of_restarts(
            ch, seed, lambda start, oriented: self._descend(ch, goal, start, wish if oriented else None),
            wish is not None)

    def _descend(self, ch: ArmChain, goal: np.ndarray, q: np.ndarray,
                 wish: tuple[np.ndarray, np.ndarray] | None) -> tuple[np.ndarray, float, int]:
        """One attempt from ``q``: (final q, position error, iterations). Stops when the hand
        point is there (and the wished axis aligned, or no longer turning), or when progress
        stalls for a few iterations (then a restart does better than more of the same)."""
        lower, upper = ch.lower, ch.upper
        best, stalled, iteration = np.inf, 0, 0
        error = np.inf
        for iteration in range(1, self.max_iterations + 1):
            position, jp, jw, rotation = ch.jacobian(q)
            e = goal - position
            error = float(np.sqrt(e @ e))
            turn, jt = _no_turn if wish is None else _turn(rotation @ wish[0], wish[1], jw)
            cost = error if turn is None else error + ORIENTATION_WEIGHT * float(np.sqrt(turn @ turn))
            if error <= CONVERGED and (turn is None or cost - error < 1e-4 or cost > best - 1e-5):
                return q, error, iteration
            if cost < best * 0.99:
                best, stalled = cost, 0
            else:
                stalled += 1
                if stalled >= 8:
                    break
            if turn is not None and jt is not None:  # stack the wish under the position task, weighted
                jp = np.vstack([jp, ORIENTATION_WEIGHT * jt])
                e = np.concatenate([e, ORIENTATION_WEIGHT * turn])
            q = np.clip(q + self._step(jp, e, q, lower, upper), lower, upper)
        return q, float(np.linalg.norm(goal - ch.jacobian(q)[0])), iteration

    def _step(self, j_all: np.ndarray, e: np.ndarray, q: np.ndarray, lower: np.ndarray,
              upper: np.ndarray) -> np.ndarray:
        """A damped least-squares step that leaves joints pinned at a limit where they are."""
        free = np.ones(q.size, dtype=bool)
        dq = np.zeros(q.size)
        damping = self.damping2 * np.eye(e.size)
        for _ in range(3):
            j = j_all[:, free]
            dq[:] = 0.0
            dq[free] = j.T @ np.linalg.solve(j @ j.T + damping, e)
            pinned = free & (((q <= lower + 1e-9) & (dq < 0)) | ((q >= upper - 1e-9) & (dq > 0)))
            if not pinned.any():
                break
            free &= ~pinned
            if not free.any():
                return np.zeros(q.size)
        largest = float(np.max(np.abs(dq)))
        if largest > self.max_step:
            dq *= self.max_step / largest
        return dq


_no_turn: tuple[np.ndarray | None, np.ndarray | None] = (None, None)  # no orientation wished for


def _turn(current: np.ndarray, wanted: np.ndarray, jw: np.ndarray) -> tuple[np.ndarray | None, np.ndarray | None]:
    """(rotation vector taking ``current`` onto ``wanted``, the angular Jacobian with the twist
    about ``current`` removed: spinning about the axis itself neither helps nor matters)."""
    cross = np.cross(current, wanted)
    sin, cos = float(np.sqrt(cross @ cross)), float(current @ wanted)
    if sin < 1e-9:  # aligned, or exactly opposite: then any perpendicular axis will do
        if cos > 0:
            return np.zeros(3), jw
        helper = np.array([1.0, 0.0, 0.0]) if abs(current[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        cross = np.cross(current, helper)
        sin = float(np.sqrt(cross @ cross))
    turn = cross / sin * np.arctan2(sin, cos)
    projector = np.eye(3) - np.outer(current, current)
    return turn, projector @ jw
