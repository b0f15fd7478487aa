"""The world server as a process: READY, the request/reply protocol, and every way it ends."""

from __future__ import annotations

import json
import os
import signal
import socket
import statistics
import subprocess
import sys
import time
from pathlib import Path

import pytest

from stuart_bt.daemon.protocol import WORLD_CODES, check_daemon_message
from stuart_bt.sim.world.client import WorldClient, WorldError, launch_world
from stuart_bt.sim.world.scene import default_robot_path

STANDIN = Path(__file__).parent / "data" / "standin_robot.xml"
ROBOT = None if default_robot_path().is_file() else STANDIN


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    log_path = tmp_path_factory.mktemp("world") / "world.log"
    with open(log_path, "wb") as log, launch_world(robot=ROBOT, stderr=log) as w:
        yield w


def test_ready_line_and_state(world):
    ready = world.ready
    assert ready["type"] == "ready"
    assert ready["socket"] == str(world.socket_path) and ready["clock"] == str(world.clock_path)
    assert 0.002 <= ready["timestep"] <= 0.005
    state = world.call("state")
    assert set(state) >= {"t", "base", "base_velocity", "base_status", "joints", "arm_busy", "held", "objects",
                          "person", "collision"}
    assert state["base_status"] == "idle"
    assert {"bottle", "cup", "apple", "book"} <= set(state["objects"])
    assert state["person"] is None
    assert state["held"] == {"left": None, "right": None}
    assert "right_shoulder_pitch_joint" in state["joints"] and "base_x" not in state["joints"]


def test_errors_are_replies_not_crashes(world):
    with pytest.raises(WorldError) as e:
        world.call("fly")
    assert e.value.code == "unknown_command"
    with pytest.raises(WorldError) as e:
        world.call("base_velocity", vx="fast")
    assert e.value.code == "bad_request"
    with pytest.raises(WorldError) as e:
        world.call("set_object", label="unicorn", x=0, y=0, z=1)
    assert e.value.code == "not_found"
    assert world.call("ping")["t"] >= 0.0  # still serving


def test_the_world_speaks_the_daemons_line_protocol_to_several_clients(world):
    clients = [WorldClient(world.socket_path) for _ in range(3)]
    try:
        times = [c.call("state")["t"] for c in clients]
        assert all(t >= 0 for t in times)
    finally:
        for c in clients:
            c.close()
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as raw:
        raw.connect(str(world.socket_path))
        raw.sendall(b'{"id": "a", "cmd": "ping"}\nnot json\n{"id": 7, "cmd": "ping", "args": {}}\n'
                    b'{"id": "b", "cmd": "pnig"}\n{"id": "c", "cmd": "ping", "args": []}\n')
        buffer = b""
        while buffer.count(b"\n") < 5:
            buffer += raw.recv(65536)
        replies = [check_daemon_message(json.loads(line)) for line in buffer.splitlines()]
    assert replies[0]["id"] == "a" and replies[0]["type"] == "done" and replies[0]["result"]["t"] >= 0
    assert [r["type"] for r in replies[1:]] == ["error"] * 4
    assert {r["code"] for r in replies[1:]} <= set(WORLD_CODES)
    assert (replies[1]["id"], replies[1]["code"]) == (None, "bad_request")
    assert (replies[2]["id"], replies[2]["code"]) == (None, "bad_request") and "'id'" in replies[2]["reason"]
    assert (replies[3]["id"], replies[3]["code"]) == ("b", "unknown_command") and "ping" in replies[3]["reason"]
    assert (replies[4]["id"], replies[4]["code"]) == ("c", "bad_request") and "'args'" in replies[4]["reason"]


def test_the_ready_line_is_a_daemon_ready_line_with_the_world_s_details(world):
    ready = check_daemon_message(world.ready)
    assert (ready["type"], ready["family"], ready["pid"]) == ("ready", "world", world.pid)
    assert {"ping", "state", "base_path", "render", "shutdown"} <= set(ready["commands"])
    assert ready["socket"] == str(world.socket_path) and ready["timestep"] > 0


def _wait_exit(proc: subprocess.Popen, timeout: float = 10.0) -> int:
    return proc.wait(timeout)


def test_sigterm_removes_socket_and_clock(tmp_path):
    w = launch_world(robot=ROBOT, stderr=subprocess.DEVNULL)
    try:
        assert w.socket_path.exists() and w.clock_path.exists()
        os.kill(w.pid, signal.SIGTERM)
        assert _wait_exit(w.proc) == 0
        assert not w.socket_path.exists() and not w.clock_path.exists()
    finally:
        w.close()


def test_stdin_eof_ends_the_world(tmp_path):
    w = launch_world(robot=ROBOT, stderr=subprocess.DEVNULL)
    try:
        w.proc.stdin.close()  # what happens when the parent dies
        assert _wait_exit(w.proc) == 0
        assert not w.socket_path.exists() and not w.clock_path.exists()
    finally:
        w.close()


def test_shutdown_command_and_clock_after_exit(tmp_path):
    w = launch_world(robot=ROBOT, stderr=subprocess.DEVNULL)
    try:
        clock = w.clock()
        assert w.call("shutdown")["t"] >= 0.0
        assert _wait_exit(w.proc) == 0
        assert not w.socket_path.exists() and not w.clock_path.exists()
        # A reader of a stopped world's clock carries on at wall rate instead of freezing.
        assert not clock.alive
        t0 = clock.now()
        time.sleep(0.05)
        assert clock.now() > t0
        clock.close()
    finally:
        w.close()


def test_viewer_without_display_says_so(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    argv = [sys.executable, "-m", "stuart_bt.sim.world", "--socket", str(tmp_path / "w.sock"),
            "--clock", str(tmp_path / "w.clock"), "--viewer"]
    done = subprocess.run(argv, env=env, capture_output=True, timeout=30, stdin=subprocess.DEVNULL)
    assert done.returncode == 2
    assert b"needs a display" in done.stderr
    assert done.stdout == b""


def _noisy_poses(seed: int, n: int = 60) -> list[tuple[float, float, float]]:
    with launch_world(robot=ROBOT, seed=seed, loc_noise=True, stderr=subprocess.DEVNULL) as w:
        return [(s["base"]["x"], s["base"]["y"], s["base"]["yaw"]) for s in (w.call("state") for _ in range(n))]


def test_localisation_noise_is_small_and_seeded():
    first, again = _noisy_poses(3), _noisy_poses(3)
    assert first == again  # one seeded generator: the same run gives the same noise
    xs = [p[0] for p in first]
    yaws = [p[2] for p in first]
    assert 0.003 < statistics.pstdev(xs) < 0.03  # the robot stands at (0, 0): all of it is noise
    assert 0.002 < statistics.pstdev(yaws) < 0.03
    assert abs(statistics.mean(xs)) < 0.01


def test_info_describes_the_robot(world):
    info = world.call("info")
    assert info["objects"] == ["apple", "book", "bottle", "cup"]
    assert {"head_camera", "chase"} <= set(info["cameras"])
    elbow = info["joints"]["left_elbow_joint"]
    assert elbow["lower"] == pytest.approx(-1.0472, abs=1e-3) and elbow["upper"] == pytest.approx(2.0944, abs=1e-3)
    assert info["limits"]["dead_band"] == 0.3
