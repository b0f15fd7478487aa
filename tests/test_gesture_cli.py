"""``stuart-bt gesture list|record|show|play`` the way a user drives them: the real console script
in a subprocess, looking only at exit status, stdout, stderr and the files written.

``--from-world`` and ``play`` run against a world started with ``launch_world``; the arms are
posed through the world's own ``arm_trajectory`` command, as a teleoperation tool would.
"""

from __future__ import annotations

import json
import math
import re
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from stuart_bt.skills.gesture.keyframes import NEUTRAL, load_gesture_file

REPO = Path(__file__).resolve().parents[1]
ARM_AND_HAND = set(NEUTRAL)


def _console_script() -> list[str]:
    script = Path(sys.executable).with_name("stuart-bt")
    if script.exists():
        return [str(script)]
    found = shutil.which("stuart-bt")
    return [found] if found else [sys.executable, "-m", "stuart_bt.cli"]


CLI = _console_script()


def stuart(*args: Any, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    """``stuart-bt ARGS`` from the repository root, output captured as text."""
    return subprocess.run([*CLI, *map(str, args)], cwd=REPO, capture_output=True, stdin=subprocess.DEVNULL,
                          encoding="utf-8", errors="replace", timeout=timeout, check=False)


def failed(result: subprocess.CompletedProcess[str]) -> list[str]:
    """Exit 1, no traceback, every stderr line one ``stuart-bt: ...`` message; the lines."""
    assert result.returncode == 1, (result.returncode, result.stdout, result.stderr)
    assert "Traceback" not in result.stderr + result.stdout, result.stderr
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert lines and all(line.startswith("stuart-bt: ") for line in lines), lines
    return lines


def frames_of(path: Path) -> list[dict[str, Any]]:
    return json.loads(path.read_text(encoding="utf-8"))["keyframes"]


@pytest.mark.parametrize("action", ["list", "record", "show", "play"])
def test_help_of_every_action(action: str) -> None:
    result = stuart("gesture", action, "--help")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith(f"usage: stuart-bt gesture {action}"), result.stdout


# -- list ------------------------------------------------------------------------------------------
def test_list_shows_the_library_with_vendor_ids() -> None:
    result = stuart("gesture", "list")
    assert result.returncode == 0, result.stderr
    row = re.compile(r"^(?P<name>\S.*?)\s+(?P<id>\d+)\s+[\d.]+\s+(yes|no)", re.MULTILINE)
    ids = {m["name"]: int(m["id"]) for m in row.finditer(result.stdout)}
    assert ids["high wave"] == 26 and ids["release arm"] == 99 and len(ids) == 16
    assert re.search(r"^high wave .*\bwave, hello$", result.stdout, re.MULTILINE)


# -- record from the command line --------------------------------------------------------------------
def test_record_fills_every_frame_from_neutral_and_the_previous_frame(tmp_path: Path) -> None:
    out = tmp_path / "sub" / "point.json"
    result = stuart("gesture", "record", "point", "-o", out,
                    "--keyframe", "1.0 right_shoulder_pitch_joint=-1.2 right_elbow_joint=0.3",
                    "--keyframe", "2 right_elbow=60deg right_hand_index_0_joint=0.5",  # suffix-less, degrees
                    "-k", "3.5",  # hold until 3.5 s
                    "-k", "4.5 neutral left_elbow_joint=1.0")  # back to neutral, but for one joint
    assert result.returncode == 0, result.stderr
    assert "point" in result.stderr and "4 keyframes" in result.stderr and "right arm" in result.stderr
    doc = json.loads(out.read_text(encoding="utf-8"))
    assert doc["name"] == "point" and [f["t"] for f in doc["keyframes"]] == [1.0, 2.0, 3.5, 4.5]
    first, second, third, fourth = (f["joints"] for f in doc["keyframes"])
    assert set(first) == set(second) == set(third) == set(fourth) == ARM_AND_HAND
    neutral = {k: round(v, 5) for k, v in NEUTRAL.items()}
    assert first == {**neutral, "right_shoulder_pitch_joint": -1.2, "right_elbow_joint": 0.3}
    assert fourth == {**neutral, "left_elbow_joint": 1.0}
    assert second["right_shoulder_pitch_joint"] == -1.2  # carried over
    assert second["right_elbow_joint"] == pytest.approx(math.radians(60), abs=1e-5)
    assert third == second
    assert load_gesture_file(out).name == "point"  # what the player reads


def test_record_at_a_joint_limit_still_loads(tmp_path: Path) -> None:
    out = tmp_path / "fist.json"
    result = stuart("gesture", "record", "fist", "-o", out,
                    "-k", "0.5 right_hand_thumb_2_joint=-1.74532925 right_hand_index_1_joint=1.74532925")
    assert result.returncode == 0, result.stderr
    joints = load_gesture_file(out).keyframes[0].joints  # a value rounded past its limit would not load
    assert joints["right_hand_thumb_2_joint"] == pytest.approx(-1.74532925, abs=1e-5)


def test_record_lists_every_problem_and_writes_nothing(tmp_path: Path) -> None:
    out = tmp_path / "bad.json"
    out.write_text("keep me", encoding="utf-8")
    lines = failed(stuart("gesture", "record", "bad", "-o", out,
                          "-k", "1.0 right_elbo_joint=0.3 left_elbow_joint=9 right_shoulder_pitch_joint=abc",
                          "-k", "0.5 right_elbow_joint=0.1",
                          "-k", "soon right_elbow_joint=0.1",
                          "-k", "2 right_elbow_joint"))
    text = "\n".join(lines)
    assert "unknown joint 'right_elbo_joint' (did you mean 'right_elbow_joint'?)" in text
    assert "left_elbow_joint = 9.0000 rad is outside its limits [-1.0472, 2.0944]" in text
    assert "right_shoulder_pitch_joint = 'abc' is not a number" in text
    assert "--keyframe 2 (t = 0.5 s): time 0.5 s does not come after the previous keyframe's 1 s" in text
    assert "--keyframe 3: must start with a time in seconds, got 'soon'" in text
    assert "--keyframe 4 (t = 2 s): expected joint=radians or 'neutral', got 'right_elbow_joint'" in text
    assert lines[-1] == f"stuart-bt: nothing written to {out}"
    assert len(lines) == 7
    assert out.read_text(encoding="utf-8") == "keep me"


@pytest.mark.parametrize("args, message", [
    ((), "nothing to record"),
    (("-k", "1 right_elbow_joint=0.1", "--at", "2"), "--at needs --from-world"),
    (("-k", "1 right_elbow_joint=nan"), "right_elbow_joint = 'nan' is not a number"),
    (("-k", "1 right_elbow_joint=0.1 right_elbow=0.2"), "names right_elbow_joint twice"),
])
def test_record_usage_mistakes(tmp_path: Path, args: tuple[str, ...], message: str) -> None:
    out = tmp_path / "g.json"
    lines = failed(stuart("gesture", "record", "g", "-o", out, *args))
    assert any(message in line for line in lines), lines
    assert not out.exists()


def test_record_append_continues_a_file(tmp_path: Path) -> None:
    out = tmp_path / "g.json"
    assert stuart("gesture", "record", "g", "-o", out, "-k", "1 left_elbow_joint=0.5").returncode == 0
    result = stuart("gesture", "record", "g", "-o", out, "--append", "-k", "2 left_shoulder_roll_joint=0.6")
    assert result.returncode == 0, result.stderr
    frames = frames_of(out)
    assert [f["t"] for f in frames] == [1, 2]
    assert frames[1]["joints"]["left_elbow_joint"] == 0.5 and frames[1]["joints"]["left_shoulder_roll_joint"] == 0.6
    lines = failed(stuart("gesture", "record", "g", "-o", out, "--append", "-k", "1.5 left_elbow_joint=0"))
    assert "time 1.5 s does not come after the previous keyframe's 2 s" in lines[0]
    assert len(frames_of(out)) == 2


# -- show --------------------------------------------------------------------------------------------
def test_show_checks_and_tabulates_a_file(tmp_path: Path) -> None:
    out = tmp_path / "g.json"
    assert stuart("gesture", "record", "nod", "-o", out, "-k", "1 right_elbow_joint=0.3",
                  "-k", "2 right_elbow_joint=0.9").returncode == 0
    result = stuart("gesture", "show", out)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].startswith("'nod'") and "ok, 2 keyframes over 2 s; moves right arm" in lines[0]
    header = next(line for line in lines if line.startswith("joint (rad)"))
    assert header.split()[2:] == ["1", "s", "2", "s", "limits"]
    rows = [line for line in lines if line.startswith("right_elbow_joint")]
    assert rows and rows[0].split()[1:3] == ["0.300", "0.900"]
    assert not any(line.startswith("left_") for line in lines)  # only joints that move
    shown = stuart("gesture", "show", out, "--all").stdout.splitlines()
    assert any(line.startswith("left_elbow_joint") for line in shown)


