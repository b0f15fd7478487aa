"""Acceptance: the lab tour runs with ``--backend unitree`` against the fake G1 services, which
record the navigation, speech and gesture requests the tree asked for, in order; and a killed tree
process leaves a robot that was told to stop."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from stuart_bt.core import gestures
from unitree_fake import FakeRobot

pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")

REPO = Path(__file__).resolve().parent.parent
CLI = [str(Path(sys.executable).with_name("stuart-bt"))]
MARKERS = json.loads((REPO / "sim" / "maps" / "lab_markers.json").read_text())["markers"]


def expected_action_ids(plays: list[dict]) -> list[int]:
    """The arm service ids the gesture commands should become, with 'release arm' (99) before
    anything that follows a held pose."""
    ids, holding = [], False
    for args in plays:
        for name in args.get("sequence") or [args["name"]]:
            gesture = gestures.lookup(name)
            if holding and gesture.action_id != 99:
                ids.append(99)
            ids.append(gesture.action_id)
            holding = gesture.holds
    return ids


@pytest.mark.slow
def test_the_lab_tour_completes_and_the_robot_got_the_tree_s_navigation_speech_and_gestures(tmp_path):
    with FakeRobot(nav_speed=10.0) as robot:
        log = tmp_path / "tour.jsonl"
        run = subprocess.run([*CLI, "run", "trees/lab_tour.yaml", "--backend", "unitree", "--speed", "10",
                              "--view", "none", "--log", str(log), "--report", str(tmp_path / "tour.json")],
                             cwd=REPO, env=robot.env, capture_output=True, text=True, timeout=240)
        assert run.returncode == 0, run.stderr[-2000:]
        report = json.loads((tmp_path / "tour.json").read_text())
        assert report["status"] == "SUCCESS"
        events = [json.loads(line) for line in log.read_text().splitlines()]
        commands = [e for e in events if e["kind"] == "command"]

        navigations = [c["args"] for c in commands if c["family"] == "loco" and c["cmd"] == "navigate"]
        stations = [n["marker"] for n in navigations]
        assert stations == [f"station_{i}" for i in range(1, 7)]
        goals = [r["parameter"]["data"]["targetPose"] for r in robot.rpc("slam_operate", 1102)]
        station_xy = [(MARKERS[s]["x"], MARKERS[s]["y"]) for s in stations]
        final_legs = [(g["x"], g["y"]) for g in goals
                      if any(abs(g["x"] - x) < 1e-3 and abs(g["y"] - y) < 1e-3 for x, y in station_xy)]
        assert final_legs == station_xy
        assert all(r["code"] == 0 for r in robot.rpc("slam_operate", 1102))

        said = [c["args"]["text"] for c in commands if c["family"] == "tts" and c["cmd"] == "say"]
        spoken = [r["parameter"]["text"] for r in robot.rpc("voice", 1001)]
        assert spoken == said and len(said) == 8
        assert all(r["parameter"]["speaker_id"] == 1 for r in robot.rpc("voice", 1001))

        plays = [c["args"] for c in commands if c["family"] == "gesture" and c["cmd"] == "play"]
        executed = [r["parameter"]["data"] for r in robot.rpc("arm", 7106)]
        assert executed[:len(expected_action_ids(plays))] == expected_action_ids(plays)
        assert all(r["code"] == 0 for r in robot.rpc("arm", 7106))


WALK_FAR = """
description: A long body-relative walk, to be interrupted.
root:
  navigate: {dx: 20.0}
"""


@pytest.mark.slow
def test_killing_the_tree_process_makes_the_loco_daemon_stop_the_robot(tmp_path):
    tree = tmp_path / "walk.yaml"
    tree.write_text(WALK_FAR)
    with FakeRobot() as robot:
        proc = subprocess.Popen([*CLI, "run", str(tree), "--backend", "unitree", "--view", "none"], cwd=REPO,
                                env=robot.env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True)
        try:
            robot.wait_for(lambda r: r.get("api") == 7105 and any(r["parameter"]["velocity"]), timeout=60,
                           what="the walk's first velocity command")
            os.kill(proc.pid, signal.SIGKILL)  # no goodbye from the tree: only the pipe closing tells the daemon
            proc.wait(timeout=10)
            stop = robot.wait_for(lambda r: r.get("api") == 7105 and not any(r["parameter"]["velocity"]), timeout=10,
                                  what="a zero-velocity command after the kill")
        finally:
            if proc.poll() is None:
                proc.kill()
        moves = [r for r in robot.rpc("sport", 7105) if any(r["parameter"]["velocity"])]
        assert all(r["parameter"]["duration"] <= 0.3 for r in moves)  # even unheard, the robot halts in 0.3 s
        print(f"stop arrived {stop['t'] - moves[-1]['t']:.3f} s after the last motion command")
        late = [r for r in moves if r["t"] > stop["t"]]
        assert late == []  # nothing moved the robot again after the stop


def test_a_daemon_options_file_reaches_the_daemons(tmp_path):
    options = tmp_path / "robot.yaml"
    options.write_text("tts:\n  volume: 55\ngesture:\n  ramp: 0.3\n")
    with FakeRobot() as robot:
        run = subprocess.run([*CLI, "run", "trees/greet.yaml", "--backend", "unitree", "--speed", "10",
                              "--view", "none", "--daemon-options", str(options)],
                             cwd=REPO, env=robot.env, capture_output=True, text=True, timeout=120)
        assert run.returncode == 0, run.stderr[-2000:]
        assert robot.rpc("voice", 1006)[-1]["parameter"] == {"volume": 55}


def test_a_daemon_options_file_naming_no_family_is_one_message(tmp_path):
    options = tmp_path / "robot.yaml"
    options.write_text("tss:\n  volume: 55\n")
    run = subprocess.run([*CLI, "run", "trees/greet.yaml", "--backend", "unitree", "--daemon-options", str(options)],
                         cwd=REPO, capture_output=True, text=True, timeout=60)
    assert run.returncode == 1
    assert run.stderr.strip() == (f"stuart-bt: --daemon-options {options}: unknown family 'tss' (did you mean 'tts'?); "
                                  "families: loco, tts, gesture, pick, vision")
