"""Cameras on demand (size, intrinsics, metric depth at a known object) and recordings."""

from __future__ import annotations

import subprocess
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from stuart_bt.sim.world.client import WorldError, launch_world
from stuart_bt.sim.world.scene import default_robot_path

STANDIN = Path(__file__).parent / "data" / "standin_robot.xml"
ROBOT = None if default_robot_path().is_file() else STANDIN
BOOK_HALF_HEIGHT = 0.016


@pytest.fixture(scope="module")
def world():
    with launch_world(robot=ROBOT, stderr=subprocess.DEVNULL) as w:
        yield w


def test_head_camera_depth_at_a_known_object(world, tmp_path):
    world.call("set_base", x=0.0, y=0.0, yaw=0.0)
    book = np.array([1.0, 0.05, BOOK_HALF_HEIGHT])  # lying on the floor ahead, in the camera's view
    world.call("set_object", label="book", x=float(book[0]), y=float(book[1]), z=float(book[2]), yaw=0.0)
    driver = world.clock(driver=True)  # hold still while rendering and comparing
    try:
        reply = world.call("render", camera="head_camera", width=320, height=240, depth=True,
                           path=str(tmp_path / "head.png"))
    finally:
        driver.close()
    rgb = np.asarray(Image.open(reply["path"]))
    depth = np.load(reply["depth_path"])
    assert rgb.shape == (240, 320, 3) and depth.shape == (240, 320) and depth.dtype == np.float32
    k = reply["intrinsics"]
    assert k["cx"] == pytest.approx(159.5) and k["cy"] == pytest.approx(119.5) and k["fx"] == k["fy"] > 0
    # Project the middle of the book's top face into the image; the depth there is its z in
    # the optical frame.
    top = book + [0.0, 0.0, BOOK_HALF_HEIGHT]
    position = np.array(reply["camera_pose"]["position"])
    rotation = np.array(reply["camera_pose"]["rotation"])
    x, y, z = rotation.T @ (top - position)
    u, v = k["fx"] * x / z + k["cx"], k["fy"] * y / z + k["cy"]
    assert 0 <= u < 320 and 0 <= v < 240, (u, v)
    measured = float(depth[int(round(v)), int(round(u))])
    assert measured == pytest.approx(z, abs=0.01)
    assert 0.5 < z < 2.5
    r, g, b = rgb[int(round(v)), int(round(u))].astype(int)
    assert g > r and g > b  # the book is green


def test_render_rejects_bad_requests(world, tmp_path):
    with pytest.raises(WorldError) as e:
        world.call("render", camera="tail_camera", path=str(tmp_path / "x.png"))
    assert e.value.code == "not_found"
    with pytest.raises(WorldError) as e:
        world.call("render", camera="chase", width=100000, path=str(tmp_path / "x.png"))
    assert e.value.code == "bad_request"


def test_chase_camera_render(world, tmp_path):
    reply = world.call("render", camera="chase", width=160, height=120, path=str(tmp_path / "chase.png"))
    image = Image.open(reply["path"])
    assert image.size == (160, 120)
    assert reply["depth_path"] is None
    assert np.asarray(image).std() > 5  # not a blank frame


@pytest.mark.parametrize("suffix", ["mp4", "gif"])
def test_recording_writes_a_video(world, tmp_path, suffix):
    path = tmp_path / f"run.{suffix}"
    world.call("set_base", x=0.0, y=0.0, yaw=0.0)
    start = world.call("record", path=str(path), fps=10, width=160, height=128)
    assert start["path"] == str(path)
    world.call("base_velocity", wz=1.0, duration=1.0)
    t0 = world.call("state")["t"]
    deadline = time.monotonic() + 30
    while world.call("state")["t"] < t0 + 1.0:
        assert time.monotonic() < deadline
        time.sleep(0.01)
    done = world.call("record_stop")["recordings"]
    assert len(done) == 1 and done[0]["frames"] >= 10
    assert path.stat().st_size > 1000
    if suffix == "gif":
        with Image.open(path) as gif:  # Pillow merges identical consecutive frames, adding their durations
            assert gif.size == (160, 128) and 2 <= gif.n_frames <= done[0]["frames"]
            total_ms = 0
            for i in range(gif.n_frames):
                gif.seek(i)
                total_ms += gif.info["duration"]
            assert total_ms == pytest.approx(done[0]["frames"] * 100, abs=gif.n_frames)  # 10 fps
    else:
        import imageio.v2 as imageio

        with imageio.get_reader(str(path)) as reader:
            frames = sum(1 for _ in reader)
        assert frames == done[0]["frames"]


def test_record_for_the_whole_run_and_the_map(tmp_path):
    video, picture = tmp_path / "whole.gif", tmp_path / "map.png"
    with launch_world(robot=ROBOT, record=str(video), record_fps=5, map_out=str(picture),
                      stderr=subprocess.DEVNULL) as w:
        w.call("base_path", waypoints=[[1.0, 0.0]])
        deadline = time.monotonic() + 30
        while w.call("state")["base_status"] != "arrived":
            assert time.monotonic() < deadline
            time.sleep(0.01)
    assert video.stat().st_size > 1000
    with Image.open(picture) as image:
        assert image.size[0] > 400 and image.size[1] > 300
