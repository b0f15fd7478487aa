"""The generated G1 model files: up to date, loadable by MuJoCo and Pinocchio, and true to
FIELD_NOTES (joint names and limits, geometry, camera, mass). MuJoCo and Pinocchio must agree
on the hand points: the IK (Pinocchio/PlaCo) plans what the simulator (MuJoCo) plays."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco")
pin = pytest.importorskip("pinocchio")

from stuart_bt.sim.robot import MJCF_PATH, URDF_PATH, description  # noqa: E402

# FIELD_NOTES, typed in again here on purpose (not read from the description under test)
LEFT_LIMITS = {
    "left_shoulder_pitch_joint": (-3.0892, 2.6704),
    "left_shoulder_roll_joint": (-1.5882, 2.2515),
    "left_shoulder_yaw_joint": (-2.618, 2.618),
    "left_elbow_joint": (-1.0472, 2.0944),
    "left_wrist_roll_joint": (-1.972, 1.972),
    "left_wrist_pitch_joint": (-1.614, 1.614),
    "left_wrist_yaw_joint": (-1.614, 1.614),
}
RIGHT_LIMITS = {name.replace("left_", "right_"): ((-hi, -lo) if "roll" in name and "shoulder" in name else (lo, hi))
                for name, (lo, hi) in LEFT_LIMITS.items()}
HAND_KINDS = ("thumb_0", "thumb_1", "thumb_2", "index_0", "index_1", "middle_0", "middle_1")
HAND_JOINTS = [f"{s}_hand_{k}_joint" for s in ("left", "right") for k in HAND_KINDS]
CAMERA_XYZ = (0.0576, 0.0175, 0.4299)
CAMERA_PITCH_DEG = 47.6


@pytest.fixture(scope="module")
def mj():
    model = mujoco.MjModel.from_xml_path(str(MJCF_PATH))
    return model, mujoco.MjData(model)


@pytest.fixture(scope="module")
def pin_model():
    model = pin.buildModelFromUrdf(str(URDF_PATH))
    return model, model.createData()


def qpos_index(model, joint: str) -> int:
    return int(model.jnt_qposadr[model.joint(joint).id])


def set_joints(model, data, joints: dict[str, float]) -> None:
    data.qpos[:] = 0.0
    for name, value in joints.items():
        data.qpos[qpos_index(model, name)] = value
    mujoco.mj_kinematics(model, data)
    mujoco.mj_camlight(model, data)  # cameras are placed in a step of their own


def in_torso(model, data, point: np.ndarray) -> np.ndarray:
    torso = model.body("torso_link").id
    return data.xmat[torso].reshape(3, 3).T @ (point - data.xpos[torso])


# --- files ----------------------------------------------------------------------------------------

def test_committed_files_match_the_description() -> None:
    done = subprocess.run([sys.executable, "-m", "stuart_bt.sim.robot", "--check"], capture_output=True, text=True,
                          timeout=60, check=False)
    assert done.returncode == 0, f"model files drifted from sim/robot/description.py:\n{done.stderr}"


def test_check_reports_a_drifted_file(tmp_path, monkeypatch) -> None:
    from stuart_bt.sim.robot import __main__ as cli

    fake = tmp_path / "g1.xml"
    fake.write_text("<mujoco/>")
    monkeypatch.setattr(cli, "MJCF_PATH", fake)
    assert cli.stale() == [fake]
    assert cli.main(["--check"]) == 1


def test_both_files_load(mj, pin_model) -> None:
    model, _ = mj
    assert model.nq == 3 + 3 + 14 + 14  # base, waist, arms, hands
    pmodel, _ = pin_model
    assert pmodel.nq == 3 + 14 + 14  # the URDF leaves the base joints out (root: pelvis)
    assert pmodel.names[1] == "waist_yaw_joint"


def test_pinocchio_reads_the_mjcf_too() -> None:
    model = pin.buildModelFromMJCF(str(MJCF_PATH))
    names = set(model.names)
    assert set(LEFT_LIMITS) | set(RIGHT_LIMITS) | set(HAND_JOINTS) <= names


# --- joints ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("name,limits", sorted({**LEFT_LIMITS, **RIGHT_LIMITS}.items()))
def test_arm_joint_names_and_limits_match_field_notes(mj, pin_model, name, limits) -> None:
    model, _ = mj
    lo, hi = model.jnt_range[model.joint(name).id]
    assert (lo, hi) == pytest.approx(limits, abs=1e-3)
    pmodel, _ = pin_model
    j = pmodel.getJointId(name)
    q = pmodel.joints[j].idx_q
    assert (pmodel.lowerPositionLimit[q], pmodel.upperPositionLimit[q]) == pytest.approx(limits, abs=1e-3)


def test_hand_waist_and_base_joints_exist_with_actuators(mj) -> None:
    model, _ = mj
    expected = [*HAND_JOINTS, *LEFT_LIMITS, *RIGHT_LIMITS, "waist_yaw_joint", "waist_roll_joint", "waist_pitch_joint",
                "base_x", "base_y", "base_yaw"]
    for name in expected:
        joint = model.joint(name)
        actuator = model.actuator(name)  # a position servo named like its joint
        assert actuator.trnid[0] == joint.id
        assert model.actuator_gainprm[actuator.id][0] > 0
    assert model.nu == len(expected)
    for name in HAND_JOINTS:  # every finger can move both ways from somewhere in its range
        lo, hi = model.jnt_range[model.joint(name).id]
        assert hi - lo > 0.5


def test_arm_joint_semantics(mj) -> None:
    """Vendor semantics: pitch < 0 raises the arm forward, left roll > 0 raises it sideways,
    elbow 0 is a right angle with the forearm forward."""
    model, data = mj
    def hand(**joints: float) -> np.ndarray:
        set_joints(model, data, {f"left_{k}_joint": v for k, v in joints.items()})
        return in_torso(model, data, data.site("left_hand_point").xpos)
    shoulder = np.array([0.004, 0.100, 0.248])
    forward = hand(elbow=math.pi / 2, shoulder_pitch=-math.pi / 2) - shoulder
    assert forward[0] > 0.4 and abs(forward[2]) < 0.01
    sideways = hand(elbow=math.pi / 2, shoulder_roll=math.pi / 2) - shoulder
    assert sideways[1] > 0.4 and abs(sideways[2]) < 0.01
    bent = hand() - shoulder
    assert bent[0] == pytest.approx(0.234, abs=1e-3) and bent[2] == pytest.approx(-0.1845, abs=1e-3)


# --- kinematics -------------------------------------------------------------------------------

def test_hand_points_agree_between_mujoco_and_pinocchio(mj, pin_model) -> None:
    model, data = mj
    pmodel, pdata = pin_model
    rng = np.random.default_rng(7)
    limited = [n for n in (*LEFT_LIMITS, *RIGHT_LIMITS, "waist_yaw_joint", "waist_roll_joint", "waist_pitch_joint")]
    worst = 0.0
    for _ in range(60):
        joints = {n: rng.uniform(*model.jnt_range[model.joint(n).id]) for n in limited}
        set_joints(model, data, joints)
        q = pin.neutral(pmodel)
        for name, value in joints.items():
            q[pmodel.joints[pmodel.getJointId(name)].idx_q] = value
        pin.framesForwardKinematics(pmodel, pdata, q)
        torso = pdata.oMf[pmodel.getFrameId("torso_link")]
        for site in ("left_hand_point", "right_hand_point"):
            from_pin = torso.actInv(pdata.oMf[pmodel.getFrameId(site)]).translation
            from_mj = in_torso(model, data, data.site(site).xpos)
            worst = max(worst, float(np.linalg.norm(from_pin - from_mj)))
    assert worst < 1e-3


@pytest.mark.parametrize("side", ["left", "right"])
def test_straight_arm_reach_from_the_shoulder(mj, side) -> None:
    model, data = mj
    set_joints(model, data, {f"{side}_elbow_joint": math.pi / 2})  # straight arm, hanging
    shoulder = data.xpos[model.body(f"{side}_shoulder_pitch_link").id]
    reach = float(np.linalg.norm(data.site(f"{side}_hand_point").xpos - shoulder))
    assert reach == pytest.approx(0.42, abs=0.03)
    assert in_torso(model, data, shoulder) == pytest.approx([0.004, 0.100 if side == "left" else -0.100, 0.248],
                                                            abs=1e-6)


def test_standing_heights(mj) -> None:
    model, data = mj
    set_joints(model, data, {})
    assert data.xpos[model.body("pelvis").id][2] == pytest.approx(0.793, abs=1e-6)
    assert data.xpos[model.body("torso_link").id][2] == pytest.approx(0.837, abs=0.005)
    assert data.xpos[model.body("left_shoulder_pitch_link").id][2] == pytest.approx(1.085, abs=0.005)
    top = max(data.geom_xpos[g][2] + model.geom_rbound[g] for g in range(model.ngeom)
              if model.geom_bodyid[g] == model.body("head_link").id)
    assert top == pytest.approx(1.32, abs=0.02)


def test_total_mass(mj, pin_model) -> None:
    model, _ = mj
    mass = float(model.body_mass.sum())
    assert mass == pytest.approx(34.0, rel=0.10)
    pmodel, _ = pin_model
    assert sum(i.mass for i in pmodel.inertias) == pytest.approx(mass, rel=1e-6)


# --- sensors --------------------------------------------------------------------------------

def camera_in_torso(model, data):
    set_joints(model, data, {})
    cam = model.camera("head_camera").id
    torso = model.body("torso_link").id
    rot_torso = data.xmat[torso].reshape(3, 3)
    position = rot_torso.T @ (data.cam_xpos[cam] - data.xpos[torso])
    rot = rot_torso.T @ data.cam_xmat[cam].reshape(3, 3)
    return position, rot


def test_head_camera_pose_and_pitch(mj) -> None:
    model, data = mj
    position, rot = camera_in_torso(model, data)
    assert position == pytest.approx(CAMERA_XYZ, abs=1e-6)
    view = -rot[:, 2]  # MuJoCo cameras look along -z
    pitch_down = math.degrees(math.atan2(-view[2], view[0]))
    assert pitch_down == pytest.approx(CAMERA_PITCH_DEG, abs=0.1)
    assert abs(view[1]) < 1e-9  # straight ahead, no yaw
    assert rot[:, 1][2] > 0.5 and rot[:, 1][0] > 0  # image up is up (and, pitched down, a bit forward)
    assert rot[:, 0] == pytest.approx([0.0, -1.0, 0.0], abs=1e-9)  # image right is the robot's right


def project(model, data, point: np.ndarray, width: int = 640, height: int = 480) -> tuple[float, float]:
    """Pixel (u right, v down) of a world point in head_camera, pinhole with MuJoCo's fovy."""
    cam = model.camera("head_camera").id
    local = data.cam_xmat[cam].reshape(3, 3).T @ (point - data.cam_xpos[cam])
    depth = -local[2]
    assert depth > 0, "behind the camera"
    focal = (height / 2) / math.tan(math.radians(model.cam_fovy[cam]) / 2)
    return width / 2 + focal * local[0] / depth, height / 2 - focal * local[1] / depth


