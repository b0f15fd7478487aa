"""Gesture keyframes: every library gesture has a valid trajectory on the sim model that starts
and ends where it should and looks like its name (checked with MuJoCo forward kinematics);
validation and the gesture file format report every problem."""

from __future__ import annotations

import json

import numpy as np
import pytest

from stuart_bt.core import gestures
from stuart_bt.skills.gesture.backend import Keyframe
from stuart_bt.skills.gesture.keyframes import (
    NEUTRAL,
    GestureFileError,
    end_pose,
    gesture_file_problems,
    keyframes,
    load_gesture_file,
    save_gesture_file,
    validate_keyframes,
)

mujoco = pytest.importorskip("mujoco")

from stuart_bt.sim.robot import MJCF_PATH  # noqa: E402

ALL = sorted(gestures.LIBRARY)
ARM_AND_HAND = set(NEUTRAL)


@pytest.fixture(scope="module")
def mj():
    model = mujoco.MjModel.from_xml_path(str(MJCF_PATH))
    return model, mujoco.MjData(model)


def hands(mj, joints: dict[str, float]) -> dict[str, np.ndarray]:
    """Both hand points in torso_link (MuJoCo FK, base and waist at zero)."""
    model, data = mj
    data.qpos[:] = 0.0
    for name, value in joints.items():
        data.qpos[model.jnt_qposadr[model.joint(name).id]] = value
    mujoco.mj_kinematics(model, data)
    torso = model.body("torso_link").id
    rot_t = data.xmat[torso].reshape(3, 3).T
    return {arm: rot_t @ (data.site(f"{arm}_hand_point").xpos - data.xpos[torso]) for arm in ("left", "right")}


def same(a: dict[str, float], b: dict[str, float]) -> bool:
    return a.keys() == b.keys() and all(abs(a[k] - b[k]) < 1e-9 for k in a)


@pytest.mark.parametrize("name", ALL)
def test_every_gesture_validates_and_lasts_its_duration(name, mj) -> None:
    frames = keyframes(name)
    assert validate_keyframes(frames) == []
    assert frames[0].t == 0.0
    assert frames[-1].t == pytest.approx(gestures.LIBRARY[name].duration, rel=0.1)
    model, _ = mj
    for frame in frames:
        assert set(frame.joints) == ARM_AND_HAND  # every frame names every arm and hand joint
        for joint, value in frame.joints.items():  # limits straight from the MJCF, not the description
            lo, hi = model.jnt_range[model.joint(joint).id]
            assert lo <= value <= hi, (name, frame.t, joint, value)


@pytest.mark.parametrize("name", ALL)
def test_start_and_end_poses(name) -> None:
    gesture = gestures.LIBRARY[name]
    frames = keyframes(name)
    assert same(frames[0].joints, NEUTRAL)
    if gesture.holds:
        assert not same(frames[-1].joints, NEUTRAL), "a held gesture ends in its pose"
        assert same(frames[-1].joints, frames[-2].joints), "the held pose is reached before the end and kept"
    else:
        assert same(frames[-1].joints, NEUTRAL)
    if name != "release arm":  # from neutral, releasing is standing still for its duration
        assert len({json.dumps(f.joints, sort_keys=True) for f in frames}) >= 2  # something moves


def test_release_arm_returns_from_a_held_pose_to_neutral() -> None:
    held = end_pose("hands up")
    frames = keyframes("release arm", start=held)
    assert same(frames[0].joints, held) and same(frames[-1].joints, NEUTRAL)
    assert frames[-1].t == gestures.LIBRARY["release arm"].duration
    assert same(keyframes("release_arm")[0].joints, NEUTRAL)  # any accepted spelling


def test_aliases_and_unknown_names() -> None:
    assert keyframes("wave") == keyframes("high wave")
    with pytest.raises(ValueError, match="did you mean 'clap'"):
        keyframes("clapp")


def test_clap_brings_the_hands_together_in_front(mj) -> None:
    gaps = []
    for frame in keyframes("clap"):
        h = hands(mj, frame.joints)
        gaps.append((float(np.linalg.norm(h["left"] - h["right"])), h))
    closest, h = min(gaps, key=lambda g: g[0])
    assert closest < 0.10
    assert h["left"][0] > 0.2 and h["right"][0] > 0.2  # in front of the chest
    assert sum(1 for gap, _ in gaps if gap < 0.10) >= 2  # more than one clap
    assert max(gap for gap, _ in gaps) > 0.25  # and apart in between


def test_high_wave_raises_the_right_hand_and_waves_it(mj) -> None:
    frames = keyframes("high wave")
    raised = [hands(mj, f.joints) for f in frames[1:-1]]
    assert all(h["right"][2] > 0.4 for h in raised)  # above the shoulders (torso_link z 0.248)
    ys = [h["right"][1] for h in raised]
    assert max(ys) - min(ys) > 0.1  # side to side
    left = [hands(mj, f.joints)["left"] for f in frames]
    assert max(np.linalg.norm(p - left[0]) for p in left) < 1e-9  # the left arm stays down


def test_heart_hands_meet_over_the_chest(mj) -> None:
    h = hands(mj, end_pose("heart"))
    assert np.linalg.norm(h["left"] - h["right"]) < 0.10
    for p in h.values():
        assert 0.12 < p[0] < 0.35 and 0.1 < p[2] < 0.35  # before the chest, at chest height


def test_hands_up_and_high_five_are_up(mj) -> None:
    up = hands(mj, end_pose("hands up"))
    assert up["left"][2] > 0.6 and up["right"][2] > 0.6
    five = hands(mj, end_pose("high five"))
    assert five["right"][2] > 0.4 and five["left"][2] < 0.0