def test_show_lists_every_problem_of_a_broken_file(tmp_path: Path) -> None:
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"name": "x", "keyframes": [
        {"t": 1.0, "joints": {"right_elbow_joint": 5.0}},
        {"t": 0.5, "joints": {"rigth_elbow_joint": 0.1}}]}), encoding="utf-8")
    result = stuart("gesture", "show", bad)
    assert result.returncode == 1 and "Traceback" not in result.stderr
    lines = result.stderr.splitlines()
    assert all(line.startswith(f"{bad}: keyframe ") for line in lines), lines
    assert any("outside its limits" in line for line in lines)
    assert any("does not come after" in line for line in lines)
    assert any("did you mean 'right_elbow_joint'" in line for line in lines)


def test_show_a_library_gesture_and_a_missing_file() -> None:
    result = stuart("gesture", "show", "wave", "--degrees")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("'high wave' (library gesture, vendor id 26)")
    assert "joint (deg)" in result.stdout
    missing = stuart("gesture", "show", "hi wave")
    assert missing.returncode == 1 and missing.stderr.strip() == "hi wave: file not found (did you mean 'high wave'?)"


# -- the sim: record from a world's pose, play back, play in a tree -----------------------------------------
POSE = {"right_shoulder_pitch_joint": -1.0, "right_shoulder_roll_joint": -0.4, "right_elbow_joint": 0.2,
        "right_hand_index_0_joint": 0.6, "left_wrist_yaw_joint": 0.3}