def test_floor_one_metre_ahead_projects_centre_bottom(mj) -> None:
    model, data = mj
    set_joints(model, data, {})
    u, v = project(model, data, np.array([1.0, 0.0, 0.0]))
    assert abs(u - 320) < 0.1 * 640  # centred
    assert 240 < v < 480  # below the middle, inside the image
    _, v_far = project(model, data, np.array([2.0, 0.0, 0.0]))
    assert v_far < v  # further away is higher in the image
    u_left, _ = project(model, data, np.array([1.0, 0.3, 0.0]))
    assert u_left < u  # the robot's left is the image's left


RENDER_SCRIPT = textwrap.dedent("""
    import json, sys
    import mujoco, numpy as np
    spec = mujoco.MjSpec.from_file(sys.argv[1])
    ball = spec.worldbody.add_geom()
    ball.name, ball.type, ball.size, ball.pos, ball.rgba = (
        "marker", mujoco.mjtGeom.mjGEOM_SPHERE, [0.04, 0, 0], [1.0, 0.0, 0.04], [1, 0, 0, 1])
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    try:
        renderer = mujoco.Renderer(model, 480, 640)
    except Exception as e:
        print(json.dumps({"skip": str(e)}))
        sys.exit(0)
    renderer.update_scene(data, camera="head_camera")
    image = renderer.render()
    red = (image[:, :, 0] > 150) & (image[:, :, 1] < 80) & (image[:, :, 2] < 80)
    rows, cols = np.nonzero(red)
    print(json.dumps({"pixels": int(rows.size), "row": float(rows.mean()) if rows.size else -1,
                      "col": float(cols.mean()) if rows.size else -1}))
""")


