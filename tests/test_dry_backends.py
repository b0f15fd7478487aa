"""Dry backends: plausible durations on the shared clock, state kept symbolically, real refusals."""

from __future__ import annotations

import math
import time

import pytest

from stuart_bt.core.clock import ScaledClock
from stuart_bt.core.events import EventRecorder, EventStream
from stuart_bt.daemon.supervisor import Supervisor

FACTOR = 40.0


@pytest.fixture
def daemon(tmp_path):
    """``daemon(family, factor=..., **options)``: one dry daemon under a supervisor."""
    made: list[Supervisor] = []

    def start(family: str, factor: float = FACTOR, **options) -> Supervisor:
        clock = ScaledClock(factor)
        sup = Supervisor("dry", clock, EventStream(clock), families=(family,), options={family: options},
                         run_dir=tmp_path)
        sup.recorder = EventRecorder(sup.events)
        made.append(sup)
        sup.start()
        return sup

    yield start
    for sup in made:
        sup.shutdown()


def run(sup: Supervisor, cmd: str, **args):
    family = sup.families[0]
    return sup.wait(sup.client(family).request(cmd, args), timeout=5.0)


def progress_of(sup: Supervisor, request) -> list[dict]:
    return [e.data["data"] for e in sup.recorder.of_kind("daemon")
            if e.data["id"] == request.id and e.data["type"] == "progress"]


# -- loco ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("factor", [20.0, 40.0])
def test_a_straight_walk_lasts_its_length_at_half_a_metre_per_second_of_clock_time(daemon, factor):
    loco = daemon("loco", factor=factor)
    started = time.monotonic()
    walk = run(loco, "navigate", pose={"x": 2.0, "y": 0.0, "yaw": None})
    wall = time.monotonic() - started
    assert walk.accepted_data == {"duration": 4.0}
    # at least its clock length; far less than 4 s of wall time (a factor ignored), however busy the machine
    assert 4.0 / factor <= wall < 4.0 / factor + 1.0


def test_walking_to_the_left_turns_to_face_walks_and_keeps_the_heading_of_travel(daemon):
    loco = daemon("loco")
    walk = run(loco, "navigate", pose={"x": 0.0, "y": 2.0, "yaw": None})
    assert walk.accepted_data["duration"] == pytest.approx(math.pi / 2 / 0.8 + 2.0 / 0.5, abs=1e-3)
    assert walk.result == {"pose": {"x": 0.0, "y": 2.0, "yaw": 1.5708}, "marker": None, "distance": 2.0}


def test_a_goal_heading_adds_a_final_turn(daemon):
    loco = daemon("loco")
    walk = run(loco, "navigate", pose={"x": 0.0, "y": 2.0, "yaw": 0.0}, marker="kitchen")
    assert walk.accepted_data["duration"] == pytest.approx(2 * (math.pi / 2 / 0.8) + 4.0, abs=1e-3)
    assert walk.result == {"pose": {"x": 0.0, "y": 2.0, "yaw": 0.0}, "marker": "kitchen", "distance": 2.0}


def test_progress_reports_the_interpolated_pose_about_every_half_second(daemon):
    loco = daemon("loco")
    walk = run(loco, "navigate", pose={"x": 3.0, "y": 0.0, "yaw": None})  # 6 s of clock time
    poses = [d["pose"]["x"] for d in progress_of(loco, walk)]
    assert 8 <= len(poses) <= 12
    assert poses == sorted(poses) and poses[0] > 0.0 and poses[-1] < 3.0
    assert all(d["phase"] == "walk" for d in progress_of(loco, walk))


def test_a_relative_move_is_in_the_body_frame_of_the_start_pose(daemon):
    loco = daemon("loco", start_pose={"x": 1.0, "y": 1.0, "yaw": math.pi / 2})
    forward = run(loco, "navigate", relative={"dx": 1.0})
    assert forward.result["pose"] == {"x": 1.0, "y": 2.0, "yaw": 1.5708}
    left = run(loco, "navigate", relative={"dy": 1.0})  # facing +y, left is -x; ends facing +y again
    assert left.result["pose"] == {"x": 0.0, "y": 2.0, "yaw": 1.5708}


