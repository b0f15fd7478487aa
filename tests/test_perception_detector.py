"""The sim detector on rendered head-camera frames (it finds, clips and misses like a real one),
recorded frames (write, read back, same answers), depth noise and dropouts, and the YOLO
detector's refusal to run without local weights."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

pytest.importorskip("cv2", reason="perception needs the 'vision' extra (opencv-python-headless)")
pytest.importorskip("mujoco", reason="rendered frames need the 'sim' extra (mujoco)")

from stuart_bt.core.world import Pose
from stuart_bt.perception.frames import CameraError, Frame, Intrinsics
from stuart_bt.perception.pipeline import Perception
from stuart_bt.perception.projection import CameraMount, project, world_to_torso
from stuart_bt.perception.recorded import RecordedFrames, save_frame
from stuart_bt.perception.sim_camera import DepthNoise, SimCamera
from stuart_bt.perception.sim_detector import SimDetector
from stuart_bt.perception.yolo import DetectorConfigError, YoloDetector
from stuart_bt.sim.world.client import launch_world

KITCHEN = (3.5, 1.5, 0.0)
BOTTLE_REST_Z, APPLE_REST_Z = 0.855, 0.79  # object centres standing on the kitchen table


@pytest.fixture(scope="module")
def world():
    with launch_world(stderr=subprocess.DEVNULL) as w:
        yield w


def look(world, *, at=KITCHEN, objects=None, size=(424, 240), noise=None) -> tuple[Frame, dict]:
    """Stand the robot at ``at``, place objects, let them settle, render one frame."""
    world.call("set_base", x=at[0], y=at[1], yaw=at[2])
    world.call("set_object", label="bottle", x=4.01, y=1.38, z=BOTTLE_REST_Z, yaw=0.0)
    world.call("set_object", label="apple", x=4.35, y=1.85, z=APPLE_REST_Z)
    for label, (x, y, z) in (objects or {}).items():
        world.call("set_object", label=label, x=x, y=y, z=z, yaw=0.0)
    driver = world.clock(driver=True)
    try:
        driver.sleep_until(driver.now() + 0.3)
        camera = SimCamera(world.client(), *size, noise=noise)
        try:
            frame = camera.read()
        finally:
            camera.close()
        return frame, world.call("state")["objects"]
    finally:
        driver.close()


def truth_pixel(frame: Frame, p: dict) -> tuple[float, float]:
    mount = CameraMount.sim()
    return project(mount.to_optical(world_to_torso(np.array([p["x"], p["y"], p["z"]]), frame.robot_pose)),
                   frame.intrinsics)


@pytest.mark.parametrize("size", [(424, 240), (640, 480)])
def test_at_the_kitchen_the_bottle_and_the_apple_are_detected_around_their_true_pixels(world, size):
    frame, truth = look(world, size=size)
    assert frame.rgb.shape == (size[1], size[0], 3) and frame.depth.shape == (size[1], size[0])
    detections = SimDetector().detect(frame)
    assert sorted(d.label for d in detections) == ["apple", "bottle"]
    for d in detections:
        u, v = truth_pixel(frame, truth[d.label])
        u0, v0, u1, v1 = d.box
        assert u0 <= u <= u1 and v0 <= v <= v1, f"{d.label} at ({u:.0f}, {v:.0f}) outside {d.box}"
        assert d.confidence >= 0.75 and d.mask is not None and d.mask.sum() > 100


def test_a_bottle_standing_in_front_of_the_apple_hides_it(world):
    frame, _ = look(world, objects={"apple": (4.12, 1.315, APPLE_REST_Z), "bottle": (4.01, 1.38, BOTTLE_REST_Z)})
    everything = {d.label: d for d in SimDetector(threshold=0.0).detect(frame)}
    assert "bottle" in everything
    kept = [d.label for d in SimDetector().detect(frame)]
    assert "apple" not in kept, f"a mostly hidden apple was detected: {everything.get('apple')}"


def test_an_object_cut_by_the_image_border_is_clipped_and_less_certain(world):
    frame, _ = look(world, objects={"apple": (4.25, 2.05, APPLE_REST_Z)})
    apple = next(d for d in SimDetector(threshold=0.0).detect(frame) if d.label == "apple")
    assert apple.box[0] == 0, "the apple should be cut by the left border"
    whole, _ = look(world)
    whole_apple = next(d for d in SimDetector().detect(whole) if d.label == "apple")
    assert apple.confidence < whole_apple.confidence


def test_two_blobs_of_one_label_are_two_detections():
    labels = np.full((60, 80), -1, dtype=np.int16)
    labels[10:30, 5:25] = 0
    labels[10:30, 50:70] = 0
    frame = Frame(np.zeros((60, 80, 3), np.uint8), np.ones((60, 80), np.float32),
                  Intrinsics(50, 50, 39.5, 29.5, 80, 60), labels=labels, label_names=("bottle",))
    boxes = sorted(d.box for d in SimDetector().detect(frame))
    assert boxes == [(5, 10, 25, 30), (50, 10, 70, 30)]


def test_recorded_frames_read_back_and_give_the_same_positions(world, tmp_path):
    frame, _ = look(world)
    save_frame(tmp_path, 0, frame)
    meta = json.loads((tmp_path / "intrinsics.json").read_text())
    assert meta["depth_scale"] == 0.001 and meta["label_names"] == list(frame.label_names)
    source = RecordedFrames(tmp_path)
    again = source.read()
    assert np.array_equal(again.rgb, frame.rgb) and np.array_equal(again.labels, frame.labels)
    assert np.abs(again.depth - frame.depth).max() <= 0.0005 + 1e-6  # millimetre steps
    assert again.robot_pose.to_dict() == frame.robot_pose.to_dict()
    with pytest.raises(CameraError, match="all 1 frames"):
        source.read()
    perception = Perception(SimDetector(), CameraMount.sim())
    live = {p.detection.label: p.world for p in perception.process(frame)[0]}
    replay = {p.detection.label: p.world for p in perception.process(again)[0]}
    assert live.keys() == replay.keys() == {"apple", "bottle"}
    for label in live:
        assert np.linalg.norm(live[label] - replay[label]) < 0.002


def test_a_folder_without_intrinsics_is_one_clear_error(tmp_path):
    with pytest.raises(CameraError, match="no intrinsics.json in"):
        RecordedFrames(tmp_path)


def test_noisy_depth_with_dropouts_still_places_the_bottle_within_two_and_a_half_centimetres(world):
    frame, truth = look(world, noise=DepthNoise(sigma_at_1m=0.004, dropout=0.2))
    assert (frame.depth == 0).mean() > 0.15  # the dropouts are there
    [bottle] = [p for p in Perception(SimDetector(), CameraMount.sim()).process(frame)[0]
                if p.detection.label == "bottle"]
    t = truth["bottle"]
    assert np.linalg.norm(bottle.world - [t["x"], t["y"], t["z"]]) < 0.025


def test_the_frame_carries_the_localised_pose_of_the_robot(world):
    frame, _ = look(world, at=(3.2, 1.4, 0.1))
    assert frame.robot_pose.to_dict() == Pose(3.2, 1.4, 0.1).to_dict()


def test_yolo_without_weights_says_so_and_fetches_nothing(tmp_path):
    with pytest.raises(DetectorConfigError, match="needs a local ONNX weights file"):
        YoloDetector(None)
    missing = tmp_path / "yolov8n.onnx"
    with pytest.raises(DetectorConfigError, match=f"YOLO weights not found: {missing}"):
        YoloDetector(missing)
    assert not missing.exists()