def test_rendered_marker_lands_where_projected(mj) -> None:
    """Render through MuJoCo itself (EGL on the CPU, in a child process because the GL
    back end is fixed at import): a red ball 1 m ahead on the floor shows up in the lower
    middle of the image, where the projection says."""
    env = {**os.environ, "MUJOCO_GL": "egl"}
    done = subprocess.run([sys.executable, "-c", RENDER_SCRIPT, str(MJCF_PATH)], capture_output=True, text=True,
                          timeout=60, env=env, check=False)
    if done.returncode != 0:
        pytest.skip(f"no offscreen rendering here: {done.stderr.strip().splitlines()[-1:]}")
    seen = json.loads(done.stdout.strip().splitlines()[-1])
    if "skip" in seen:
        pytest.skip(f"no offscreen rendering here: {seen['skip']}")
    model, data = mj
    set_joints(model, data, {})
    u, v = project(model, data, np.array([1.0, 0.0, 0.04]))
    assert seen["pixels"] > 50
    assert abs(seen["col"] - u) < 10 and abs(seen["row"] - v) < 10
    assert 240 < seen["row"] < 480 and abs(seen["col"] - 320) < 64


def test_lidar_is_upside_down_on_the_head(mj) -> None:
    model, data = mj
    set_joints(model, data, {})
    site = data.site("lidar")
    assert in_torso(model, data, site.xpos) == pytest.approx([0.0003, 0.0, 0.4284], abs=1e-6)
    assert site.xmat.reshape(3, 3)[:, 2] == pytest.approx([0, 0, -1], abs=1e-9)