def test_a_turn_takes_angle_over_0_8_rad_per_second_and_wraps_the_heading(daemon):
    loco = daemon("loco", start_pose={"x": 0.0, "y": 0.0, "yaw": 3.0})
    turn = run(loco, "turn", angle=0.8)
    assert turn.accepted_data == {"duration": 1.0}
    assert turn.result["pose"]["yaw"] == round(3.8 - 2 * math.pi, 4)


def test_a_goal_within_tolerance_needs_no_motion(daemon):
    loco = daemon("loco")
    walk = run(loco, "navigate", pose={"x": 0.05, "y": 0.0, "yaw": 0.05}, tolerance=0.1, yaw_tolerance=0.1)
    assert walk.accepted_data == {"duration": 0.0}
    assert walk.result["pose"] == {"x": 0.0, "y": 0.0, "yaw": 0.0} and walk.result["distance"] == 0.0


def test_the_pose_is_in_every_heartbeat_while_walking(daemon):
    loco = daemon("loco", factor=20.0)
    client = loco.client("loco")
    walk = client.request("navigate", {"pose": {"x": 5.0, "y": 0.0, "yaw": None}})
    seen = []
    while not walk.finished:
        loco.wait(walk, timeout=0.1)
        seen.append((client.state["pose"]["x"], client.state["moving"]))
    assert any(0.0 < x < 5.0 and moving for x, moving in seen)


# -- tts -----------------------------------------------------------------------------------------

def test_speaking_takes_0_4_s_plus_0_36_s_a_word_and_is_remembered(daemon):
    tts = daemon("tts")
    said = run(tts, "say", text="Hello, I am Stuart.")
    assert said.accepted_data == {"duration": pytest.approx(0.4 + 4 * 0.36)}
    assert said.result == {"text": "Hello, I am Stuart.", "duration": pytest.approx(1.84)}
    run(tts, "say", text="Welcome to the lab.")
    state = run(tts, "state").result
    assert state == {"speaking": None, "spoken": ["Hello, I am Stuart.", "Welcome to the lab."], "spoken_total": 2}


def test_a_new_utterance_preempts_the_current_one(daemon):
    tts = daemon("tts")
    client = tts.client("tts")
    first = client.request("say", {"text": "This is a long introduction that nobody will hear to the end"})
    second = tts.wait(client.request("say", {"text": "Stop, please."}))
    assert (first.error_code, first.reason) == ("preempted", f"say {second.id} took the voice")
    assert second.ok
    assert run(tts, "state").result["spoken"] == ["Stop, please."]


# -- gesture -------------------------------------------------------------------------------------

def test_a_gesture_lasts_its_library_duration(daemon):
    gesture = daemon("gesture")
    wave = run(gesture, "play", name="wave")
    assert wave.accepted_data == {"duration": 3.5}
    assert wave.result == {"played": ["high wave"], "duration": 3.5}


def test_a_sequence_plays_in_order_and_a_holding_pose_stays_until_release(daemon):
    gesture = daemon("gesture")
    seq = run(gesture, "play", sequence=["clap", "heart"])
    assert seq.result == {"played": ["clap", "heart"], "duration": 6.5}
    assert [d["gesture"] for d in progress_of(gesture, seq)] == sorted(
        [d["gesture"] for d in progress_of(gesture, seq)], key=["clap", "heart"].index)
    assert run(gesture, "state").result == {"playing": None, "holding": "heart"}
    run(gesture, "play", name="release arm")
    assert run(gesture, "state").result == {"playing": None, "holding": None}


def test_keyframes_last_until_the_last_frame(daemon):
    gesture = daemon("gesture")
    frames = [{"t": 0.0, "joints": {"left_elbow_joint": 0.0}}, {"t": 2.0, "joints": {"left_elbow_joint": 1.2}}]
    played = run(gesture, "play", keyframes=frames)
    assert played.result == {"keyframes": 2, "duration": 2.0}
    backwards = run(gesture, "play", keyframes=list(reversed(frames)))
    assert backwards.error_code == "bad_request" and "'t' must be >= 2.0" in backwards.reason


