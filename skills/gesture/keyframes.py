"""Keyframe trajectories for the library gestures on the sim's arms and Dex3-1 hands, their
validation, and the recorded-gesture file format.

Why here and as data: the vendor plays its arm actions (ids in :mod:`stuart_bt.core.gestures`)
inside the robot; the simulator has to play something that looks like them, and recorded
custom gestures use the same shape. Poses were designed with the sim model's forward
kinematics (hand positions and palm directions noted next to each) and are kept as literal
joint angles so that a gesture is the same on every run.

Every frame names all 28 arm and hand joints. A trajectory starts at :data:`NEUTRAL` (arms
down by the sides, hands open; a player blends from wherever the arms really are into the
first frame) and ends there, except that gestures that *hold* end in their held pose, and
"release arm" goes from a given pose (the held one) back to neutral. ``t`` is seconds after
the start; the last ``t`` is the library's duration.

Conventions (the model's, which are the vendor's): shoulder pitch < 0 raises the arm forward;
shoulder roll > 0 swings the left arm out (the right arm: < 0); elbow 0 is a right angle with
the forearm forward, pi/2 a straight arm. Poses are written for the left arm and mirrored
(roll, yaw, wrist roll, wrist yaw change sign) unless a gesture is one-sided.

File format: ``{"name": str, "keyframes": [{"t": s, "joints": {joint name: rad}}]}``.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from stuart_bt.core import gestures
from stuart_bt.core.errors import StuartError
from stuart_bt.core.jsonfile import is_finite_number, to_json
from stuart_bt.core.suggest import did_you_mean
from stuart_bt.sim.robot import description as desc

from .backend import Keyframe

Pose = dict[str, float]
ArmValues = tuple[float, float, float, float, float, float, float]  # desc.ARM_JOINT_KINDS order

NEUTRAL: Pose = {name: desc.NEUTRAL[name] for side in desc.SIDES
                 for name in (*desc.arm_joints(side), *desc.hand_joints(side))}
"""Arms down by the sides, elbows a little bent, hands open (the model's neutral pose)."""

GESTURE_JOINTS: tuple[str, ...] = tuple(NEUTRAL) + desc.WAIST_JOINTS
"""Joints a keyframe may name: both arms, both hands, the waist (never the base)."""

# --- building blocks ----------------------------------------------------------------------------

_MIRRORED_ARM = {"shoulder_roll", "shoulder_yaw", "wrist_roll", "wrist_yaw"}
# Dex3-1: thumb_0 turns about +x on the left and -x on the right, so the same value is the
# mirror image; the other joints close with opposite signs on the two hands.
_SAME_SIGN_HAND = {"thumb_0"}

# Left-hand shapes (rad); the right hand gets the mirror image.
HAND_SHAPES: dict[str, dict[str, float]] = {
    "open": {kind: 0.0 for kind in desc.HAND_JOINT_KINDS},
    "relaxed": {"thumb_0": 0.0, "thumb_1": 0.2, "thumb_2": 0.3, "index_0": -0.3, "index_1": -0.3,
                "middle_0": -0.3, "middle_1": -0.3},
    "curl": {"thumb_0": 0.0, "thumb_1": 0.3, "thumb_2": 0.6, "index_0": -0.7, "index_1": -0.9,
             "middle_0": -0.7, "middle_1": -0.9},  # the heart's curved fingers
    "grip": {"thumb_0": 0.3, "thumb_1": 0.4, "thumb_2": 0.6, "index_0": -0.6, "index_1": -0.6,
             "middle_0": -0.6, "middle_1": -0.6},  # a handshake
}

NEUTRAL_ARM: ArmValues = tuple(desc.NEUTRAL[f"left_{k}_joint"] for k in desc.ARM_JOINT_KINDS)  # type: ignore[assignment]


def mirror(values: ArmValues) -> ArmValues:
    """The other arm's angles for the mirror-image pose."""
    return tuple(-v if kind in _MIRRORED_ARM else v
                 for kind, v in zip(desc.ARM_JOINT_KINDS, values, strict=True))  # type: ignore[return-value]


def arm(side: str, values: ArmValues) -> Pose:
    return {f"{side}_{kind}_joint": float(v) for kind, v in zip(desc.ARM_JOINT_KINDS, values, strict=True)}


def hand(side: str, shape: str) -> Pose:
    left = HAND_SHAPES[shape]
    sign = {kind: 1.0 if side == "left" or kind in _SAME_SIGN_HAND else -1.0 for kind in desc.HAND_JOINT_KINDS}
    return {f"{side}_hand_{kind}_joint": sign[kind] * left[kind] + 0.0 for kind in desc.HAND_JOINT_KINDS}


def pose(left: ArmValues | None = None, right: ArmValues | None = None, left_hand: str = "open",
         right_hand: str = "open") -> Pose:
    """A whole-body gesture pose. ``left`` is in left-arm terms, ``right`` in right-arm terms
    (use :func:`mirror` to copy a left pose across); ``None`` keeps that arm neutral."""
    return {**arm("left", left or NEUTRAL_ARM), **arm("right", right or mirror(NEUTRAL_ARM)),
            **hand("left", left_hand), **hand("right", right_hand)}


def both(values: ArmValues, shape: str = "open") -> Pose:
    """The same pose on both arms (right mirrored)."""
    return pose(values, mirror(values), shape, shape)


def nudge(values: ArmValues, **changes: float) -> ArmValues:
    """``values`` with some joints moved by the given amounts (``elbow=0.3``)."""
    out = list(values)
    for kind, delta in changes.items():
        out[desc.ARM_JOINT_KINDS.index(kind)] += delta
    return tuple(out)  # type: ignore[return-value]


# --- the poses (designed with the model's FK; hand point positions in torso_link) ------------

# high wave, right arm: upper arm out and up, forearm up, palm forward; hand (0.05, -0.30, 0.52).
# The elbow swings the hand ~9 cm either way in y.
WAVE_R: ArmValues = (-0.25, -1.85, -0.94, 0.4, 0.17, -0.17, -0.33)
# face wave, right: hand in front of the right cheek (0.20, -0.15, 0.38), palm forward, fingers up;
# shoulder yaw swings it sideways ~7 cm.
FACE_WAVE_R: ArmValues = (-1.0, -0.33, -0.03, -0.31, -1.25, 0.07, -0.27)
# high five, right: hand up and forward (0.25, -0.20, 0.50), palm forward, fingers up.
HIGH_FIVE_R: ArmValues = (-1.85, -0.53, 0.44, 0.7, -0.89, -0.05, -0.53)
# clap, left (right mirrored): palms facing, fingers forward-up; open: hands at y = +-0.16,
# together: hands at y = +-0.022 (hand points 4.4 cm apart, palms nearly touching), x 0.32, z 0.12.
CLAP_OPEN: ArmValues = (-0.39, 0.15, 0.14, 0.31, -0.13, -0.19, -0.18)
CLAP_TOGETHER: ArmValues = (-0.52, -0.21, -0.12, 0.54, 0.18, -0.28, 0.22)
# hug, left: arms wide (hand 0.33, 0.30, 0.10), then closing round (0.34, 0.07, 0.10), palms in.
HUG_OPEN: ArmValues = (-0.93, 0.53, 0.29, 1.39, -0.07, -0.36, -0.63)
HUG_CLOSED: ArmValues = (-0.77, 0.25, -0.59, 0.77, -0.57, -0.14, -0.61)
# heart, left: hand before the chest (0.20, 0.035, 0.20), palm toward the body, fingers up and
# in: with the mirrored right hand the curled fingers meet above, the thumbs below.
HEART: ArmValues = (-0.52, 0.46, -0.93, -0.23, -1.44, -0.7, -0.84)
# right heart, right: the right hand alone over the chest centre (0.20, 0.0, 0.22).
RIGHT_HEART_R: ArmValues = (-0.61, -0.29, 0.96, -0.2, 1.29, -0.66, 0.66)
# shake hand, right: hand forward at belt height (0.30, -0.13, 0.02), palm facing left, fingers
# forward; the pump moves it up and down ~4 cm.
SHAKE_R: ArmValues = (-0.43, -0.07, -0.05, 0.89, 0.05, -0.46, 0.1)
# hands up, left: arm straight up, a little out (hand 0.05, 0.20, 0.65).
HANDS_UP: ArmValues = (-2.95, 0.25, 0.0, 1.45, 0.0, 0.0, 0.0)
# reject, right: hand up before the chest (0.30, -0.12, 0.24), palm out ("no"), swung sideways.
REJECT_R: ArmValues = (-0.77, -0.12, 0.06, 0.35, -1.43, 0.02, -1.16)
# x-ray: forearms crossed before the chest, left hand (0.22, -0.14, 0.32) behind the right
# hand (0.29, 0.14, 0.34), palms toward the body.
XRAY_L: ArmValues = (-1.05, -0.54, -0.74, 0.5, -0.98, -0.47, -0.49)
XRAY_R: ArmValues = (-1.69, 0.7, 0.11, 1.57, 1.13, -0.57, 1.12)
# kiss, left: fingertips at the mouth (0.13, 0.04, 0.37), palm in; then thrown forward and out
# (0.36, 0.18, 0.33), palm up.
KISS_MOUTH: ArmValues = (-0.86, -0.39, -0.25, -0.7, -1.12, 0.07, 0.02)
KISS_THROW: ArmValues = (-1.56, -0.07, 1.03, 0.59, -0.76, 0.74, 0.6)


def _high_wave(d: float) -> list[tuple[float, Pose]]:
    a, b = nudge(WAVE_R, elbow=-0.35), nudge(WAVE_R, elbow=0.35)
    frames = [(0.0, NEUTRAL), (0.9, pose(right=WAVE_R))]
    for i, t in enumerate((1.2, 1.5, 1.8, 2.1, 2.4)):
        frames.append((t, pose(right=a if i % 2 == 0 else b)))
    return frames + [(2.7, pose(right=WAVE_R)), (d, NEUTRAL)]


def _face_wave(d: float) -> list[tuple[float, Pose]]:
    a, b = nudge(FACE_WAVE_R, shoulder_yaw=0.35), nudge(FACE_WAVE_R, shoulder_yaw=-0.35)
    frames = [(0.0, NEUTRAL), (0.8, pose(right=FACE_WAVE_R))]
    for i, t in enumerate((1.05, 1.3, 1.55, 1.8)):
        frames.append((t, pose(right=a if i % 2 == 0 else b)))
    return frames + [(2.1, pose(right=FACE_WAVE_R)), (d, NEUTRAL)]


def _high_five(d: float) -> list[tuple[float, Pose]]:
    return [(0.0, NEUTRAL), (1.2, pose(right=nudge(HIGH_FIVE_R, elbow=-0.3))), (2.0, pose(right=HIGH_FIVE_R)),
            (d, pose(right=HIGH_FIVE_R))]


def _clap(d: float) -> list[tuple[float, Pose]]:
    frames = [(0.0, NEUTRAL), (0.7, both(CLAP_OPEN))]
    for i, t in enumerate((0.95, 1.2, 1.45, 1.7, 1.95)):
        frames.append((t, both(CLAP_TOGETHER if i % 2 == 0 else CLAP_OPEN)))
    return frames + [(d, NEUTRAL)]


def _hug(d: float) -> list[tuple[float, Pose]]:
    return [(0.0, NEUTRAL), (1.5, both(HUG_OPEN)), (3.0, both(HUG_CLOSED, "relaxed")), (d, both(HUG_CLOSED, "relaxed"))]


def _heart(d: float) -> list[tuple[float, Pose]]:
    return [(0.0, NEUTRAL), (1.2, both(nudge(HEART, elbow=0.4))), (2.2, both(HEART, "curl")),
            (d, both(HEART, "curl"))]


def _right_heart(d: float) -> list[tuple[float, Pose]]:
    held = pose(right=RIGHT_HEART_R, right_hand="curl")
    return [(0.0, NEUTRAL), (1.2, pose(right=nudge(RIGHT_HEART_R, elbow=0.4))), (2.2, held), (d, held)]


def _shake_hand(d: float) -> list[tuple[float, Pose]]:
    up = nudge(SHAKE_R, shoulder_pitch=-0.07, elbow=-0.09)
    down = nudge(SHAKE_R, shoulder_pitch=0.07, elbow=0.09)
    held = pose(right=SHAKE_R, right_hand="grip")
    frames = [(0.0, NEUTRAL), (1.2, pose(right=SHAKE_R)), (1.6, held)]
    for i, t in enumerate((1.9, 2.2, 2.5, 2.8)):
        frames.append((t, pose(right=up if i % 2 == 0 else down, right_hand="grip")))
    return frames + [(3.1, held), (d, held)]


def _hands_up(d: float) -> list[tuple[float, Pose]]:
    return [(0.0, NEUTRAL), (0.8, both(nudge(HANDS_UP, shoulder_pitch=1.2, elbow=-0.4))), (1.8, both(HANDS_UP)),
            (d, both(HANDS_UP))]


def _reject(d: float) -> list[tuple[float, Pose]]:
    a, b = nudge(REJECT_R, shoulder_yaw=0.3), nudge(REJECT_R, shoulder_yaw=-0.3)
    frames = [(0.0, NEUTRAL), (0.8, pose(right=REJECT_R))]
    for i, t in enumerate((1.1, 1.4, 1.7, 2.0)):
        frames.append((t, pose(right=a if i % 2 == 0 else b)))
    return frames + [(2.3, pose(right=REJECT_R)), (d, NEUTRAL)]


def _right_hand_up(d: float) -> list[tuple[float, Pose]]:
    up = mirror(HANDS_UP)
    return [(0.0, NEUTRAL), (0.8, pose(right=nudge(up, shoulder_pitch=1.2, elbow=-0.4))), (1.8, pose(right=up)),
            (d, pose(right=up))]


def _xray(d: float) -> list[tuple[float, Pose]]:
    crossed = pose(XRAY_L, XRAY_R)
    return [(0.0, NEUTRAL), (0.8, pose(nudge(XRAY_L, shoulder_roll=0.5), nudge(XRAY_R, shoulder_roll=-0.9))),
            (1.5, crossed), (2.6, crossed), (d, NEUTRAL)]


def _kiss(sides: tuple[str, ...]) -> Callable[[float], list[tuple[float, Pose]]]:
    def frames(d: float) -> list[tuple[float, Pose]]:
        def with_arms(values: ArmValues, shape: str) -> Pose:
            return pose(values if "left" in sides else None, mirror(values) if "right" in sides else None,
                        shape if "left" in sides else "open", shape if "right" in sides else "open")
        at_mouth = with_arms(KISS_MOUTH, "relaxed")
        thrown = with_arms(KISS_THROW, "open")
        mouth_at = 0.3 * d
        return [(0.0, NEUTRAL), (mouth_at, at_mouth), (mouth_at + 0.4, at_mouth), (0.62 * d, thrown),
                (0.75 * d, thrown), (d, NEUTRAL)]
    return frames


def _release(d: float, start: Pose) -> list[tuple[float, Pose]]:
    return [(0.0, start), (d, NEUTRAL)]


BUILDERS: dict[str, Callable[[float], list[tuple[float, Pose]]]] = {
    "two hand kiss": _kiss(("left", "right")),
    "left kiss": _kiss(("left",)),
    "right kiss": _kiss(("right",)),
    "hands up": _hands_up,
    "clap": _clap,
    "high five": _high_five,
    "hug": _hug,
    "heart": _heart,
    "right heart": _right_heart,
    "reject": _reject,
    "right hand up": _right_hand_up,
    "x-ray": _xray,
    "face wave": _face_wave,
    "high wave": _high_wave,
    "shake hand": _shake_hand,
}


def keyframes(name: str, start: Mapping[str, float] | None = None) -> list[Keyframe]:
    """The keyframes of library gesture ``name`` (any spelling :func:`gestures.lookup` accepts).

    ``start`` matters only for "release arm": the pose to release from (default: neutral, a
    no-op that still takes the gesture's time). Raises ``ValueError`` for an unknown gesture.
    """
    gesture = gestures.lookup(name)
    if gesture is None:
        raise ValueError(f"no gesture {name!r}{did_you_mean(name, gestures.names())}")
    if gesture.name == "release arm":
        frames = _release(gesture.duration, {**NEUTRAL, **(start or {})})
    else:
        frames = BUILDERS[gesture.name](gesture.duration)
    return [Keyframe(round(t, 6), dict(joints)) for t, joints in frames]


def end_pose(name: str) -> Pose:
    """Where the arms are when gesture ``name`` ends (its held pose for gestures that hold)."""
    return dict(keyframes(name)[-1].joints)


# --- validation -----------------------------------------------------------------------------------

def joint_limits() -> dict[str, tuple[float, float]]:
    """Limits of every joint a gesture may name (arms, hands, waist), from the robot description."""
    limits = desc.g1().limits()
    return {name: limits[name] for name in GESTURE_JOINTS}


_LIMITS = joint_limits()
# how people group the gesture joints: (label, name prefix, is a hand); the more specific last
JOINT_GROUPS = (("left arm", "left_", False), ("right arm", "right_", False), ("left hand", "left_hand_", True),
                ("right hand", "right_hand_", True), ("waist", "waist_", False))


def validate_keyframes(frames: Iterable[Keyframe | Mapping[str, Any]]) -> list[str]:
    """Every problem with ``frames`` in words (empty: fine): unknown joint names (with a
    did-you-mean), angles outside their limits (with the limits), non-numbers, negative times,
    times that do not increase. Frames may be :class:`Keyframe` or ``{"t", "joints"}`` dicts."""
    problems: list[str] = []
    previous: float | None = None
    count = 0
    for i, frame in enumerate(frames):
        count += 1
        where = f"keyframe {i}"
        if isinstance(frame, Mapping):
            t, joints = frame.get("t"), frame.get("joints")
        elif isinstance(frame, Keyframe):
            t, joints = frame.t, frame.joints
        else:
            problems.append(f"{where}: must be an object with 't' and 'joints', got {frame!r}")
            continue
        if not is_finite_number(t):
            problems.append(f"{where}: t {t!r} is not a number of seconds")
        else:
            t = float(t)
            if t < 0:
                problems.append(f"{where}: t = {t:g} s is negative")
            if previous is not None and t <= previous:
                problems.append(f"{where}: t = {t:g} s does not come after the previous keyframe's {previous:g} s")
            previous = t
        if not isinstance(joints, Mapping):
            problems.append(f"{where}: 'joints' must map joint names to radians, got {joints!r}")
            continue
        if not joints:
            problems.append(f"{where}: names no joints")
        for name, value in joints.items():
            if name not in _LIMITS:
                problems.append(f"{where}: unknown joint {name!r}{did_you_mean(str(name), GESTURE_JOINTS)}")
            elif not is_finite_number(value):
                problems.append(f"{where}: {name} = {value!r} is not a number of radians")
            else:
                lo, hi = _LIMITS[name]
                if not lo <= float(value) <= hi:
                    problems.append(f"{where}: {name} = {float(value):.4f} rad is outside its limits "
                                    f"[{lo:.4f}, {hi:.4f}]")
    if count == 0:
        problems.append("there are no keyframes")
    return problems


# --- recorded gesture files -------------------------------------------------------------------

class GestureFileError(StuartError, ValueError):
    """A gesture file that cannot be used; ``problems`` lists every reason."""

    def __init__(self, path: Path, problems: list[str]) -> None:
        super().__init__(f"{path}: " + "; ".join(problems))
        self.path = path
        self.problems = problems


@dataclass(frozen=True)
class RecordedGesture:
    name: str
    keyframes: list[Keyframe]


FILE_KEYS = ("name", "keyframes")
FRAME_KEYS = ("t", "joints")


def gesture_file_problems(path: Path | str) -> list[str]:
    """Every problem with the gesture file at ``path`` (empty: it loads)."""
    return _read(Path(path))[1]


def load_gesture_file(path: Path | str) -> RecordedGesture:
    """The recorded gesture in ``path``; :class:`GestureFileError` lists every problem."""
    gesture, problems = _read(Path(path))
    if problems or gesture is None:
        raise GestureFileError(Path(path), problems)
    return gesture


def save_gesture_file(path: Path | str, name: str, frames: list[Keyframe]) -> Path:
    """Write ``frames`` as gesture ``name``, after checking them (nothing is written if they
    have a problem: a recorder must not leave a file the player will refuse)."""
    path = Path(path)
    problems = ([] if isinstance(name, str) and name.strip() else ["'name' must be a non-empty string"])
    problems += validate_keyframes(frames)
    if problems:
        raise GestureFileError(path, problems)
    doc = {"name": name,
           "keyframes": [{"t": round(f.t, 4), "joints": {k: _round_inward(k, float(v)) for k, v in f.joints.items()}}
                         for f in frames]}
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(to_json(doc, indent=1) + "\n", encoding="utf-8")
    return path


def _round_inward(joint: str, value: float, digits: int = 5) -> float:
    """Round for the file without leaving the joint's limits (a value at a limit stays loadable)."""
    low, high = _LIMITS.get(joint, (-math.inf, math.inf))
    return min(max(round(value, digits), math.ceil(low * 10**digits) / 10**digits),
               math.floor(high * 10**digits) / 10**digits)


def _read(path: Path) -> tuple[RecordedGesture | None, list[str]]:
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        return None, ["file not found"]
    except (OSError, UnicodeDecodeError) as e:
        return None, [f"cannot read: {e}"]
    except json.JSONDecodeError as e:
        return None, [f"not JSON: {e.msg} at line {e.lineno} column {e.colno}"]
    if not isinstance(doc, dict):
        return None, [f"must be a JSON object with 'name' and 'keyframes', got {type(doc).__name__}"]
    problems = [f"unknown key {key!r}{did_you_mean(str(key), FILE_KEYS)}" for key in doc if key not in FILE_KEYS]
    name = doc.get("name")
    if not isinstance(name, str) or not name.strip():
        problems.append(f"'name' must be a non-empty string, got {name!r}")
    raw = doc.get("keyframes")
    if not isinstance(raw, list) or not raw:
        problems.append(f"'keyframes' must be a non-empty list, got {raw!r}")
        return None, problems
    for i, item in enumerate(raw):
        if isinstance(item, dict):
            problems += [f"keyframe {i}: unknown key {key!r}{did_you_mean(str(key), FRAME_KEYS)}"
                         for key in item if key not in FRAME_KEYS]
    problems += validate_keyframes(raw)
    if problems:
        return None, problems
    clean = [Keyframe(float(f["t"]), {str(k): float(v) for k, v in f["joints"].items()}) for f in raw]
    return RecordedGesture(str(name), clean), problems
