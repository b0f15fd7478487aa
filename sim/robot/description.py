"""The simplified Unitree G1 ("Stuart") as plain data: the one source both model files come from.

MuJoCo (``mjcf.py``) and Pinocchio/PlaCo (``urdf.py``) must agree on every joint and length,
so neither file is written by hand: both are generated from :func:`g1` and a test checks the
committed files still match. Numbers come from ``/work/shared/FIELD_NOTES.md`` (vendor SDK and
description files, BSD-3) unless a comment says where else.

Conventions (REP-103): metres, radians, kilograms; x forward, y left, z up. A joint's origin is
the pose of its child link in its parent link at q = 0 (as in URDF); its axis is in the child
link. Capsules and cylinders lie along their local z axis, ``size = (radius, half_length)``;
boxes have ``size = half extents``.

Simplifications, on purpose: legs are fixed geometry on the pelvis (the world server moves the
base kinematically through ``base_x``, ``base_y``, ``base_yaw``); the three shoulder axes meet
at the shoulder pitch joint and the forearm joints are collinear (the vendor's few-millimetre
side offsets are left out), which makes the reachable set a clean shell around the shoulder.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

Vec3 = tuple[float, float, float]
RGBA = tuple[float, float, float, float]
Side = Literal["left", "right"]
SIDES: tuple[Side, Side] = ("left", "right")

# --- numbers other modules read -------------------------------------------------------------

PELVIS_HEIGHT = 0.793  # standing pelvis z (FIELD_NOTES)
WAIST_HEIGHT = 0.044  # torso_link origin above the pelvis: torso_link at z ~0.837 standing
SHOULDER_XYZ: Vec3 = (0.004, 0.100, 0.248)  # left shoulder pitch joint in torso_link; right mirrors y
UPPER_ARM = 0.1845  # shoulder to elbow
FOREARM_TO_WRIST_YAW = 0.184  # elbow to wrist yaw joint: 0.100 + 0.038 + 0.046 as in the vendor chain
HAND_POINT_PAST_WRIST_YAW = 0.05  # grasp point beyond the wrist yaw joint
REACH = UPPER_ARM + FOREARM_TO_WRIST_YAW + HAND_POINT_PAST_WRIST_YAW  # 0.4185: straight arm
HEAD_CAMERA_XYZ: Vec3 = (0.0576, 0.0175, 0.4299)  # RealSense D435i on torso_link
HEAD_CAMERA_PITCH = math.radians(47.6)  # down from horizontal
HEAD_CAMERA_FOVY = 42.0  # degrees: the D435i colour stream is ~69 x 42 deg (Intel datasheet)
LIDAR_XYZ: Vec3 = (0.0003, 0.0, 0.4284)  # Livox MID-360 on torso_link, mounted upside down
HAND_PALM_NORMAL: dict[str, Vec3] = {"left": (0.0, -1.0, 0.0), "right": (0.0, 1.0, 0.0)}
"""The palm's outward normal in the wrist-yaw / hand-point frame. With every arm joint at zero
the forearm points forward, thumb up, and the palms face each other (as on the real G1)."""
HAND_FINGER_AXIS: Vec3 = (1.0, 0.0, 0.0)  # fingers extend along +x of the hand-point frame

ARM_JOINT_KINDS = ("shoulder_pitch", "shoulder_roll", "shoulder_yaw", "elbow", "wrist_roll", "wrist_pitch",
                   "wrist_yaw")
HAND_JOINT_KINDS = ("thumb_0", "thumb_1", "thumb_2", "index_0", "index_1", "middle_0", "middle_1")
WAIST_JOINTS = ("waist_yaw_joint", "waist_roll_joint", "waist_pitch_joint")
BASE_JOINTS = ("base_x", "base_y", "base_yaw")

# Left-side limits (FIELD_NOTES); the right side mirrors roll- and yaw-like joints.
LEFT_ARM_LIMITS: dict[str, tuple[float, float]] = {
    "shoulder_pitch": (-3.0892, 2.6704),
    "shoulder_roll": (-1.5882, 2.2515),
    "shoulder_yaw": (-2.618, 2.618),
    "elbow": (-1.0472, 2.0944),
    "wrist_roll": (-1.972222054, 1.972222054),
    "wrist_pitch": (-1.614429558, 1.614429558),
    "wrist_yaw": (-1.614429558, 1.614429558),
}
# Dex3-1 limits: the values in Unitree's public g1_29dof_with_hand description (BSD-3); the
# right hand's flexion signs are opposite to the left's (left fingers close negative, right positive).
HAND_LIMITS: dict[str, dict[str, tuple[float, float]]] = {
    "left": {"thumb_0": (-1.04719755, 1.04719755), "thumb_1": (-0.72431163, 1.04719755),
             "thumb_2": (0.0, 1.74532925), "index_0": (-1.57079632, 0.0), "index_1": (-1.74532925, 0.0),
             "middle_0": (-1.57079632, 0.0), "middle_1": (-1.74532925, 0.0)},
    "right": {"thumb_0": (-1.04719755, 1.04719755), "thumb_1": (-1.04719755, 0.72431163),
              "thumb_2": (-1.74532925, 0.0), "index_0": (0.0, 1.57079632), "index_1": (0.0, 1.74532925),
              "middle_0": (0.0, 1.57079632), "middle_1": (0.0, 1.74532925)},
}
WAIST_LIMITS = {"waist_yaw_joint": (-2.618, 2.618), "waist_roll_joint": (-0.52, 0.52),
                "waist_pitch_joint": (-0.52, 0.52)}  # vendor 29-DoF G1 (unlocked waist)


def arm_joints(side: Side) -> tuple[str, ...]:
    """The seven arm joints of ``side``, shoulder to wrist (the vendor's motor order)."""
    return tuple(f"{side}_{kind}_joint" for kind in ARM_JOINT_KINDS)


def hand_joints(side: Side) -> tuple[str, ...]:
    """The seven Dex3-1 joints of ``side`` (vendor names)."""
    return tuple(f"{side}_hand_{kind}_joint" for kind in HAND_JOINT_KINDS)


def arm_limits(side: Side) -> dict[str, tuple[float, float]]:
    """Joint name -> (lower, upper) for one arm. Only shoulder roll is asymmetric, so only it is
    mirrored on the right (both arms share axes, so abduction is + on the left, - on the right)."""
    out = {}
    for kind, (lo, hi) in LEFT_ARM_LIMITS.items():
        mirrored = side == "right" and kind == "shoulder_roll"
        out[f"{side}_{kind}_joint"] = (-hi, -lo) if mirrored else (lo, hi)
    return out


def shoulder_xyz(side: Side) -> np.ndarray:
    """The shoulder pitch joint (the centre of the shoulder) in torso_link."""
    x, y, z = SHOULDER_XYZ
    return np.array([x, y if side == "left" else -y, z])


NEUTRAL: dict[str, float] = {
    # Arms down by the sides, elbows a little bent, hands open: how the G1 stands after
    # "release arm". Elbow q = pi/2 would be a straight arm; 1.25 leaves the forearm ~18 deg forward.
    # Shoulder roll 0.12 rad outward keeps the upper arms clear of the chest.
    **{f"{s}_shoulder_pitch_joint": 0.0 for s in SIDES},
    "left_shoulder_roll_joint": 0.12, "right_shoulder_roll_joint": -0.12,
    **{f"{s}_shoulder_yaw_joint": 0.0 for s in SIDES},
    **{f"{s}_elbow_joint": 1.25 for s in SIDES},
    **{f"{s}_wrist_{k}_joint": 0.0 for s in SIDES for k in ("roll", "pitch", "yaw")},
    **{name: 0.0 for s in SIDES for name in hand_joints(s)},
}


# --- data classes ---------------------------------------------------------------------------

@dataclass(frozen=True)
class Geom:
    """A primitive shape on a link. ``mass`` feeds the link's inertia (both files get the same
    explicit inertial); ``collide=False`` makes it visual only (the legs, which would otherwise
    rub the floor while the base is moved kinematically)."""

    name: str
    type: Literal["box", "sphere", "capsule", "cylinder"]
    size: tuple[float, ...]
    pos: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)
    rgba: RGBA = (0.25, 0.25, 0.27, 1.0)
    mass: float = 0.0
    collide: bool = True


