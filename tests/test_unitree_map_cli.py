"""``stuart-bt map``: mapping commands reach the robot's SLAM service through the loco daemon,
and bad input gets one clear message before any daemon starts."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from unitree_fake import FakeRobot

pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")

CLI = [str(Path(sys.executable).with_name("stuart-bt"))]


def stuart(*args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*CLI, *args], capture_output=True, text=True, env=env, timeout=60, stdin=subprocess.DEVNULL)


def test_map_start_save_relocalise_and_close_send_the_slam_ids_and_paths():
    with FakeRobot() as robot:
        assert stuart("map", "start", env=robot.env).returncode == 0
        saved = stuart("map", "save", "/home/unitree/lab.pcd", env=robot.env)
        assert saved.returncode == 0, saved.stderr
        assert json.loads(saved.stdout) == {"saved": "/home/unitree/lab.pcd"}
        relocalised = stuart("map", "relocalise", "/home/unitree/lab.pcd", "--pose", "1.5,-2,1.5708", env=robot.env)
        assert relocalised.returncode == 0, relocalised.stderr
        pose = stuart("map", "pose", env=robot.env)
        assert pose.returncode == 0, pose.stderr
        assert json.loads(pose.stdout)["pose"] == pytest.approx({"x": 1.5, "y": -2.0, "yaw": 1.5708}, abs=1e-3)
        assert stuart("map", "close", env=robot.env).returncode == 0
        calls = {r["api"]: r["parameter"]["data"] for r in robot.rpc("slam_operate")}
    assert set(calls) == {1801, 1802, 1804, 1901}
    assert calls[1802] == {"address": "/home/unitree/lab.pcd"}
    assert (calls[1804]["x"], calls[1804]["y"], calls[1804]["address"]) == (1.5, -2.0, "/home/unitree/lab.pcd")
    assert calls[1804]["q_z"] == pytest.approx(0.7071, abs=1e-3)


def test_a_map_that_fails_to_load_reports_the_vendor_code():
    with FakeRobot() as robot:
        failed = stuart("map", "relocalise", "/home/unitree/missing.pcd", env=robot.env)
    assert failed.returncode == 1
    assert "vendor code 507" in failed.stderr and "map could not be loaded" in failed.stderr
    assert "Traceback" not in failed.stderr


@pytest.mark.parametrize("args, message", [
    (("save",), "map save needs PATH"),
    (("save", "lab.map"), "PATH must be an absolute .pcd path"),
    (("relocalise", "/home/unitree/lab.pcd", "--pose", "1,2"), "--pose must be X,Y,YAW"),
    (("start", "/home/unitree/lab.pcd"), "map start takes no PATH"),
])
def test_bad_map_input_is_one_message(args, message):
    result = stuart("map", *args)
    assert result.returncode == 1
    assert len(result.stderr.strip().splitlines()) == 1 and result.stderr.startswith("stuart-bt: ")
    assert message in result.stderr
