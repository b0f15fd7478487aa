"""What every gesture backend offers: play library gestures (one or a sequence) or keyframes.

Names are resolved against :mod:`stuart_bt.core.gestures` here, so every backend rejects an unknown
gesture the same way, with a suggestion, before anything moves.
"""

from __future__ import annotations

from abc import abstractmethod
from dataclasses import dataclass
from typing import Any

from stuart_bt.core import gestures
from stuart_bt.core.suggest import did_you_mean
from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, Backend, DaemonError, Handler

UNKNOWN_GESTURE_VENDOR_CODE = 7402  # in the arm service's 74xx error range


@dataclass(frozen=True)
class Keyframe:
    """Joint targets (radians, by G1 joint name) to reach ``t`` seconds after the start."""

    t: float
    joints: dict[str, float]


class GestureBackend(Backend):
    family = "gesture"

    @abstractmethod
    def play(self, sequence: list[gestures.Gesture]) -> Activity:
        """Play library gestures one after another (a single gesture is a sequence of one)."""

    @abstractmethod
    def play_keyframes(self, keyframes: list[Keyframe]) -> Activity:
        """Move the arms through recorded keyframes."""

    def commands(self) -> dict[str, Handler]:
        return {"play": self._play_command}

    def _play_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("name", "sequence", "keyframes"), "play")
        which = a.one_of(args, ("name", "sequence", "keyframes"), "play")
        if which == "name":
            return self.play([find_gesture(a.string(args, "name", "play"))])
        if which == "sequence":
            names = args["sequence"]
            if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
                raise a.bad("play", f"'sequence' must be a non-empty list of gesture names, got {names!r}")
            return self.play([find_gesture(n) for n in names])
        return self.play_keyframes(parse_keyframes(args["keyframes"]))


def find_gesture(name: str) -> gestures.Gesture:
    gesture = gestures.lookup(name)
    if gesture is None:
        raise DaemonError("unknown_gesture", f"no gesture {name!r}{did_you_mean(name, gestures.names())}",
                          vendor_code=UNKNOWN_GESTURE_VENDOR_CODE)
    return gesture


def parse_keyframes(value: Any) -> list[Keyframe]:
    if not isinstance(value, list) or not value:
        raise a.bad("play", f"'keyframes' must be a non-empty list, got {value!r}")
    frames: list[Keyframe] = []
    for i, frame in enumerate(value):
        where = f"play keyframes[{i}]"
        if not isinstance(frame, dict):
            raise a.bad(where, f"must be an object with 't' and 'joints', got {frame!r}")
        a.only_known(frame, ("t", "joints"), where)
        t = a.number(frame, "t", where, minimum=frames[-1].t if frames else 0.0)
        joints = a.mapping(frame, "joints", where)
        frames.append(Keyframe(t, {name: a.number(joints, name, f"{where} joints") for name in joints}))
    return frames