@dataclass(frozen=True)
class Link:
    name: str
    geoms: tuple[Geom, ...] = ()


@dataclass(frozen=True)
class Joint:
    """``kind`` 'fixed' welds the child (MJCF: a body with no joint; URDF: a fixed joint)."""

    name: str
    kind: Literal["hinge", "slide", "fixed"]
    parent: str
    child: str
    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)
    axis: Vec3 = (0.0, 0.0, 1.0)
    lower: float | None = None  # None: unlimited
    upper: float | None = None
    effort: float = 0.0  # N m or N
    velocity: float = 0.0  # rad/s or m/s
    kp: float = 0.0  # position actuator gain (MJCF); 0 = no actuator
    kv: float = 0.0  # its velocity gain
    armature: float = 0.0  # reflected rotor inertia; steadies stiff servos on light links
    damping: float = 0.0

    @property
    def limited(self) -> bool:
        return self.lower is not None and self.upper is not None


@dataclass(frozen=True)
class Site:
    """A named point (and frame) on a link: MJCF site, URDF fixed frame link."""

    name: str
    link: str
    xyz: Vec3
    rpy: Vec3 = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Camera:
    """``rpy`` is the camera *body* frame in REP-103 terms (x along the view, z up); the MJCF
    writer turns it into MuJoCo's camera frame (looking along -z, +y up)."""

    name: str
    link: str
    xyz: Vec3
    rpy: Vec3
    fovy: float  # degrees, vertical
    resolution: tuple[int, int] = (640, 480)


