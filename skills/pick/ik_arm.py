"""One arm as a 7-joint Pinocchio chain from sim/models/g1.urdf, working in torso_link.

Both IK solvers seed, check limits and verify through this: the verdict on a result never
depends on the solver that produced it. Every joint outside the arm is locked at zero, so the
torso_link frame sits at a constant pose in the reduced model's root (the pelvis) and torso
coordinates are one fixed transform away.
"""

from __future__ import annotations

import functools

import numpy as np
import pinocchio as pin

from stuart_bt.core.suggest import did_you_mean
from stuart_bt.sim.robot import NEUTRAL, URDF_PATH, arm_joints

from .ik import as_arm


@functools.lru_cache(maxsize=1)
def full_model() -> pin.Model:
    return pin.buildModelFromUrdf(str(URDF_PATH))


class ArmChain:
    """Forward kinematics, Jacobians and limits of one arm, positions in torso_link."""

    def __init__(self, arm: str) -> None:
        model = full_model()
        self.arm = arm
        self.joints: tuple[str, ...] = arm_joints(as_arm(arm))
        locked = [model.getJointId(n) for n in model.names[1:] if n not in self.joints]
        self.model = pin.buildReducedModel(model, locked, pin.neutral(model))
        self.data = self.model.createData()
        order = [self.model.names[i] for i in range(1, self.model.njoints)]
        if tuple(order) != self.joints:
            raise RuntimeError(f"unexpected joint order in the reduced {arm} arm: {order}")
        self.lower = self.model.lowerPositionLimit.copy()
        self.upper = self.model.upperPositionLimit.copy()
        self.hand = self.model.getFrameId(f"{arm}_hand_point")
        torso = self.model.getFrameId("torso_link")
        pin.framesForwardKinematics(self.model, self.data, pin.neutral(self.model))
        self.root_to_torso = self.data.oMf[torso].copy()  # constant: nothing between them moves
        self.torso_rotation_t = self.root_to_torso.rotation.T.copy()
        self.torso_translation = self.root_to_torso.translation.copy()
        self.neutral = np.array([NEUTRAL[n] for n in self.joints])

    # --- conversions ----------------------------------------------------------------------
    def vector(self, q: dict[str, float] | None) -> np.ndarray:
        """Joint dict -> vector; missing joints from NEUTRAL; unknown names refused (a typo
        would otherwise silently seed from neutral)."""
        out = self.neutral.copy()
        for name, value in (q or {}).items():
            if name not in self.joints:
                if name.startswith(f"{self.arm}_") and not name.startswith(f"{self.arm}_hand_"):
                    raise ValueError(f"unknown {self.arm} arm joint {name!r}{did_you_mean(name, self.joints)}")
                continue  # the other arm, the hands, the waist: not this solver's business
            out[self.joints.index(name)] = float(value)
        return out

    def named(self, q: np.ndarray) -> dict[str, float]:
        return {n: float(v) for n, v in zip(self.joints, q, strict=True)}

    def to_root(self, p_torso: np.ndarray) -> np.ndarray:
        return self.root_to_torso.rotation @ p_torso + self.torso_translation

    # --- kinematics ---------------------------------------------------------------------------
    def position(self, q: np.ndarray) -> np.ndarray:
        """Hand point in torso_link."""
        pin.framesForwardKinematics(self.model, self.data, q)
        return self.torso_rotation_t @ (self.data.oMf[self.hand].translation - self.torso_translation)

    def rotation(self, q: np.ndarray) -> np.ndarray:
        """Hand-point frame orientation in torso_link."""
        pin.framesForwardKinematics(self.model, self.data, q)
        return self.torso_rotation_t @ self.data.oMf[self.hand].rotation

    def jacobian(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(hand position in root, 3x7 linear and 3x7 angular Jacobian in root axes, hand rotation
        in root): one kinematics pass for everything an iteration needs."""
        j = pin.computeFrameJacobian(self.model, self.data, q, self.hand, pin.LOCAL_WORLD_ALIGNED)
        m = self.data.oMf[self.hand]
        return m.translation, j[:3], j[3:], m.rotation

    def axis_error(self, q: np.ndarray, axis_local: np.ndarray, target_torso: np.ndarray) -> float:
        """Angle (rad) between a hand-frame axis and where it should point."""
        current = self.rotation(q) @ axis_local
        return float(np.arccos(np.clip(current @ target_torso, -1.0, 1.0)))

    # --- limits -------------------------------------------------------------------------------
    def clip(self, q: np.ndarray) -> np.ndarray:
        return np.clip(q, self.lower, self.upper)

    def outside_limits(self, q: np.ndarray, slack: float = 0.0) -> list[str]:
        """Joints out of range, each with its value and limits."""
        return [f"{n}={v:.4f} not in [{lo:.4f}, {hi:.4f}]"
                for n, v, lo, hi in zip(self.joints, q, self.lower, self.upper, strict=True)
                if v < lo - slack or v > hi + slack]

    def random(self, rng: np.random.Generator, margin: float = 0.1) -> np.ndarray:
        """A configuration drawn uniformly inside the limits (a restart seed)."""
        return rng.uniform(self.lower + margin, self.upper - margin)


@functools.lru_cache(maxsize=2)
def chain(arm: str) -> ArmChain:
    """The shared chain of ``arm`` (built once per process)."""
    return ArmChain(arm)
