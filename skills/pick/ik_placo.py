"""PlaCo IK: PlaCo's kinematics QP on the robot from sim/models/g1.urdf, one arm unmasked.

Why PlaCo as the second solver: it treats joint limits as QP constraints rather than by
projection, and it is what a whole-body controller (waist, both arms) would grow from. Each
``solve(apply=True)`` is one constrained Gauss-Newton step, each joint's change bounded to
0.5 rad through PlaCo's velocity limits (unbounded steps overshoot and cycle far from the
target); the loop repeats it until the hand point is within :data:`ik.CONVERGED` of it.
The floating base PlaCo adds is masked and put at the pelvis, so PlaCo's world is the URDF
root; every joint but the arm's seven is masked.

The orientation wish is a soft axis-alignment task with a small weight; if it still pulls the
hand off the target (a wish the limits cannot grant), a position-only pass follows.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import placo

from stuart_bt.sim.robot import URDF_PATH

from .ik import CONVERGED, TARGET_AXES, Arm, IKSolver, Orientation
from .ik_arm import ArmChain, chain

ORIENTATION_WEIGHT = 0.05  # relative to the position task's 1.0
REGULARISATION = 1e-6  # keeps the QP well posed near full stretch
MAX_STEP = 0.5  # rad per joint per iteration (as the pin solver): bounds via velocity limits x dt
STEP_DT = 0.02  # s: only the product with the velocity bound matters


class _ArmProblem:
    """A robot and one kinematics solver per orientation wish, for one arm."""

    def __init__(self, arm: Arm, ch: ArmChain) -> None:
        self.arm = arm
        self.frame = f"{arm}_hand_point"
        self.robot = placo.RobotWrapper(str(URDF_PATH), placo.Flags.ignore_collisions)
        self.robot.set_T_world_fbase(np.eye(4))
        self.joints = ch.joints
        for name in self.joints:  # full Gauss-Newton steps overshoot far from the target and cycle
            self.robot.set_velocity_limit(name, MAX_STEP / STEP_DT)
        self.solvers: dict[Orientation, tuple[placo.KinematicsSolver, object]] = {}

    def solver(self, orientation: Orientation) -> tuple[placo.KinematicsSolver, Any]:
        """(solver, its position task), built on first use."""
        if orientation not in self.solvers:
            solver = placo.KinematicsSolver(self.robot)
            solver.mask_fbase(True)
            for name in self.robot.joint_names():
                if name not in self.joints:
                    solver.mask_dof(name)
            solver.enable_joint_limits(True)
            solver.dt = STEP_DT
            solver.enable_velocity_limits(True)
            task = solver.add_position_task(self.frame, np.zeros(3))
            task.configure(f"{self.frame}_position", "soft", 1.0)
            if orientation:
                local, torso_axis = TARGET_AXES[self.arm][orientation]
                align = solver.add_axisalign_task(self.frame, local, torso_axis)  # torso axes = root axes at waist 0
                align.configure(f"{self.frame}_{orientation}", "soft", ORIENTATION_WEIGHT)
            solver.add_regularization_task(REGULARISATION)
            self.solvers[orientation] = (solver, task)
        return self.solvers[orientation]

    def set(self, q: np.ndarray) -> None:
        for name, value in zip(self.joints, q, strict=True):
            self.robot.set_joint(name, float(value))
        self.robot.update_kinematics()

    def get(self) -> np.ndarray:
        return np.array([self.robot.get_joint(name) for name in self.joints])

    def error(self, goal: np.ndarray) -> float:
        return float(np.linalg.norm(goal - self.robot.get_T_world_frame(self.frame)[:3, 3]))


class PlacoSolver(IKSolver):
    name = "placo"

    def __init__(self, max_iterations: int = 40, restarts: int = 6, seed: int = 0) -> None:
        self.max_iterations = max_iterations
        self.restarts = restarts
        self.seed = seed
        self._problems: dict[str, _ArmProblem] = {}

    def chain(self, arm: Arm) -> ArmChain:
        return chain(arm)

    def _problem(self, arm: Arm) -> _ArmProblem:
        if arm not in self._problems:
            self._problems[arm] = _ArmProblem(arm, self.chain(arm))
        return self._problems[arm]

    def _solve(self, arm: Arm, target: np.ndarray, seed: np.ndarray,
               orientation: Orientation) -> tuple[np.ndarray, int, str]:
        ch = self.chain(arm)
        problem = self._problem(arm)
        goal = ch.to_root(target)
        return self._best_of_restarts(
            ch, seed, lambda start, oriented: self._descend(problem, goal, start, orientation if oriented else None),
            bool(orientation))

    def _descend(self, problem: _ArmProblem, goal: np.ndarray, q: np.ndarray,
                 orientation: Orientation) -> tuple[np.ndarray, float, int]:
        solver, task = problem.solver(orientation)
        task.target_world = goal
        problem.set(q)
        error = problem.error(goal)
        best_error, stalled, steps, settle = error, 0, 0, 0
        while steps < self.max_iterations:
            if error <= CONVERGED:
                settle += 1  # once there, a few more steps let a soft orientation wish settle
                if not orientation or settle > 3:
                    break
            solver.solve(True)
            problem.robot.update_kinematics()
            steps += 1
            error = problem.error(goal)
            if error < best_error * 0.99:
                best_error, stalled = error, 0
            elif error > CONVERGED:
                stalled += 1
                if stalled >= 8:
                    break
        return problem.get(), error, steps