@dataclass(frozen=True)
class Robot:
    name: str
    root: str  # the top link (MJCF: top body; URDF: root link)
    root_xyz: Vec3  # where the root stands in the world at base q = 0
    base_joints: tuple[Joint, ...]  # on the root, parent "world": MJCF only
    links: dict[str, Link]
    joints: tuple[Joint, ...]  # the tree below the root, parents before children
    sites: tuple[Site, ...] = ()
    cameras: tuple[Camera, ...] = ()
    _by_name: dict[str, Joint] = field(default_factory=dict, repr=False, compare=False)

    def __post_init__(self) -> None:
        self._by_name.update({j.name: j for j in (*self.base_joints, *self.joints)})

    def joint(self, name: str) -> Joint:
        return self._by_name[name]

    def children(self, link: str) -> list[Joint]:
        return [j for j in self.joints if j.parent == link]

    def movable(self) -> list[Joint]:
        """Every non-fixed joint, base joints first (the MJCF qpos order)."""
        return [j for j in (*self.base_joints, *self.joints) if j.kind != "fixed"]

    def limits(self) -> dict[str, tuple[float, float]]:
        return {j.name: (j.lower, j.upper) for j in self.movable() if j.limited}  # type: ignore[misc]

    def total_mass(self) -> float:
        return sum(g.mass for link in self.links.values() for g in link.geoms)


# --- rotations and inertia ------------------------------------------------------------------

