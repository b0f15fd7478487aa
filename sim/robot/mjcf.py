"""MJCF text for MuJoCo from the robot description: a complete model (floor, light, robot,
actuators) that loads on its own, and whose robot a scene can graft in.

Grafting: every name is unprefixed and the model uses no default classes, textures or
materials, so ``MjSpec.attach`` (or copying the ``pelvis`` body and the ``<actuator>`` block)
brings nothing that could clash except the names themselves.

Contacts: robot geoms that may touch the world have ``contype=1 conaffinity=0``: they collide
with ordinary scene geoms (1/1) but never with each other (the simplified arm passes close to
the chest); legs are visual only (``0/0``) since the base slides over the floor kinematically.
Robot geoms are in group 1 so a lidar or depth ray can skip them with a geom-group filter.
Bodies carry ``gravcomp=1``: the arm servos hold poses as the real arm SDK's controller does.
"""

from __future__ import annotations

from xml.sax.saxutils import quoteattr

import numpy as np

from .description import NEUTRAL, Camera, Geom, Joint, Robot, inertial, matrix_quat, rpy_matrix

ROBOT_GROUP = 1
TIMESTEP = 0.002
# MuJoCo camera frame (x right, y up, looking along -z) expressed in a REP-103 camera body frame
# (x along the view, y left, z up): columns are the MuJoCo axes.
_MJ_CAMERA_IN_BODY = np.array([[0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])


def num(value: float) -> str:
    """Stable short text for a number (same input, same text: the --check diff relies on it)."""
    value = round(float(value), 9)
    if value == 0:
        return "0"
    return f"{value:.9g}"


def nums(values) -> str:
    return " ".join(num(v) for v in values)


def _attrs(**kwargs: object) -> str:
    return "".join(f" {k.rstrip('_')}={quoteattr(str(v))}" for k, v in kwargs.items() if v is not None)


def _quat(rpy) -> str | None:
    if not any(rpy):
        return None
    return nums(matrix_quat(rpy_matrix(rpy)))


def _geom(g: Geom) -> str:
    if g.type == "box":
        size = nums(g.size)
    elif g.type == "sphere":
        size = num(g.size[0])
    else:
        size = nums(g.size)
    contype, conaffinity = (1, 0) if g.collide else (0, 0)
    pos = nums(g.pos) if any(g.pos) else None
    return (f"<geom{_attrs(name=g.name, type=g.type, size=size, pos=pos, quat=_quat(g.rpy))}"
            f"{_attrs(rgba=nums(g.rgba), contype=contype, conaffinity=conaffinity, group=ROBOT_GROUP)}/>")


def _joint(j: Joint) -> str:
    return (f"<joint{_attrs(name=j.name, type=j.kind, axis=nums(j.axis))}"
            f"{_attrs(range=nums((j.lower, j.upper)) if j.limited else None)}"
            f"{_attrs(armature=num(j.armature) if j.armature else None)}"
            f"{_attrs(damping=num(j.damping) if j.damping else None)}/>")


def _camera(c: Camera) -> str:
    rot = rpy_matrix(c.rpy) @ _MJ_CAMERA_IN_BODY
    return (f"<camera{_attrs(name=c.name, pos=nums(c.xyz), quat=nums(matrix_quat(rot)), fovy=num(c.fovy))}"
            f"{_attrs(resolution=nums(c.resolution))}/>")


def _body(robot: Robot, link: str, pos, rpy, joints: list[Joint], depth: int) -> list[str]:
    pad = "  " * depth
    lines = [f"{pad}<body{_attrs(name=link, pos=nums(pos) if any(pos) else None, quat=_quat(rpy), gravcomp=1)}>"]
    mass, com, inertia = inertial(robot.links[link])
    if mass > 0:
        full = (inertia[0, 0], inertia[1, 1], inertia[2, 2], inertia[0, 1], inertia[0, 2], inertia[1, 2])
        lines.append(f"{pad}  <inertial{_attrs(pos=nums(com), mass=num(mass), fullinertia=nums(full))}/>")
    lines += [f"{pad}  {_joint(j)}" for j in joints if j.kind != "fixed"]
    lines += [f"{pad}  {_geom(g)}" for g in robot.links[link].geoms]
    for site in robot.sites:
        if site.link == link:
            lines.append(f"{pad}  <site{_attrs(name=site.name, pos=nums(site.xyz), quat=_quat(site.rpy))}"
                         f"{_attrs(size='0.008', rgba='1 0.3 0.1 0.8', group=3)}/>")
    lines += [f"{pad}  {_camera(c)}" for c in robot.cameras if c.link == link]
    for child in robot.children(link):
        lines += _body(robot, child.child, child.xyz, child.rpy, [child], depth + 1)
    lines.append(f"{pad}</body>")
    return lines


def _actuators(robot: Robot) -> list[str]:
    lines = []
    for j in robot.movable():
        if j.kp <= 0:
            continue
        lines.append(f"    <position{_attrs(name=j.name, joint=j.name, kp=num(j.kp), kv=num(j.kv) if j.kv else None)}"
                     f"{_attrs(ctrlrange=nums((j.lower, j.upper)) if j.limited else None)}"
                     f"{_attrs(forcerange=nums((-j.effort, j.effort)) if j.effort else None)}/>")
    return lines


def _home_key(robot: Robot, home: dict[str, float]) -> list[str]:
    """``<key name="home">``: the standing pose (qpos and matching servo targets), so a viewer
    or a world server starts the robot with its arms down rather than at all-zero joints."""
    joints = robot.movable()
    qpos = [home.get(j.name, 0.0) for j in joints]
    ctrl = [home.get(j.name, 0.0) for j in joints if j.kp > 0]
    return ["  <keyframe>", f'    <key name="home" qpos="{nums(qpos)}" ctrl="{nums(ctrl)}"/>', "  </keyframe>"]


def to_mjcf(robot: Robot, source: str = "stuart_bt.sim.robot.description",
            home: dict[str, float] | None = None) -> str:
    """The standalone MJCF document (floor, light, robot, one position actuator per joint, and
    a ``home`` keyframe at ``home``, default :data:`description.NEUTRAL`)."""
    width, height = robot.cameras[0].resolution if robot.cameras else (640, 480)
    body = _body(robot, robot.root, robot.root_xyz, (0.0, 0.0, 0.0), list(robot.base_joints), 2)
    lines = [
        f"<!-- Generated by `python -m stuart_bt.sim.robot` from {source}; do not edit by hand. -->",
        f"<mujoco{_attrs(model=robot.name)}>",
        '  <compiler angle="radian" autolimits="true"/>',
        f'  <option timestep="{num(TIMESTEP)}" integrator="implicitfast"/>',
        f'  <visual><global offwidth="{width}" offheight="{height}"/></visual>',
        "  <worldbody>",
        '    <light name="sun" pos="0 0 4" dir="0 0 -1" directional="true"/>',
        '    <geom name="floor" type="plane" size="0 0 0.05" rgba="0.55 0.57 0.6 1"/>',
        *body,
        "  </worldbody>",
        "  <actuator>",
        *_actuators(robot),
        "  </actuator>",
        *_home_key(robot, NEUTRAL if home is None else home),
        "</mujoco>",
    ]
    return "\n".join(lines) + "\n"
