"""Manipulation on the G1: IK-planned arm trajectories on rt/arm_sdk, Dex3-1 hands on rt/dex3/*/cmd.

A pick is planned completely before anything moves, with the simulator's solvers
(:mod:`.ik`): the reach pre-check and IK within the joint limits must succeed for the pre-grasp
(10 cm above and 8 cm in front), the grasp and the lift, else ``unreachable`` and the arm never
moves. Then, after the confirmation gate (on by default on the robot: a person confirms the
planned motion with the ``confirm`` command), the arm is blended in and moves: approach,
descend, close the hand, lift, and holds. A release lowers back to the grasp height, opens the
hand, retracts to the neutral pose and blends the arm back to the walking controller.

Objects come from the request's ``position`` (where perception saw them), else the ``objects``
option or skills/objects.json; the robot's pose comes with every request.

Options (besides the link settings in :mod:`stuart_bt.skills.vendor`): ``objects``, ``solver``
(pin | placo, default pin), ``confirm`` (default true), ``ramp`` (0.5 s blend ramp),
``grasp_dz`` (0.03 m above the object's centre).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from stuart_bt.core.clock import Clock
from stuart_bt.core.world import Pose
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, DaemonError, Done, Handler, Progress
from stuart_bt.sim.robot import description as desc
from stuart_bt.skills import vendor
from stuart_bt.skills.arm_stream import ARM_REST, ArmStreamer, Targets
from stuart_bt.skills.gesture.keyframes import hand

from .dry import DryPick, Position, _lateral
from .ik import Arm, as_arm, check_reachable
from .sim import LIFT, PRE_GRASP, torso_to_world, world_to_torso
from .solvers import make_solver

OWN_OPTIONS = ("objects", "solver", "confirm", "ramp", "grasp_dz")
Phase = tuple[str, Targets, float]  # (name, joint targets to reach, seconds)


class ArmPhases(Activity):
    """Phases streamed one after another; optionally held at a confirmation gate first."""

    resource = "arms"

    def __init__(self, backend: UnitreePick, phases: list[Phase], finish: Any, gate: bool,
                 planned: dict[str, Any], release_at_end: bool) -> None:
        self.backend = backend
        self.phases = phases
        self.finish = finish
        self.awaiting_confirm = gate
        self.planned = planned
        self.release_at_end = release_at_end
        self.index = -1

    def start(self, now: float) -> dict[str, Any]:
        self.backend.active = self
        return {"awaiting_confirm": self.awaiting_confirm, "planned": self.planned}

    def confirm(self) -> None:
        self.awaiting_confirm = False

    def poll(self, now: float) -> Progress | Done | None:
        streamer = self.backend.streamer
        if self.awaiting_confirm:
            return None
        if self.index >= 0 and not streamer.settled():
            return None
        if self.index == len(self.phases) - 1:
            if self.release_at_end and not streamer.finished():
                return None  # the last program ramps the arm back to the controller
            self.backend.active = None
            return Done(self.finish())
        self.index += 1
        name, targets, seconds = self.phases[self.index]
        last = self.release_at_end and self.index == len(self.phases) - 1
        streamer.play([(0.0, streamer.targets() or self.backend.neutral()), (seconds, targets)], hold=not last)
        return Progress({"phase": name})

    def cancel(self, now: float) -> dict[str, Any]:
        self.backend.streamer.ramp_out()
        self.backend.active = None
        return {"phase": self.phases[self.index][0] if self.index >= 0 else "waiting for confirm"}


class UnitreePick(DryPick):
    name = "unitree"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, {k: v for k, v in options.items() if k == "objects"})
        self.options = options
        self.link = vendor.link_from(options, "pick", OWN_OPTIONS)
        where = "pick unitree options"
        self.solver = vendor.startup_option(lambda: make_solver(a.string(options, "solver", where, default="pin",
                                                                         choices=("pin", "placo"))))
        self.gate = bool(options.get("confirm", True))
        self.grasp_dz = vendor.startup_option(lambda: a.number(options, "grasp_dz", where, default=0.03))
        ramp = vendor.startup_option(lambda: a.number(options, "ramp", where, default=0.5, minimum=0.05))
        vendor.connect(self.link)
        self.streamer = ArmStreamer(ramp)
        self.active: ArmPhases | None = None
        self._grasp: dict[str, Any] | None = None  # side, torso target and joint solutions of the held grasp

    def commands(self) -> dict[str, Handler]:
        return {**super().commands(), "confirm": self._confirm_command}

    def neutral(self) -> Targets:
        return dict(ARM_REST)

    # -- planning ---------------------------------------------------------------------------------
    def pick(self, label: str, arm: str, robot_pose: Pose, position: dict[str, float] | None = None) -> Activity:
        if self.held is not None:
            raise DaemonError("already_holding", f"already holding the {self.held} ({self.held_arm} arm); "
                                                 "release it first")
        at = self._aim(label, position)
        target = world_to_torso(np.array([at.x, at.y, at.z + self.grasp_dz]), robot_pose)
        side = as_arm(arm if arm != "auto" else ("left" if _lateral(robot_pose, at) >= 0 else "right"))
        points = {"pre_grasp": target + PRE_GRASP, "grasp": target, "lift": target + LIFT}
        solutions = self._solve(label, side, points, target)
        open_hand, closed = hand(side, "open"), hand(side, "grip")
        phases: list[Phase] = [
            ("approach", {**solutions["pre_grasp"], **open_hand}, 1.5),
            ("descend", {**solutions["grasp"], **open_hand}, 1.0),
            ("close", {**solutions["grasp"], **closed}, 0.6),
            ("lift", {**solutions["lift"], **closed}, 1.0),
        ]
        planned = {"arm": side, "target_torso": [round(float(v), 4) for v in target],
                   "joints": {k: round(v, 4) for k, v in solutions["grasp"].items()}}

        def finish() -> dict[str, Any]:
            self._grasp = {"side": side, "target": target, "solutions": solutions}
            return {"object": label, "arm": side, "position": self.take(label, side).to_dict()}

        return ArmPhases(self, phases, finish, self.gate, planned, release_at_end=False)

    def _solve(self, label: str, side: Arm, points: dict[str, np.ndarray], target: np.ndarray) -> dict[str, Targets]:
        """Every waypoint reachable and solved within the joint limits, or ``unreachable``."""
        for name, point in points.items():
            reason = check_reachable(side, point)
            if reason:
                raise DaemonError("unreachable", f"{label} {name}: {reason}",
                                  data={"target_torso": [round(float(v), 4) for v in target]})
        seed = {j: desc.NEUTRAL[j] for j in desc.arm_joints(side)}
        solutions: dict[str, Targets] = {}
        for name, point in points.items():
            result = self.solver.solve(side, point, seed)
            if not result.success:
                raise DaemonError("unreachable", f"{label} {name}: no arm configuration: {result.reason}",
                                  data={"target_torso": [round(float(v), 4) for v in target]})
            solutions[name] = dict(result.q)
            seed = result.q
        return solutions

    def release(self, arm: str, robot_pose: Pose) -> Activity:
        if self.held is None or self._grasp is None or arm not in ("auto", self.held_arm):
            raise DaemonError("not_holding", f"the {'robot' if arm == 'auto' else arm + ' arm'} holds nothing")
        grasp = self._grasp
        side, solutions = grasp["side"], grasp["solutions"]
        closed, open_hand = hand(side, "grip"), hand(side, "open")
        neutral = {j: desc.NEUTRAL[j] for j in desc.arm_joints(side)}
        phases: list[Phase] = [
            ("lower", {**solutions["grasp"], **closed}, 1.2),
            ("open", {**solutions["grasp"], **open_hand}, 0.6),
            ("retract", {**neutral, **open_hand}, 1.5),
        ]
        label = self.held

        def finish() -> dict[str, Any]:
            where = torso_to_world(grasp["target"] - np.array([0.0, 0.0, self.grasp_dz]), robot_pose)
            self.objects[label] = Position(*(float(v) for v in where))
            self.held = self.held_arm = self._held_from = self._grasp = None
            return {"object": label, "arm": side, "position": self.objects[label].to_dict()}

        return ArmPhases(self, phases, finish, False, {"arm": side}, release_at_end=True)

    def _confirm_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, (), "confirm")
        if self.active is None or not self.active.awaiting_confirm:
            raise DaemonError("not_found", "no pick is waiting for confirmation")
        self.active.confirm()
        return _Confirmed()

    # -- safety -----------------------------------------------------------------------------------
    def stop(self) -> None:
        """Blend the arms back to the walking controller (the hand keeps its grip)."""
        self.streamer.ramp_out()

    def state(self) -> dict[str, Any]:
        return {**super().state(), "awaiting_confirm": bool(self.active and self.active.awaiting_confirm)}

    def close(self) -> None:
        self.streamer.close()


class _Confirmed(Activity):
    resource = None

    def poll(self, now: float) -> Done:
        return Done({"confirmed": True})

    def cancel(self, now: float) -> None:
        return None
