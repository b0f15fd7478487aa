"""Low-level arm and hand commands for the G1: joint targets on ``rt/arm_sdk`` at 50 Hz, blended in.

The G1's walking controller owns the arms until a program asks for them: on ``rt/arm_sdk`` the
q of motor 29 is the blend weight (0: the controller's arms, 1: ours), so every program ramps the
weight in before it moves and out when it lets go, and the arms never jump. Each message carries
the CRC the robot checks. Dex3-1 hand targets go to ``rt/dex3/{left,right}/cmd`` with the same
cadence while a program runs.

A thread publishes, so the cadence holds whatever the daemon loop is doing, and a cancelled or
stopped program still ramps out. Used by the unitree gesture and pick backends only (daemon
processes: it imports the vendor SDK).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Mapping
from dataclasses import dataclass
from itertools import pairwise

from unitree_sdk2py.idl.default import unitree_hg_msg_dds__HandCmd_, unitree_hg_msg_dds__LowCmd_
from unitree_sdk2py.idl.unitree_hg.msg.dds_ import HandCmd_, LowCmd_
from unitree_sdk2py.utils.crc import CRC

from stuart_bt.sim.robot import description as desc
from stuart_bt.skills import vendor

ARM_SDK_TOPIC = "rt/arm_sdk"
HAND_TOPIC = "rt/dex3/{side}/cmd"
WEIGHT_MOTOR = 29
RATE = 50.0  # Hz, the rate the vendor's arm examples use
ARM_KP, ARM_KD = 60.0, 1.5
HAND_KP, HAND_KD = 1.5, 0.1
HAND_ENABLE = 0x01  # Dex3 motor mode: id in bits 0-3, status (1 = enabled) in bits 4-6

MOTOR_INDEX: dict[str, int] = {
    **{name: 12 + i for i, name in enumerate(desc.WAIST_JOINTS)},
    **{f"left_{kind}_joint": 15 + i for i, kind in enumerate(desc.ARM_JOINT_KINDS)},
    **{f"right_{kind}_joint": 22 + i for i, kind in enumerate(desc.ARM_JOINT_KINDS)},
}
"""G1 motor order on the low-level bus (FIELD_NOTES): waist 12-14, left arm 15-21, right arm 22-28."""

Targets = dict[str, float]
ARM_REST: Targets = {j: desc.NEUTRAL[j] for side in desc.SIDES for j in desc.arm_joints(side)}
"""Targets for arm joints a program does not name: the neutral pose (arms down by the sides)."""


@dataclass(frozen=True)
class Program:
    """Joint targets over time: ramp the weight in, follow keyframes, then ramp out or hold.

    ``frames`` are ``(seconds after the ramp-in, targets)``, times non-decreasing."""

    frames: tuple[tuple[float, Targets], ...]
    ramp: float
    hold: bool = False
    weight_from: float = 0.0

    @property
    def length(self) -> float:
        """Seconds until the program ends (a holding program never ends by itself)."""
        return self.ramp + self.frames[-1][0] + (0.0 if self.hold else self.ramp)

    def at(self, t: float) -> tuple[float, Targets]:
        """(blend weight, joint targets) ``t`` seconds after the start."""
        end = self.ramp + self.frames[-1][0]
        if t < self.ramp:
            weight = self.weight_from + (1.0 - self.weight_from) * t / self.ramp if self.ramp > 0 else 1.0
        elif t <= end or self.hold:
            weight = 1.0
        else:
            weight = max(0.0, 1.0 - (t - end) / self.ramp) if self.ramp > 0 else 0.0
        return weight, interpolate(self.frames, t - self.ramp)


def interpolate(frames: tuple[tuple[float, Targets], ...], t: float) -> Targets:
    """Linear interpolation between keyframes; before the first and after the last, hold them."""
    if t <= frames[0][0]:
        return dict(frames[0][1])
    for (t0, q0), (t1, q1) in pairwise(frames):
        if t <= t1:
            f = 0.0 if t1 <= t0 else (t - t0) / (t1 - t0)
            return {j: q0.get(j, q1[j]) + (q1[j] - q0.get(j, q1[j])) * f for j in q1} | \
                {j: v for j, v in q0.items() if j not in q1}
    return dict(frames[-1][1])


class ArmStreamer:
    """The publishing thread. ``play`` starts a program; ``ramp_out`` lets go from wherever the
    arms are; ``finished`` says the current program has run to its end."""

    def __init__(self, ramp: float = 0.5, rate: float = RATE) -> None:
        self.ramp = ramp
        self.period = 1.0 / rate
        self._arm = vendor.publisher(ARM_SDK_TOPIC, LowCmd_)
        self._hands = {side: vendor.publisher(HAND_TOPIC.format(side=side), HandCmd_) for side in desc.SIDES}
        self._crc = CRC()
        self._lock = threading.Lock()
        self._program: Program | None = None
        self._started = 0.0
        self._last: tuple[float, Targets] = (0.0, {})
        self._closing = False
        self._thread = threading.Thread(target=self._run, name="arm_sdk", daemon=True)
        self._thread.start()

    # -- control (daemon loop) --------------------------------------------------------------------
    def play(self, frames: list[tuple[float, Targets]], hold: bool = False) -> Program:
        """Start a program from the current blend weight (already 1 when a held pose continues)."""
        with self._lock:
            weight, _ = self._last
            ramp = self.ramp * (1.0 - weight)
            program = Program(tuple(frames), ramp, hold, weight)
            self._program, self._started = program, time.monotonic()
        return program

    def ramp_out(self) -> None:
        """Let go now: hold the last targets and ramp the weight from where it is to 0."""
        with self._lock:
            weight, targets = self._last
            if self._program is None or weight <= 0.0:
                self._program = None
                return
            ramp = self.ramp * weight
            self._program = _RampOut(((0.0, targets),), ramp, False, weight)
            self._started = time.monotonic()

    def finished(self) -> bool:
        with self._lock:
            program = self._program
            return program is None or (not program.hold and time.monotonic() - self._started >= program.length)

    def settled(self) -> bool:
        """The current program has reached its last keyframe (a holding one keeps holding)."""
        with self._lock:
            program = self._program
            return program is None or time.monotonic() - self._started >= program.ramp + program.frames[-1][0]

    def targets(self) -> Targets:
        with self._lock:
            return dict(self._last[1])

    def weight(self) -> float:
        with self._lock:
            return self._last[0]

    def close(self, timeout: float = 2.0) -> None:
        """Ramp out, wait for the weight to reach 0 (bounded), stop the thread."""
        self.ramp_out()
        deadline = time.monotonic() + timeout
        while not self.finished() and time.monotonic() < deadline:
            time.sleep(self.period)
        self._closing = True
        self._thread.join(timeout=1.0)

    # -- the thread ---------------------------------------------------------------------------------
    def _run(self) -> None:
        next_tick = time.monotonic()
        while not self._closing:
            next_tick += self.period
            with self._lock:
                program, started = self._program, self._started
                if program is not None:
                    now = time.monotonic() - started
                    self._last = program.at(now)
                    if not program.hold and now >= program.length:
                        self._program = None  # the last sample (weight 0 after a ramp-out) goes out below
                weight, targets = self._last
            if program is not None:
                self._publish(weight, targets)
            time.sleep(max(0.0, next_tick - time.monotonic()))

    def _publish(self, weight: float, targets: Mapping[str, float]) -> None:
        msg = unitree_hg_msg_dds__LowCmd_()
        # every arm motor gets a target: one left at kp = kd = 0 would go limp at full weight
        for joint, q in {**ARM_REST, **targets}.items():
            index = MOTOR_INDEX.get(joint)
            if index is None:
                continue
            motor = msg.motor_cmd[index]
            motor.q, motor.dq, motor.tau, motor.kp, motor.kd = float(q), 0.0, 0.0, ARM_KP, ARM_KD
        msg.motor_cmd[WEIGHT_MOTOR].q = float(weight)
        msg.crc = self._crc.Crc(msg)
        self._arm.Write(msg)
        for side in desc.SIDES:
            joints = desc.hand_joints(side)
            if any(j in targets for j in joints):
                hand = unitree_hg_msg_dds__HandCmd_()
                for i, joint in enumerate(joints):
                    motor = hand.motor_cmd[i]
                    motor.mode = i | (HAND_ENABLE << 4)
                    motor.q, motor.kp, motor.kd = float(targets.get(joint, 0.0)), HAND_KP, HAND_KD
                self._hands[side].Write(hand)


class _RampOut(Program):
    """Hold the targets; the weight goes from ``weight_from`` down to 0 over ``ramp`` seconds."""

    @property
    def length(self) -> float:
        return self.ramp

    def at(self, t: float) -> tuple[float, Targets]:
        weight = 0.0 if self.ramp <= 0 else max(0.0, self.weight_from * (1.0 - t / self.ramp))
        return weight, dict(self.frames[0][1])