def rpy_matrix(rpy: Vec3) -> np.ndarray:
    """URDF convention: roll about x, then pitch about y, then yaw about z, all fixed axes."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def matrix_rpy(m: np.ndarray) -> Vec3:
    """Inverse of :func:`rpy_matrix` (pitch kept in [-pi/2, pi/2])."""
    pitch = math.atan2(-m[2, 0], math.hypot(m[0, 0], m[1, 0]))
    if abs(math.cos(pitch)) < 1e-9:  # gimbal lock: put everything in yaw
        return (0.0, pitch, math.atan2(-m[0, 1], m[1, 1]))
    return (math.atan2(m[2, 1], m[2, 2]), pitch, math.atan2(m[1, 0], m[0, 0]))


def matrix_quat(m: np.ndarray) -> tuple[float, float, float, float]:
    """Rotation matrix -> unit quaternion (w, x, y, z), w >= 0 (MuJoCo's order)."""
    t = m[0, 0] + m[1, 1] + m[2, 2]
    if t > 0:
        s = 2.0 * math.sqrt(1.0 + t)
        q = (0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s)
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = ((m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s)
    elif m[1, 1] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        q = ((m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s)
    else:
        s = 2.0 * math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        q = ((m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s)
    sign = -1.0 if q[0] < 0 else 1.0
    return (sign * q[0], sign * q[1], sign * q[2], sign * q[3])


def _own_inertia(g: Geom) -> np.ndarray:
    """Inertia of a solid primitive about its centre, in its own frame."""
    m = g.mass
    if g.type == "box":
        a, b, c = (s * s for s in g.size)
        return np.diag([m / 3 * (b + c), m / 3 * (a + c), m / 3 * (a + b)])
    if g.type == "sphere":
        return np.eye(3) * 0.4 * m * g.size[0] ** 2
    r, h = g.size
    if g.type == "cylinder":
        side = m * (3 * r * r + 4 * h * h) / 12
        return np.diag([side, side, m * r * r / 2])
    # capsule: a cylinder plus two hemispheres, mass shared by volume
    v_cyl, v_sph = math.pi * r * r * 2 * h, 4 / 3 * math.pi * r ** 3
    mc, ms = m * v_cyl / (v_cyl + v_sph), m * v_sph / (v_cyl + v_sph)
    axial = mc * r * r / 2 + ms * 0.4 * r * r
    side = mc * (3 * r * r + 4 * h * h) / 12 + ms * (0.4 * r * r + h * h + 0.75 * h * r)
    return np.diag([side, side, axial])


def inertial(link: Link) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass, centre of mass, 3x3 inertia about the centre of mass) of a link, in its frame,
    from its geoms: written explicitly into both files so they cannot disagree."""
    massive = [g for g in link.geoms if g.mass > 0]
    mass = sum(g.mass for g in massive)
    if mass <= 0:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    com = np.sum([g.mass * np.asarray(g.pos) for g in massive], axis=0) / mass
    inertia = np.zeros((3, 3))
    for g in massive:
        rot = rpy_matrix(g.rpy)
        d = np.asarray(g.pos) - com
        inertia += rot @ _own_inertia(g) @ rot.T + g.mass * (d @ d * np.eye(3) - np.outer(d, d))
    return mass, com, inertia


def segment(name: str, a: Vec3, b: Vec3, radius: float, mass: float, rgba: RGBA,
            kind: Literal["capsule", "cylinder"] = "capsule", collide: bool = True) -> Geom:
    """A capsule or cylinder from point ``a`` to point ``b`` (ends of the axis, caps excluded)."""
    pa, pb = np.asarray(a, float), np.asarray(b, float)
    d = pb - pa
    length = float(np.linalg.norm(d))
    z = d / length
    cx, cy, cz = (float(v) for v in (pa + pb) / 2)
    mid = (cx, cy, cz)
    # the shapes are symmetric about their axis and end to end: only the axis line matters, so
    # axis-aligned segments get round angles (readable model files)
    for axis, rpy in ((2, (0.0, 0.0, 0.0)), (0, (0.0, math.pi / 2, 0.0)), (1, (math.pi / 2, 0.0, 0.0))):
        if abs(abs(z[axis]) - 1.0) < 1e-12:
            return Geom(name, kind, (radius, length / 2), mid, rpy, rgba, mass, collide)
    helper = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(helper, z)
    x /= np.linalg.norm(x)
    rot = np.column_stack([x, np.cross(z, x), z])
    return Geom(name, kind, (radius, length / 2), mid, matrix_rpy(rot), rgba, mass, collide)


# --- the G1 -----------------------------------------------------------------------------------

DARK: RGBA = (0.18, 0.18, 0.2, 1.0)
SILVER: RGBA = (0.68, 0.69, 0.72, 1.0)
BLACK: RGBA = (0.08, 0.08, 0.09, 1.0)
LENS: RGBA = (0.1, 0.3, 0.6, 1.0)

# Masses (kg): the vendor description's link masses where the link exists, rounded; the legs are
# lumped into the pelvis (hip 1.35 + 1.52 + 1.70, knee 1.70, ankle 0.07 + 0.61 per leg). Total ~34.
MASS = {
    "pelvis": 3.8, "leg": 6.95, "waist_yaw": 0.214, "waist_roll": 0.086, "torso": 6.7, "head": 0.9,
    "shoulder_pitch": 0.718, "shoulder_roll": 0.643, "shoulder_yaw": 0.734, "elbow": 0.6,
    "wrist_roll": 0.085, "wrist_pitch": 0.484, "wrist_yaw": 0.254,
    # Dex3-1: about 0.7 kg a hand (vendor spec sheet order of magnitude): palm plus seven segments
    "palm": 0.41, "finger_segment": 0.04,
}
# Effort (N m) / velocity (rad/s): vendor URDF values for the 29-DoF G1.
ARM_EFFORT = {"shoulder_pitch": 25, "shoulder_roll": 25, "shoulder_yaw": 25, "elbow": 25, "wrist_roll": 25,
              "wrist_pitch": 5, "wrist_yaw": 5}
ARM_VELOCITY = {"shoulder_pitch": 37, "shoulder_roll": 37, "shoulder_yaw": 37, "elbow": 37, "wrist_roll": 37,
                "wrist_pitch": 22, "wrist_yaw": 22}
# Servo gains for MuJoCo position actuators, chosen for near-critical damping with the link
# inertias here and gravity compensated (bodies carry gravcomp=1, as the arm SDK's controller does).
ARM_GAINS = {"shoulder_pitch": (120, 8), "shoulder_roll": (120, 8), "shoulder_yaw": (80, 5), "elbow": (80, 4),
             "wrist_roll": (30, 1.2), "wrist_pitch": (30, 1.2), "wrist_yaw": (30, 1.2)}
ARM_AXES: dict[str, Vec3] = {"shoulder_pitch": (0, 1, 0), "shoulder_roll": (1, 0, 0), "shoulder_yaw": (0, 0, 1),
                             "elbow": (0, 1, 0), "wrist_roll": (1, 0, 0), "wrist_pitch": (0, 1, 0),
                             "wrist_yaw": (0, 0, 1)}


def _legs() -> tuple[Geom, ...]:
    """Both legs, straight, as pelvis geometry: hip at z -0.10, knee -0.40, ankle -0.72 (pelvis
    frame), feet resting just above the floor when the pelvis stands at 0.793."""
    geoms: list[Geom] = []
    per = MASS["leg"]
    for side, sy in (("left", 1.0), ("right", -1.0)):
        y = 0.0645 * sy  # hip pitch joint y in the vendor description
        geoms += [
            segment(f"{side}_hip", (0.0, y, -0.06), (0.0, y, -0.14), 0.055, 0.30 * per, DARK, collide=False),
            segment(f"{side}_thigh", (0.0, y, -0.14), (0.0, y, -0.40), 0.05, 0.33 * per, SILVER, collide=False),
            segment(f"{side}_shin", (0.0, y, -0.40), (0.0, y, -0.72), 0.042, 0.27 * per, DARK, collide=False),
            Geom(f"{side}_foot", "box", (0.1, 0.035, 0.025), (0.03, y, -0.766), rgba=BLACK, mass=0.10 * per,
                 collide=False),
        ]
    return tuple(geoms)


def _arm(side: Side) -> tuple[list[Link], list[Joint]]:
    """Shoulder pitch -> roll -> yaw (the three axes meet at the shoulder) -> elbow -> wrist."""
    s = 1.0 if side == "left" else -1.0
    limits = arm_limits(side)
    # where each joint sits in its parent link
    offsets: dict[str, Vec3] = {
        "shoulder_pitch": (SHOULDER_XYZ[0], s * SHOULDER_XYZ[1], SHOULDER_XYZ[2]),
        "shoulder_roll": (0.0, 0.0, 0.0),
        "shoulder_yaw": (0.0, 0.0, -0.09),
        "elbow": (0.0, 0.0, -(UPPER_ARM - 0.09)),
        "wrist_roll": (0.100, 0.0, 0.0),
        "wrist_pitch": (0.038, 0.0, 0.0),
        "wrist_yaw": (0.046, 0.0, 0.0),
    }
    shapes: dict[str, tuple[Geom, ...]] = {
        "shoulder_pitch": (Geom(f"{side}_shoulder_motor", "sphere", (0.045,), rgba=DARK, mass=MASS["shoulder_pitch"]),),
        "shoulder_roll": (segment(f"{side}_upper_arm_top", (0, 0, -0.03), (0, 0, -0.085), 0.034,
                                  MASS["shoulder_roll"], SILVER),),
        "shoulder_yaw": (segment(f"{side}_upper_arm", (0, 0, 0.0), (0, 0, -0.075), 0.031,
                                 MASS["shoulder_yaw"], SILVER),),
        "elbow": (Geom(f"{side}_elbow_motor", "sphere", (0.034,), rgba=DARK, mass=0.3 * MASS["elbow"]),
                  segment(f"{side}_forearm", (0.02, 0, 0), (0.095, 0, 0), 0.029, 0.7 * MASS["elbow"], SILVER)),
        "wrist_roll": (segment(f"{side}_wrist_roll_shell", (0.0, 0, 0), (0.03, 0, 0), 0.028,
                               MASS["wrist_roll"], DARK, kind="cylinder"),),
        "wrist_pitch": (segment(f"{side}_wrist", (0.0, 0, 0), (0.03, 0, 0), 0.027, MASS["wrist_pitch"], DARK),),
        "wrist_yaw": (Geom(f"{side}_wrist_yaw_shell", "cylinder", (0.024, 0.018), rgba=DARK,
                           mass=MASS["wrist_yaw"]),),
    }
    links: list[Link] = []
    joints: list[Joint] = []
    parent = "torso_link"
    for kind in ARM_JOINT_KINDS:
        child = f"{side}_{kind}_link"
        lo, hi = limits[f"{side}_{kind}_joint"]
        kp, kv = ARM_GAINS[kind]
        links.append(Link(child, shapes[kind]))
        joints.append(Joint(f"{side}_{kind}_joint", "hinge", parent, child, offsets[kind], axis=ARM_AXES[kind],
                            lower=lo, upper=hi, effort=ARM_EFFORT[kind], velocity=ARM_VELOCITY[kind], kp=kp, kv=kv,
                            armature=0.03 if "shoulder" in kind or kind == "elbow" else 0.01, damping=0.05))
        parent = child
    return links, joints


def _hand(side: Side) -> tuple[list[Link], list[Joint]]:
    """Dex3-1: a palm welded to the wrist yaw link, a thumb (3 joints) on top, index above the
    middle finger (2 joints each). Palm outward normal -y on the left hand, +y on the right.

    Axes give the vendor's signs: fingers curl toward the palm, closing negative on the left
    (axis +z) and positive on the right (the mirror image); the thumb bends down toward the
    fingers, closing positive on the left (axis +y) and negative on the right (axis -y)."""
    s = 1.0 if side == "left" else -1.0
    palm_side = -s  # y of the palm face
    limits = HAND_LIMITS[side]
    seg = MASS["finger_segment"]
    palm = Link(f"{side}_hand_palm_link", (
        Geom(f"{side}_palm", "box", (0.045, 0.016, 0.042), (0.055, 0.0, 0.0), rgba=BLACK, mass=MASS["palm"]),))
    links = [palm]
    joints = [Joint(f"{side}_hand_palm_joint", "fixed", f"{side}_wrist_yaw_link", palm.name, (0.0, 0.0, 0.0))]
    finger_axis: Vec3 = (0.0, 0.0, 1.0)
    thumb_axis: Vec3 = (0.0, s, 0.0)
    chains = {
        # kind: (parent, origin in parent, axis, shape end in own frame, radius)
        "index_0": (palm.name, (0.1, 0.0, 0.02), finger_axis, (0.045, 0, 0), 0.011),
        "index_1": ("index_0", (0.045, 0.0, 0.0), finger_axis, (0.04, 0, 0), 0.01),
        "middle_0": (palm.name, (0.1, 0.0, -0.02), finger_axis, (0.045, 0, 0), 0.011),
        "middle_1": ("middle_0", (0.045, 0.0, 0.0), finger_axis, (0.04, 0, 0), 0.01),
        "thumb_0": (palm.name, (0.04, palm_side * 0.012, 0.045), (s, 0.0, 0.0), (0.015, 0, 0), 0.012),
        "thumb_1": ("thumb_0", (0.015, 0.0, 0.0), thumb_axis, (0.04, 0, 0), 0.011),
        "thumb_2": ("thumb_1", (0.04, 0.0, 0.0), thumb_axis, (0.035, 0, 0), 0.01),
    }
    for kind in ("thumb_0", "thumb_1", "thumb_2", "index_0", "index_1", "middle_0", "middle_1"):
        parent, origin, axis, end, radius = chains[kind]
        parent_link = parent if parent.endswith("_link") else f"{side}_hand_{parent}_link"
        child = f"{side}_hand_{kind}_link"
        lo, hi = limits[kind]
        links.append(Link(child, (segment(f"{side}_hand_{kind}", (0, 0, 0), end, radius, seg, DARK),)))
        joints.append(Joint(f"{side}_hand_{kind}_joint", "hinge", parent_link, child, origin, axis=axis,
                            lower=lo, upper=hi, effort=1.4, velocity=6.0, kp=2.0, kv=0.1, armature=0.001,
                            damping=0.01))
    return links, joints


def g1() -> Robot:
    """The whole robot, root ``pelvis`` standing at z = 0.793."""
    links: list[Link] = [
        Link("pelvis", (Geom("pelvis", "box", (0.06, 0.1, 0.055), (0.0, 0.0, -0.045), rgba=DARK,
                             mass=MASS["pelvis"]), *_legs())),
        Link("waist_yaw_link", (Geom("waist_yaw_motor", "cylinder", (0.05, 0.02), (0.0, 0.0, 0.02), rgba=DARK,
                                     mass=MASS["waist_yaw"]),)),
        Link("waist_roll_link", (Geom("waist_roll_motor", "sphere", (0.03,), rgba=DARK, mass=MASS["waist_roll"]),)),
        Link("torso_link", (
            Geom("abdomen", "box", (0.06, 0.075, 0.05), (0.0, 0.0, 0.06), rgba=DARK, mass=0.25 * MASS["torso"]),
            Geom("chest", "box", (0.07, 0.085, 0.085), (0.0, 0.0, 0.195), rgba=SILVER, mass=0.7 * MASS["torso"]),
            segment("neck", (0.0, 0.0, 0.28), (0.0, 0.0, 0.34), 0.03, 0.05 * MASS["torso"], DARK))),
        Link("head_link", (
            Geom("head", "sphere", (0.068,), (-0.015, 0.0, 0.0), rgba=BLACK, mass=MASS["head"]),)),
    ]
    joints: list[Joint] = [
        Joint("waist_yaw_joint", "hinge", "pelvis", "waist_yaw_link", axis=(0, 0, 1),
              lower=WAIST_LIMITS["waist_yaw_joint"][0], upper=WAIST_LIMITS["waist_yaw_joint"][1],
              effort=88, velocity=32, kp=400, kv=25, armature=0.05, damping=0.5),
        Joint("waist_roll_joint", "hinge", "waist_yaw_link", "waist_roll_link", (0.0, 0.0, WAIST_HEIGHT),
              axis=(1, 0, 0),
              lower=WAIST_LIMITS["waist_roll_joint"][0], upper=WAIST_LIMITS["waist_roll_joint"][1],
              effort=50, velocity=37, kp=400, kv=30, armature=0.05, damping=0.5),
        Joint("waist_pitch_joint", "hinge", "waist_roll_link", "torso_link", axis=(0, 1, 0),
              lower=WAIST_LIMITS["waist_pitch_joint"][0], upper=WAIST_LIMITS["waist_pitch_joint"][1],
              effort=50, velocity=37, kp=400, kv=30, armature=0.05, damping=0.5),
        # head centre (0.415 above torso_link) puts the head top ~1.32 m above the floor standing
        Joint("head_joint", "fixed", "torso_link", "head_link", (0.0, 0.0, 0.415)),
    ]
    for side in SIDES:
        arm_links, arm = _arm(side)
        hand_links, hand = _hand(side)
        links += arm_links + hand_links
        joints += arm + hand
    base = (
        Joint("base_x", "slide", "world", "pelvis", axis=(1, 0, 0), effort=2000, velocity=1.5, kp=20000, kv=1600),
        Joint("base_y", "slide", "world", "pelvis", axis=(0, 1, 0), effort=2000, velocity=1.5, kp=20000, kv=1600),
        Joint("base_yaw", "hinge", "world", "pelvis", axis=(0, 0, 1), effort=500, velocity=3.0, kp=600, kv=45),
    )
    sites = (
        Site("left_hand_point", "left_wrist_yaw_link", (HAND_POINT_PAST_WRIST_YAW, 0.0, 0.0)),
        Site("right_hand_point", "right_wrist_yaw_link", (HAND_POINT_PAST_WRIST_YAW, 0.0, 0.0)),
        Site("lidar", "torso_link", LIDAR_XYZ, (math.pi, 0.0, 0.0)),  # upside down: z points at the floor
    )
    cameras = (Camera("head_camera", "torso_link", HEAD_CAMERA_XYZ, (0.0, HEAD_CAMERA_PITCH, 0.0), HEAD_CAMERA_FOVY),)
    return Robot("g1", "pelvis", (0.0, 0.0, PELVIS_HEIGHT), base, {lk.name: lk for lk in links}, tuple(joints),
                 sites, cameras)