# --- simulation -------------------------------------------------------------------------------

def test_servos_hold_and_track(mj) -> None:
    model, _ = mj
    data = mujoco.MjData(model)
    for name, value in description.NEUTRAL.items():
        data.qpos[qpos_index(model, name)] = value
        data.ctrl[model.actuator(name).id] = value
    data.ctrl[model.actuator("right_shoulder_pitch_joint").id] = -1.2
    data.ctrl[model.actuator("base_x").id] = 0.3
    for _ in range(1000):  # 2 s
        mujoco.mj_step(model, data)
    assert data.qpos[qpos_index(model, "right_shoulder_pitch_joint")] == pytest.approx(-1.2, abs=0.01)
    assert data.qpos[qpos_index(model, "left_elbow_joint")] == pytest.approx(description.NEUTRAL["left_elbow_joint"],
                                                                            abs=0.01)
    assert data.qpos[qpos_index(model, "base_x")] == pytest.approx(0.3, abs=0.01)
    assert np.all(np.isfinite(data.qpos))


def test_a_scene_can_attach_the_robot() -> None:
    scene = mujoco.MjSpec()
    scene.worldbody.add_geom(name="ground", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[5, 5, 0.1])
    robot = mujoco.MjSpec.from_file(str(MJCF_PATH))
    frame = scene.worldbody.add_frame(pos=[2.0, 1.0, 0.0])
    with warnings.catch_warnings():  # MuJoCo warns about the empty prefix and the scene's own options
        warnings.simplefilter("ignore")
        frame.attach_body(robot.body("pelvis"), "", "")
        model = scene.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert model.nu == 34 and model.camera("head_camera") and model.site("left_hand_point")
    assert data.xpos[model.body("pelvis").id] == pytest.approx([2.0, 1.0, 0.793])


def test_urdf_camera_frames_look_where_the_mujoco_camera_looks(mj, pin_model) -> None:
    """URDF ``head_camera`` is a REP-103 body frame (x along the view), ``head_camera_optical``
    the ROS optical frame (z along the view, x right, y down); both match the MuJoCo camera."""
    model, data = mj
    position, rot = camera_in_torso(model, data)
    view, right, up = -rot[:, 2], rot[:, 0], rot[:, 1]
    pmodel, pdata = pin_model
    pin.framesForwardKinematics(pmodel, pdata, pin.neutral(pmodel))
    torso = pdata.oMf[pmodel.getFrameId("torso_link")]
    body = torso.actInv(pdata.oMf[pmodel.getFrameId("head_camera")])
    optical = torso.actInv(pdata.oMf[pmodel.getFrameId("head_camera_optical")])
    assert body.translation == pytest.approx(position, abs=1e-7)
    assert body.rotation[:, 0] == pytest.approx(view, abs=1e-7)
    assert body.rotation[:, 2] == pytest.approx(up, abs=1e-7)
    assert optical.rotation[:, 2] == pytest.approx(view, abs=1e-7)
    assert optical.rotation[:, 0] == pytest.approx(right, abs=1e-7)
    assert optical.rotation[:, 1] == pytest.approx(-up, abs=1e-7)


def test_home_keyframe_is_the_neutral_pose(mj) -> None:
    model, _ = mj
    key = model.key("home")
    for name, value in description.NEUTRAL.items():
        assert key.qpos[qpos_index(model, name)] == pytest.approx(value)
        assert key.ctrl[model.actuator(name).id] == pytest.approx(value)
    assert key.qpos[qpos_index(model, "base_x")] == 0.0
