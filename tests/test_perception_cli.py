"""``stuart-bt perceive`` as a person uses it: a scene arranged on the command line, the table of
detections with torso and world positions, the annotated picture, the map with the memory, a
replay of recorded frames, and bad input as one sentence with exit status 2."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("cv2", reason="perception needs the 'vision' extra (opencv-python-headless)")
pytest.importorskip("mujoco", reason="perceive --backend sim needs the 'sim' extra (mujoco)")

REPO = Path(__file__).resolve().parents[1]
CLI = [sys.executable, "-m", "stuart_bt.cli", "perceive"]


def perceive(*args: object, timeout: float = 90) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*CLI, *map(str, args)], cwd=REPO, capture_output=True, text=True, timeout=timeout,
                          stdin=subprocess.DEVNULL, env={**os.environ, "MUJOCO_GL": "egl"})


def test_a_cup_placed_by_someone_else_is_reported_where_it_stands(tmp_path):
    picture, map_png = tmp_path / "look.png", tmp_path / "map.png"
    done = perceive("--backend", "sim", "--at", "kitchen", "--place", "cup=4.2,1.25", "--frames", "2", "--json",
                    "-o", picture, "--map-out", map_png, "--save-frames", tmp_path / "frames")
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    found = {d["label"]: d for d in report["detections"]}
    assert set(found) == {"apple", "bottle", "cup"}
    cup = found["cup"]
    assert cup["world"][:2] == pytest.approx([4.2, 1.25], abs=0.025)
    assert cup["error"] < 0.025 and cup["torso"][1] < 0  # right of the robot
    assert cup["torso"][0] == pytest.approx(0.7, abs=0.025)  # 4.2 - 3.5 ahead of the kitchen marker
    assert [o["sightings"] for o in report["memory"]["objects"]] == [2, 2, 2]  # two frames, one entry each
    from PIL import Image

    with Image.open(picture) as image:
        assert image.size == (424, 240)
    with Image.open(map_png) as image:
        assert image.size[0] > 400
    assert len(list((tmp_path / "frames").glob("*_color.png"))) == 2

    replay = perceive("--backend", "recorded", "--from", tmp_path / "frames", "--json")
    assert replay.returncode == 0, replay.stderr
    again = {d["label"]: d for d in json.loads(replay.stdout)["detections"]}
    assert again["cup"]["world"] == pytest.approx(cup["world"], abs=0.003)


def test_the_table_names_every_detection_with_its_positions():
    done = perceive("--backend", "sim", "--at", "kitchen")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith("robot at (3.50, 1.50) facing 0 deg; 2 detection(s)")
    assert "torso x y z (m)" in lines[1] and "world x y z (m)" in lines[1]
    bottle = next(line for line in lines if line.startswith("bottle"))
    assert "4.010  1.380" in bottle and bottle.endswith("cm")


@pytest.mark.parametrize("args, message", [
    (("--at", "kitchn"), "unknown marker 'kitchn' (did you mean 'kitchen'?)"),
    (("--place", "bottel=4,1.3"), "no object 'bottel' in the scene (did you mean 'bottle'?)"),
    (("--place", "cup=4"), "--place wants LABEL=X,Y"),
    (("--resolution", "320x240"), "unknown resolution '320x240' (did you mean '424x240'?)"),
    (("--detector", "yolo", "--weights", "/nonexistent/yolo.onnx"), "YOLO weights not found: /nonexistent/yolo.onnx"),
    (("--backend", "recorded", "--from", "/nonexistent"), "no intrinsics.json in /nonexistent"),
])
def test_bad_input_is_one_sentence_and_exit_2(args, message):
    done = perceive(*args)
    assert done.returncode == 2
    assert message in done.stderr and "Traceback" not in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