def test_shake_hand_offers_the_right_hand_forward(mj) -> None:
    h = hands(mj, end_pose("shake hand"))
    assert h["right"][0] > 0.25 and -0.1 < h["right"][2] < 0.15


# --- validation -------------------------------------------------------------------------------

def test_validation_reports_each_problem() -> None:
    frames = [
        Keyframe(0.5, {"left_elbo_joint": 0.2}),
        Keyframe(-1.0, {"left_elbow_joint": 3.0}),
        Keyframe(0.2, {"right_shoulder_roll_joint": 2.0, "waist_yaw_joint": 0.1}),
        {"t": "soon", "joints": {"left_wrist_yaw_joint": "far"}},
        "not a frame",
    ]
    problems = validate_keyframes(frames)  # type: ignore[arg-type]
    text = "\n".join(problems)
    assert "keyframe 0: unknown joint 'left_elbo_joint' (did you mean 'left_elbow_joint'?)" in text
    assert "keyframe 1: t = -1 s is negative" in text
    assert "keyframe 1: t = -1 s does not come after the previous keyframe's 0.5 s" in text
    assert "keyframe 1: left_elbow_joint = 3.0000 rad is outside its limits [-1.0472, 2.0944]" in text
    assert "keyframe 2: right_shoulder_roll_joint = 2.0000 rad is outside its limits [-2.2515, 1.5882]" in text
    assert "keyframe 3: t 'soon' is not a number" in text
    assert "keyframe 3: left_wrist_yaw_joint = 'far' is not a number" in text
    assert "keyframe 4: must be an object" in text
    assert not any("waist_yaw_joint" in p for p in problems)  # the waist may take part
    assert validate_keyframes([]) == ["there are no keyframes"]
    assert any("base_x" in p and "unknown" in p for p in validate_keyframes([Keyframe(0.0, {"base_x": 1.0})]))


# --- files -------------------------------------------------------------------------------------

def test_save_and_load_round_trip(tmp_path) -> None:
    frames = keyframes("face wave")
    path = save_gesture_file(tmp_path / "wave.json", "my wave", frames)
    loaded = load_gesture_file(path)
    assert loaded.name == "my wave"
    assert [f.t for f in loaded.keyframes] == [f.t for f in frames]
    for a, b in zip(loaded.keyframes, frames, strict=True):
        assert a.joints.keys() == b.joints.keys()
        assert all(abs(a.joints[k] - b.joints[k]) < 1e-4 for k in a.joints)
    doc = json.loads(path.read_text())
    assert set(doc) == {"name", "keyframes"} and set(doc["keyframes"][0]) == {"t", "joints"}


def test_a_bad_file_gets_every_problem_reported(tmp_path) -> None:
    path = tmp_path / "bad.json"
    path.write_text(json.dumps({
        "nmae": "typo",
        "keyframes": [
            {"t": 0.0, "joints": {"left_elbow_joint": 1.0}, "speed": 2},
            {"t": 0.0, "joints": {"right_elbow_jiont": 1.0}},
            {"t": -2, "joints": {"right_wrist_pitch_joint": 2.5}},
        ],
    }))
    problems = gesture_file_problems(path)
    text = "\n".join(problems)
    assert "unknown key 'nmae' (did you mean 'name'?)" in text
    assert "'name' must be a non-empty string" in text
    assert "keyframe 0: unknown key 'speed'" in text
    assert "keyframe 1: t = 0 s does not come after the previous keyframe's 0 s" in text
    assert "keyframe 1: unknown joint 'right_elbow_jiont' (did you mean 'right_elbow_joint'?)" in text
    assert "keyframe 2: t = -2 s is negative" in text
    assert "keyframe 2: right_wrist_pitch_joint = 2.5000 rad is outside its limits [-1.6144, 1.6144]" in text
    with pytest.raises(GestureFileError) as caught:
        load_gesture_file(path)
    assert caught.value.problems == problems


@pytest.mark.parametrize("content,expected", [
    (None, "file not found"),
    ("{not json", "not JSON"),
    ("[1, 2]", "must be a JSON object"),
    ('{"name": "x", "keyframes": []}', "'keyframes' must be a non-empty list"),
])
def test_unreadable_files(tmp_path, content, expected) -> None:
    path = tmp_path / "g.json"
    if content is not None:
        path.write_text(content)
    assert any(expected in p for p in gesture_file_problems(path))


def test_save_refuses_bad_frames(tmp_path) -> None:
    path = tmp_path / "never.json"
    with pytest.raises(GestureFileError, match="outside its limits"):
        save_gesture_file(path, "bad", [Keyframe(0.0, {"left_elbow_joint": 5.0})])
    with pytest.raises(GestureFileError, match="'name'"):
        save_gesture_file(path, "", keyframes("clap"))
    assert not path.exists()


def test_a_value_at_a_joint_limit_survives_saving_and_loading(tmp_path):
    from stuart_bt.skills.gesture.backend import Keyframe
    from stuart_bt.skills.gesture.keyframes import _LIMITS, NEUTRAL, load_gesture_file, save_gesture_file

    joint = "right_elbow_joint"
    low, high = _LIMITS[joint]
    frames = [Keyframe(0.0, dict(NEUTRAL)), Keyframe(1.0, {**NEUTRAL, joint: high}),
              Keyframe(2.0, {**NEUTRAL, joint: low})]
    loaded = load_gesture_file(save_gesture_file(tmp_path / "edge.json", "edge", frames))
    assert low <= loaded.keyframes[2].joints[joint] <= loaded.keyframes[1].joints[joint] <= high