@pytest.fixture(scope="module")
def world() -> Iterator[Any]:
    pytest.importorskip("mujoco")
    from stuart_bt.sim.world.client import launch_world

    with launch_world(stderr=subprocess.DEVNULL) as w:
        yield w


def settle(world: Any, timeout: float = 20.0) -> dict[str, Any]:
    """The world's state once the arms have stopped moving (the world free-runs: no driver)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        state = world.call("state")
        if not any(state["arm_busy"].values()):
            return state
        time.sleep(0.02)
    raise AssertionError("the arms did not settle")


@pytest.mark.slow
def test_record_from_world_appends_the_current_arm_pose(world: Any, tmp_path: Path) -> None:
    world.call("arm_trajectory", points=[{"t": 0.3, "joints": POSE}])
    state = settle(world)
    out = tmp_path / "from_world.json"
    result = stuart("gesture", "record", "posed", "-o", out, "-k", "0.8 left_elbow_joint=0.9",
                    "--from-world", world.socket_path, "--at", 2.0)
    assert result.returncode == 0, result.stderr
    frames = load_gesture_file(out).keyframes
    assert [f.t for f in frames] == [0.8, 2.0]
    assert set(frames[1].joints) == ARM_AND_HAND  # arms and hands; never the waist or the base
    for name in ARM_AND_HAND:
        assert frames[1].joints[name] == pytest.approx(state["joints"][name], abs=1e-5), name
    for name, value in POSE.items():
        assert frames[1].joints[name] == pytest.approx(value, abs=1e-3), name

    # with no --at the pose lands one second after the last keyframe, and --append keeps the rest
    again = stuart("gesture", "record", "posed", "-o", out, "--append", "--from-world", world.socket_path)
    assert again.returncode == 0, again.stderr
    assert [f["t"] for f in frames_of(out)] == [0.8, 2.0, 3.0]


def test_record_from_a_world_that_is_not_there(tmp_path: Path) -> None:
    lines = failed(stuart("gesture", "record", "g", "-o", tmp_path / "g.json", "--from-world", tmp_path / "no.sock"))
    assert lines[0].startswith(f"stuart-bt: cannot read the pose from the world at {tmp_path / 'no.sock'}")
    assert len(lines) == 2


@pytest.mark.slow
def test_play_moves_the_world_arms_to_the_last_keyframe(world: Any, tmp_path: Path) -> None:
    out = tmp_path / "reach.json"
    assert stuart("gesture", "record", "reach", "-o", out, "-k", "0.5 left_shoulder_pitch_joint=-0.8",
                  "-k", "1.2 left_elbow_joint=0.4 left_hand_thumb_1_joint=0.5").returncode == 0
    result = stuart("gesture", "play", out, "--world", world.socket_path)
    assert result.returncode == 0, result.stderr
    assert "playing 'reach'" in result.stderr and "done at sim t" in result.stderr
    joints = settle(world)["joints"]
    last = load_gesture_file(out).keyframes[-1].joints
    for name, value in last.items():
        assert joints[name] == pytest.approx(value, abs=1e-3), name


@pytest.mark.slow
@pytest.mark.timeout(120)
def test_a_recorded_gesture_plays_in_a_tree_on_the_sim(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    gesture = tmp_path / "gestures" / "salute.json"
    assert stuart("gesture", "record", "salute", "-o", gesture,
                  "-k", "0.8 right_shoulder_pitch_joint=-1.5 right_elbow_joint=0.1",
                  "-k", "1.6").returncode == 0
    tree = tmp_path / "salute.yaml"
    tree.write_text("root:\n  sequence:\n    name: salute_tree\n    children:\n"
                    "      - gesture: {file: gestures/salute.json}\n", encoding="utf-8")
    assert stuart("validate", tree).returncode == 0
    report = tmp_path / "report.json"
    run = stuart("run", tree, "--backend", "sim", "--view", "none", "--report", report, timeout=100)
    assert run.returncode == 0, run.stderr[-2000:]
    events = json.loads(report.read_text(encoding="utf-8"))["events"]
    done = [e for e in events if e["kind"] == "daemon" and e.get("family") == "gesture" and e.get("type") == "done"]
    assert len(done) == 1 and done[0]["result"]["duration"] == pytest.approx(1.6)
