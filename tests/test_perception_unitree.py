"""The robot's vision daemon (RealSense + YOLO + the SDK's odometry) refuses to start, in one
line and before READY, when what it needs is not there: nothing is downloaded or guessed."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")
pytest.importorskip("cv2", reason="perception needs the 'vision' extra (opencv-python-headless)")

LINK = {"interface": "lo", "domain": 231, "probe_timeout": 0.2}


def start(options: dict) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "stuart_bt.skills.vision", "--backend", "unitree",
                           "--options", json.dumps({**LINK, **options})],
                          capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)


@pytest.mark.parametrize("options, message", [
    ({}, "vision unitree: the yolo detector needs a local ONNX weights file (option 'weights')"),
    ({"weights": "/nonexistent/yolov8n.onnx"}, "vision unitree: YOLO weights not found: /nonexistent/yolov8n.onnx"),
    ({"mount": "tilted"}, "'mount' must be one of"),
    ({"colour": "red"}, "unknown"),
])
def test_missing_or_wrong_settings_stop_it_before_ready_in_one_line(options, message):
    done = start(options)
    assert done.returncode != 0 and done.stdout == ""  # no READY line
    problems = [line for line in done.stderr.splitlines() if "failed to start" in line or "vision" in line]
    assert any(message in line for line in problems), done.stderr
    assert "Traceback" not in done.stderr