def test_an_unknown_gesture_in_a_sequence_is_refused_before_anything_plays(daemon):
    gesture = daemon("gesture")
    bad = run(gesture, "play", sequence=["clap", "hgu"])
    assert (bad.error_code, bad.vendor_code) == ("unknown_gesture", 7402)
    assert bad.reason == "no gesture 'hgu' (did you mean 'hug'?)"
    assert bad.accepted_data is None


# -- pick ----------------------------------------------------------------------------------------

KITCHEN = {"x": 4.0, "y": 1.5, "yaw": 0.0}
WORKBENCH = {"x": 1.0, "y": -3.0, "yaw": 0.0}


def test_the_default_lab_has_a_bottle_in_the_kitchen_and_a_cup_on_the_workbench(daemon):
    objects = run(daemon("pick"), "state").result["objects"]
    assert {"bottle", "cup", "apple", "book"} <= set(objects)
    assert math.dist((objects["bottle"]["x"], objects["bottle"]["y"]), (4.0, 1.5)) < 1.0
    assert math.dist((objects["cup"]["x"], objects["cup"]["y"]), (1.0, -3.0)) < 1.0


def test_an_object_out_of_reach_is_refused_before_any_motion(daemon):
    pick = daemon("pick")
    far = run(pick, "pick", object="bottle", robot_pose={"x": 0.0, "y": 0.0, "yaw": 0.0})
    assert (far.error_code, far.reason) == ("unreachable", "bottle is 4.2 m away; reach is 1.2 m")
    assert far.accepted_data is None and far.result == {"distance": 4.2408, "reach": 1.2}
    assert run(pick, "state").result["held"] is None


def test_an_unknown_object_is_not_found_with_a_suggestion(daemon):
    pick = daemon("pick")
    missing = run(pick, "pick", object="botle", robot_pose=KITCHEN)
    assert missing.error_code == "not_found"
    assert missing.reason.startswith("no 'botle' known (did you mean 'bottle'?) (known: apple, book, bottle")


def test_pick_holds_release_puts_down_in_front_and_both_refuse_the_wrong_state(daemon):
    pick = daemon("pick")
    started = time.monotonic()
    grasp = run(pick, "pick", object="bottle", robot_pose=KITCHEN)
    assert time.monotonic() - started >= 6.0 / FACTOR
    assert grasp.result == {"object": "bottle", "arm": "right", "position": {"x": 4.01, "y": 1.38, "z": 0.855}}
    phases = [d["phase"] for d in progress_of(pick, grasp)]  # reports come every ~0.5 s of clock time
    order = ["pre_grasp", "descend", "close", "lift"]
    assert phases and [order.index(p) for p in phases] == sorted(order.index(p) for p in phases), phases
    assert run(pick, "pick", object="apple", robot_pose=KITCHEN).error_code == "already_holding"
    assert run(pick, "release", arm="left", robot_pose=KITCHEN).error_code == "not_holding"
    put = run(pick, "release", robot_pose={"x": 4.0, "y": 1.5, "yaw": math.pi / 2})
    assert put.result == {"object": "bottle", "arm": "right", "position": {"x": 4.0, "y": 1.9, "z": 0.855}}
    again = run(pick, "release", robot_pose=KITCHEN)
    assert (again.error_code, again.reason) == ("not_holding", "the robot holds nothing")
    assert run(pick, "state").result["objects"]["bottle"] == {"x": 4.0, "y": 1.9, "z": 0.855}


def test_find_reports_position_and_distance_after_a_short_search(daemon):
    vision = daemon("vision", objects={"mug": {"x": 1.3, "y": -3.4, "z": 0.9}})
    found = run(vision, "find", object="mug", robot_pose=WORKBENCH)
    assert {k: found.result[k] for k in ("object", "position", "distance")} == {
        "object": "mug", "position": {"x": 1.3, "y": -3.4, "z": 0.9}, "distance": 0.5}
    assert [o["label"] for o in found.result["memory"]["objects"]] == ["mug"]
    assert run(vision, "find", object="cup", robot_pose=WORKBENCH).error_code == "not_found"  # options replace the file
