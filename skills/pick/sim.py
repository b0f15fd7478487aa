"""Simulated manipulation: IK-planned grasps played on the sim's arms, judged by the physics.

A pick is planned completely before anything moves: the object's position (where perception
placed it when the request carries one, else the world's) goes into the torso frame, both the reach pre-check and the
IK solver (``pin`` or ``placo``) must succeed for the pre-grasp (10 cm above and 8 cm in front,
the original system's approach), the grasp and the lift; otherwise the pick fails with
``unreachable`` and the arm never moves. Then: approach, descend, close the hand, lift, and the
world's physics decides: the object must rise at least 5 cm with the hand.

The optional confirmation gate (the original system's safety step) holds a planned pick until a
``confirm`` command names it; the planned joint targets are in the accepted reply for display.

Options: ``world`` (socket path, required), ``solver`` (pin | placo, default pin),
``confirm`` (default false in the sim), ``lift_check`` (0.05 m), ``grasp_dz`` (0.03 m: grasp this far
above the object's centre).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from stuart_bt.core.clock import Clock
from stuart_bt.core.world import Pose
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, DaemonError, Delivered, Done, Handler, Progress
from stuart_bt.sim.robot import description as desc
from stuart_bt.sim.world.client import WorldClient, WorldError

from .backend import PickBackend
from .ik import IKResult, as_arm, check_reachable
from .solvers import make_solver

TORSO_HEIGHT = desc.PELVIS_HEIGHT + desc.WAIST_HEIGHT  # torso_link above the floor, waist at zero
PRE_GRASP = np.array([-0.08, 0.0, 0.10])  # 8 cm in front (towards the robot), 10 cm above
LIFT = np.array([0.0, 0.0, 0.10])
DEFAULT_REST_HEIGHT = 0.1  # m: object origin above its surface, when it was not picked here
PLACE_CLEARANCE = 0.01  # m: let go this far above the surface
PLACE_REACH_IN = (0.06, 0.03, 0.0)  # m: put things down further in than carried, if reachable


def world_to_torso(p: np.ndarray, base: Pose) -> np.ndarray:
    """A map-frame point in the torso_link frame (REP-103; the waist is held at zero)."""
    dx, dy = p[0] - base.x, p[1] - base.y
    c, s = math.cos(base.yaw), math.sin(base.yaw)
    return np.array([c * dx + s * dy, -s * dx + c * dy, p[2] - TORSO_HEIGHT])


def torso_to_world(p: np.ndarray, base: Pose) -> np.ndarray:
    c, s = math.cos(base.yaw), math.sin(base.yaw)
    return np.array([base.x + c * p[0] - s * p[1], base.y + s * p[0] + c * p[1], p[2] + TORSO_HEIGHT])


class Phased(Activity):
    """A manipulation as a list of phases (name, world command, seconds); each phase waits its
    time and for the arms to be idle, then the next one starts."""

    resource = "arms"

    def __init__(self, backend: SimPick, phases: list[tuple[str, str, dict[str, Any], float]],
                 result: dict[str, Any], gate: bool = False, planned: dict[str, Any] | None = None) -> None:
        self.backend = backend
        self.phases = phases
        self.result = result
        self.awaiting_confirm = gate
        self.planned = planned or {}
        self.index = -1
        self.phase_end = 0.0

    def start(self, now: float) -> dict[str, Any]:
        self.backend.active = self
        if not self.awaiting_confirm:
            self._next_phase(now)
        return {"awaiting_confirm": self.awaiting_confirm, "planned": self.planned}

    def confirm(self) -> None:
        self.awaiting_confirm = False

    def _next_phase(self, now: float) -> Progress | None:
        self.index += 1
        if self.index >= len(self.phases):
            return None
        name, cmd, args, seconds = self.phases[self.index]
        self.backend.call(cmd, **args)
        self.phase_end = now + seconds
        return Progress({"phase": name})

    def next_due(self) -> float | None:
        return None if self.awaiting_confirm or self.index < 0 else self.phase_end

    def poll(self, now: float) -> Progress | Done | None:
        if self.awaiting_confirm:
            return None
        if self.index < 0:
            return self._next_phase(now)
        if now < self.phase_end or any(self.backend.call("state").get("arm_busy", {}).values()):
            return None
        if self.index == len(self.phases) - 1:
            self.backend.active = None
            return Done(self.backend.finish(self.result))
        return self._next_phase(now)

    def cancel(self, now: float) -> dict[str, Any]:
        self.backend.call("arm_stop")
        self.backend.active = None
        phase = self.phases[self.index][0] if self.index >= 0 else "waiting for confirm"
        return {"phase": phase}


class SimPick(PickBackend):
    name = "sim"

    def __init__(self, clock: Clock, options: dict[str, Any]) -> None:
        super().__init__(clock, options)
        if "world" not in options:
            raise ValueError("the sim pick backend needs the world's socket path (option 'world')")
        self.world = WorldClient(options["world"])
        self.solver = make_solver(str(options.get("solver", "pin")))
        self.gate = bool(options.get("confirm", False))
        self.lift_check = float(options.get("lift_check", 0.05))
        self.grasp_dz = float(options.get("grasp_dz", 0.03))
        self.rest_height: dict[str, float] = {}  # label -> origin height above the surface it stood on
        self.active: Phased | None = None
        self._lifted_from: float | None = None

    def commands(self) -> dict[str, Handler]:
        return {**super().commands(), "confirm": self._confirm_command}

    def call(self, cmd: str, **args: Any) -> dict[str, Any]:
        try:
            return self.world.call(cmd, **args)
        except WorldError as e:
            raise DaemonError("backend_error", f"world {cmd}: {e}") from None

    # -- pick ------------------------------------------------------------------------------------
    def pick(self, label: str, arm: str, robot_pose: Pose, position: dict[str, float] | None = None) -> Activity:
        state = self.call("state")
        if any(state.get("held", {}).values()):
            held = next(v for v in state["held"].values() if v)
            raise DaemonError("already_holding", f"already holding {held!r}; release it first")
        base = Pose.from_dict(state["base"])
        obj = _object(state, label)
        if position is not None:  # aim where the camera saw it; the physics still judges the grasp
            obj = {**obj, **position}
        # grasp the upper body of the object, where a hand closes around a bottle or a cup
        target = world_to_torso(np.array([obj["x"], obj["y"], obj["z"] + self.grasp_dz]), base)
        side = as_arm(("left" if target[1] >= 0 else "right") if arm == "auto" else arm)
        waypoints = {"pre_grasp": target + PRE_GRASP, "grasp": target, "lift": target + LIFT}
        for name, point in waypoints.items():
            reason = check_reachable(side, point)
            if reason:
                raise DaemonError("unreachable", f"{label} {name}: {reason}", data={"target_torso": target.tolist()})
        joints = state.get("joints", {})
        seed = {j: float(joints[j]) for j in desc.arm_joints(side) if j in joints}
        solutions: dict[str, IKResult] = {}
        for name, point in waypoints.items():
            result = self.solver.solve(side, point, seed)
            if not result.success:
                raise DaemonError("unreachable", f"{label} {name}: no arm configuration: {result.reason}",
                                  data={"target_torso": target.tolist()})
            solutions[name] = result
            seed = result.q
        self._lifted_from = float(obj["z"])
        self.rest_height[label] = float(obj["z"]) - self.call("surface", x=obj["x"], y=obj["y"])["z"]
        phases: list[tuple[str, str, dict[str, Any], float]] = [
            ("approach", "arm_trajectory",
             {"points": [{"t": 1.5, "joints": solutions["pre_grasp"].q}], "id": "approach"}, 1.5),
            ("descend", "arm_trajectory",
             {"points": [{"t": 1.0, "joints": solutions["grasp"].q}], "id": "descend"}, 1.0),
            ("close", "hand", {"side": side, "closed": True}, 0.6),
            ("lift", "arm_trajectory", {"points": [{"t": 1.0, "joints": solutions["lift"].q}], "id": "lift"}, 1.0),
        ]
        planned = {"arm": side, "target_torso": [round(v, 4) for v in target],
                   "joints": {k: round(v, 4) for k, v in solutions["grasp"].q.items()}}
        return Phased(self, phases, {"object": label, "arm": side}, gate=self.gate, planned=planned)

    def finish(self, result: dict[str, Any]) -> dict[str, Any]:
        """Judge a pick or release by the physics: what the hand holds and where the object is."""
        state = self.call("state")
        label, side = result["object"], result["arm"]
        obj = state.get("objects", {}).get(label)
        position = {k: round(float(obj[k]), 4) for k in ("x", "y", "z")} if obj else None
        if result.get("releasing"):
            return {"object": label, "arm": side, "position": position, "surface": result.get("surface")}
        held = state.get("held", {}).get(side)
        rise = (obj["z"] - self._lifted_from) if obj and self._lifted_from is not None else 0.0
        if held != label or rise < self.lift_check:
            self.call("hand", side=side, closed=False)
            raise DaemonError("backend_error", f"grasp failed: {label} rose {rise * 100:.1f} cm "
                              f"(needs {self.lift_check * 100:.0f} cm); hand holds {held!r}",
                              data={"position": position})
        return {"object": label, "arm": side, "position": position, "rise": round(rise, 4)}

    def _confirm_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, (), "confirm")
        if self.active is None or not self.active.awaiting_confirm:
            raise DaemonError("not_found", "no pick is waiting for confirmation")
        self.active.confirm()
        return Delivered(0.0, {"confirmed": True})

    # -- release ---------------------------------------------------------------------------
    def release(self, arm: str, robot_pose: Pose) -> Activity:
        """Put the held object down on the surface under it (table, bench), planned like a pick:
        the lowering target must pass the reach check and IK before the arm moves, else the
        robot keeps holding and says why (the floor is out of a standing G1's reach)."""
        state = self.call("state")
        held = {s: v for s, v in state.get("held", {}).items() if v}
        side = as_arm(arm if arm != "auto" else next(iter(held), "right"))
        if side not in held:
            raise DaemonError("not_holding", f"the {side} hand holds nothing")
        label = held[side]
        obj = state["objects"][label]
        surface = self.call("surface", x=obj["x"], y=obj["y"])
        drop = surface["z"] + self.rest_height.get(label, DEFAULT_REST_HEIGHT) + PLACE_CLEARANCE - obj["z"]
        base = Pose.from_dict(state["base"])
        hand = np.array(state["hand_points"][side], dtype=float) + np.array([0.0, 0.0, drop])
        where = f"on the {surface['geom'].replace('_', ' ')} ({surface['z']:.2f} m)"
        joints = state.get("joints", {})
        seed = {j: float(joints[j]) for j in desc.arm_joints(side) if j in joints}
        reason: str | None = None
        for reach_in in PLACE_REACH_IN:  # a little further in, away from the edge, when the arm allows
            target = world_to_torso(hand, base) + np.array([reach_in, 0.0, 0.0])
            reason = check_reachable(side, target)
            if reason is None:
                result = self.solver.solve(side, target, seed)
                reason = None if result.success else result.reason
            if reason is None:
                break
        if reason is not None:
            raise DaemonError("unreachable", f"cannot put the {label} down {where} from here: {reason}")
        neutral = {j: desc.NEUTRAL[j] for j in desc.arm_joints(side)}
        phases: list[tuple[str, str, dict[str, Any], float]] = [
            ("lower", "arm_trajectory", {"points": [{"t": 1.2, "joints": result.q}], "id": "lower"}, 1.2),
            ("open", "hand", {"side": side, "closed": False}, 0.6),
            ("retract", "arm_trajectory", {"points": [{"t": 1.5, "joints": neutral}], "id": "retract"}, 1.5),
        ]
        return Phased(self, phases, {"object": label, "arm": side, "releasing": True, "surface": surface["geom"]})

    def state(self) -> dict[str, Any]:
        return {"active": self.active.result.get("object") if self.active else None,
                "awaiting_confirm": bool(self.active and self.active.awaiting_confirm)}

    def stop(self) -> None:
        self.call("arm_stop")

    def close(self) -> None:
        self.world.close()


def _object(state: dict[str, Any], label: str) -> dict[str, float]:
    objects = state.get("objects", {})
    if label not in objects:
        from stuart_bt.core.suggest import did_you_mean

        raise DaemonError("not_found", f"no object {label!r} in the world{did_you_mean(label, objects)}")
    return objects[label]
