"""The ROS 2 bridge, driven across processes by a plain rclpy client (tests/ros_client.py).

Each test runs ``stuart-bt ros`` in one process and the client in another; DDS stays on this
machine (ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST) in a domain of this test session.
"""

from __future__ import annotations

import json
import math
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("rclpy", reason="the ros extra (real rclpy) is not installed: pip install -e '.[ros]'")

from ros_harness import BridgeProcess, Lines, RosClient, alive, ros_env, session_domain_id
from stuart_bt.core.catalogue import FAMILIES

KITCHEN = (3.5, 1.5)  # sim/maps/lab_markers.json
ARRIVAL = 0.5  # m: the original system's arrival tolerance


def wait_for_warnings(client: RosClient, expected: list[str], timeout: float = 30.0) -> list[str]:
    """The ``warning`` messages on /bt/events once every expected one arrived (or the time is up)."""
    deadline = time.monotonic() + timeout
    while True:
        warnings = [w["message"] for w in events_of(client, "warning")]
        if all(warnings.count(w) >= expected.count(w) for w in expected) or time.monotonic() > deadline:
            return warnings
        time.sleep(0.05)


def announced_daemons(ready_line: str) -> dict[str, int]:
    """family -> pid from the bridge's ready line ("...; daemons gesture 812, loco 813; ...")."""
    listed = ready_line.split("; daemons ", 1)[1].split(";", 1)[0]
    return {family: int(pid) for family, pid in (item.split() for item in listed.split(", "))}


def intents(client: RosClient, topic: str = "/llm/task_intent") -> list[dict]:
    return [json.loads(m["data"]) for m in client.on(topic)]


def utterances(client: RosClient, topic: str = "/bt/events") -> list[dict]:
    """Utterance events; what each was heard as (ignore, tasks, stop, ...) is their ``data_kind``."""
    return events_of(client, "utterance", topic)


def events_of(client: RosClient, kind: str, topic: str = "/bt/events") -> list[dict]:
    return [e for e in (json.loads(m["data"]) for m in client.on(topic)) if e["kind"] == kind]


def test_hey_stuart_go_to_the_kitchen_from_another_process_walks_the_sim_robot_there():
    with BridgeProcess("--backend", "sim") as bridge:
        bridge.up()
        with RosClient() as client:
            client.publish("audio_msg", "Hey Stuart, go to the kitchen")

            intent = client.wait_for(lambda m: m.get("topic") == "/llm/task_intent")
            said = client.wait_for(lambda m: m.get("topic") == "/llm/response")
            finished = client.wait_for(lambda m: m.get("topic") == "/bt/events"
                                       and '"phase":"finished"' in m["data"], timeout=180)
            status = client.wait_for(lambda m: m.get("topic") == "/bt/status"
                                     and (json.loads(m["data"]).get("mission") or {}).get("phase") == "finished")
            poses = client.on("/robot_pose")
        children = bridge.descendants()
        assert bridge.stop() == 0

    assert json.loads(intent["data"]) == {"action": "navigate_to_marker", "target": "kitchen", "x": 0.0, "y": 0.0,
                                          "yaw": 0.0, "raw_text": "go to the kitchen"}
    assert said["data"] == "Navigating to the kitchen"
    assert json.loads(finished["data"])["status"] == "succeeded"
    snapshot = json.loads(status["data"])
    assert snapshot["format"] == "stuart_bt.snapshot/1" and snapshot["mission"]["status"] == "succeeded"
    assert len(poses) > 5 and {p["frame"] for p in poses} == {"map"}
    last = poses[-1]
    assert math.hypot(last["x"] - KITCHEN[0], last["y"] - KITCHEN[1]) < ARRIVAL
    assert math.hypot(poses[0]["x"] - KITCHEN[0], poses[0]["y"] - KITCHEN[1]) > 2.0  # it walked there
    assert children and not [c for c in children if alive(c)]  # the world and every daemon are gone


def test_the_wake_filter_applies_on_audio_msg_only_and_the_namespace_prefixes_every_topic():
    with BridgeProcess("--backend", "dry", "--speed", "20", "--namespace", "lab_robot") as bridge:
        line = bridge.up()
        with RosClient("/lab_robot") as client:
            def say(topic: str, text: str) -> None:  # one at a time: topics are not ordered among themselves
                client.publish(topic, text)
                assert client.wait_for(lambda m: m.get("topic") == "/lab_robot/bt/events"
                                       and '"parsed":' in m["data"] and json.dumps(text) in m["data"])

            say("audio_msg", "go to the kitchen")  # no wake phrase: the recogniser heard chatter
            say("llm/input", "turn around")  # filtered upstream already
            say("stuart/mission", "wave")
            say("audio_msg", "Hey Stuart, stop")
            client.wait_for(lambda m: m.get("topic") == "/lab_robot/llm/task_intent" and '"stop"' in m["data"])
            heard = utterances(client, "/lab_robot/bt/events")

    assert "/lab_robot/audio_msg" in line and "/lab_robot/pick_target" in line
    assert f" domain {session_domain_id()} " in line  # ROS_DOMAIN_ID from the environment
    assert [i["action"] for i in intents(client, "/lab_robot/llm/task_intent")] == ["turn_around", "gesture", "stop"]
    assert [(u["text"], u["data_kind"]) for u in heard] == [  # the utterance's own kind: flat JSON's data_kind
        ("go to the kitchen", "ignore"), ("turn around", "tasks"), ("wave", "tasks"), ("Hey Stuart, stop", "stop")]


def test_malformed_messages_are_logged_and_ignored_and_the_bridge_keeps_listening():
    with BridgeProcess("--backend", "dry", "--speed", "20") as bridge:
        bridge.up()
        with RosClient() as client:
            client.publish("audio_msg", "")
            client.publish("audio_msg", "\x00\x01\x02  \x7f")
            client.publish("stuart/mission", "x" * 5000)
            client.publish("audio_msg", 42, int32=True)  # the wrong message type on the topic
            client.publish("pick_target", "confirm")  # no pick is waiting for it
            client.publish("pick_target", "bottle")
            intent = client.wait_for(lambda m: m.get("topic") == "/llm/task_intent")
            expected = ["ros: ignored a malformed message on audio_msg"] * 2 + [
                "ros: ignored a malformed message on stuart/mission", "ros: confirm received but no pick is waiting"]
            warnings = wait_for_warnings(client, expected)  # topics are not ordered among themselves
            logged = bridge.err.wait_for(lambda x: "ignored a malformed message on /audio_msg" in x, 30)
        still_running = bridge.proc.poll() is None
        assert bridge.stop() == 0

    assert still_running
    assert json.loads(intent["data"])["action"] == "pick_up" and json.loads(intent["data"])["target"] == "bottle"
    assert sorted(w for w in warnings if w.startswith("ros: ")) == sorted(expected)
    assert logged is not None  # and the node logged it


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_a_signal_during_a_mission_stops_the_tree_and_the_daemons_and_leaves_no_child(sig):
    with BridgeProcess("--backend", "dry") as bridge:  # real time: the walk takes seconds
        daemons = announced_daemons(bridge.up())
        with RosClient() as client:
            client.publish("stuart/mission", "go to the bathroom")
            assert client.wait_for(lambda m: m.get("topic") == "/robot_pose", timeout=30) is not None
            children = bridge.descendants()
            code = bridge.stop(sig)
            halted = client.wait_for(lambda m: m.get("topic") == "/bt/events" and '"kind":"halt"' in m["data"], 10)

    assert code == 0
    assert set(daemons) == set(FAMILIES)  # one daemon per skill family
    assert set(daemons.values()) <= {pid for pid, _ in children}
    assert not [c for c in children if alive(c)]
    assert halted is not None  # the tree was halted, and the node still said so
    assert bridge.out.wait_for(lambda x: x == "ros bridge: stopped; every daemon stopped", 10) is not None


def test_a_tree_behind_the_bridge_answers_a_question_holds_on_stop_and_finishes_after_continue(tmp_path):
    log = tmp_path / "tour.jsonl"

    def event(kind: str, reason: str = ""):
        return lambda m: m.get("topic") == "/bt/events" and json.loads(m["data"])["kind"] == kind \
            and json.loads(m["data"]).get("reason", "").startswith(reason)

    tour = str(Path(__file__).resolve().parents[1] / "trees" / "lab_tour.yaml")
    # Slow enough (~13 s of tour) that a loaded machine asks, hears the answer and says stop before the end.
    with BridgeProcess(tour, "--backend", "dry", "--speed", "10", "--log", str(log)) as bridge, RosClient() as client:
        line = bridge.up()
        client.publish("audio_msg", "Hey Stuart, what happens in the drone cage?")
        answer = client.wait_for(lambda m: m.get("topic") == "/llm/response" and "netted cage" in m["data"])
        went_on = client.wait_for(event("resume"))
        client.publish("audio_msg", "Hey Stuart, stop")
        held = client.wait_for(event("hold", "stop said"))
        client.publish("llm/input", "continue")  # woken upstream: no wake phrase needed
        code = bridge.proc.wait(60)
        sent_intents = intents(client)
    events = [json.loads(x) for x in log.read_text(encoding="utf-8").splitlines()]

    assert line.startswith("ros bridge: node /stuart_bridge") and answer is not None and went_on is not None
    assert held is not None
    assert code == 0 and bridge.out.wait_for(lambda x: x == "ros bridge: the tree ended SUCCESS; every daemon stopped",
                                             10) is not None
    [reply] = [e for e in events if e["kind"] == "reply"]
    assert reply["source"] == "facts" and reply["text"] == answer["data"]
    assert [(e["data_kind"], e["source"]) for e in events if e["kind"] == "utterance"] == [
        ("conversation", "ros:audio_msg"), ("stop", "ros:audio_msg"), ("continue", "ros:llm/input")]
    assert [i["action"] for i in sent_intents] == ["stop"]  # the stop said, as the grammar read it
    holds = [e for e in events if e["kind"] == "hold"]
    resumes = [e["t"] for e in events if e["kind"] == "resume"]
    assert [h["reason"] for h in holds] == ["answering a question", "stop said: stop"] and len(resumes) == 2
    sent_while_held = [e["cmd"] for e in events if e["kind"] == "command" and holds[1]["t"] <= e["t"] < resumes[1]]
    assert set(sent_while_held) <= {"stop", "cancel"} and "stop" in sent_while_held  # nothing that moves
    [end] = [e for e in events if e["kind"] == "run" and e["phase"] == "end"]
    assert end["status"] == "SUCCESS" and end["t"] > resumes[1]


# In the dry and sim labs every object is remembered from the start, so a mission's find never asks
# the vision daemon and no ``memory`` event comes from a short mission. This bridge process wraps a
# stand-in robot (a real event stream, nothing else) and publishes perception's own summary, made
# by its SpatialMemory, when told to on stdin.
MEMORY_BRIDGE = r"""
import sys
from stuart_bt.core.clock import ScaledClock
from stuart_bt.core.events import EventStream
from stuart_bt.perception.memory import Observation, SpatialMemory
from stuart_bt.ros.node import Bridge

class StandIn:
    events = EventStream(ScaledClock(1.0))

clock = ScaledClock(1.0)
bridge = Bridge(StandIn()).start()
print("ros bridge: node up", flush=True)
memory = SpatialMemory(clock)
for line in sys.stdin:  # "label x y z": one sighting
    label, x, y, z = line.split()
    memory.update([Observation(label, float(x), float(y), float(z), 0.9)])
    StandIn.events.publish("memory", "mission/find", **memory.summary())
bridge.close()
"""


def test_a_memory_event_publishes_the_spatial_memory_summary_and_a_marker_per_object():
    proc = subprocess.Popen([sys.executable, "-c", MEMORY_BRIDGE], env=ros_env(), stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert Lines(proc.stdout).wait_for(lambda x: x.startswith("ros bridge: node"), 60), proc.stderr.read()
        with RosClient() as client:
            proc.stdin.write("bottle 4.01 1.38 0.85\n")
            proc.stdin.flush()
            summary = client.wait_for(lambda m: m.get("topic") == "/spatial_memory/summary")
            proc.stdin.write("cup 1.0 -2.0 0.8\n")
            proc.stdin.flush()
            markers = client.wait_for(lambda m: m.get("topic") == "/spatial_memory/markers"
                                      and len(m["markers"]) == 5)
    finally:
        proc.stdin.close()
        proc.wait(30)

    memory = json.loads(summary["data"])
    assert memory["format"] == "stuart_bt.memory/1" and memory["frame"] == "map"
    assert [(o["label"], o["x"], o["y"]) for o in memory["objects"]] == [("bottle", 4.01, 1.38)]
    delete_all, *drawn = markers["markers"]
    assert delete_all["action"] == 3  # DELETEALL first: forgotten objects vanish
    assert {m["frame"] for m in drawn} == {"map"}
    assert sorted((m["text"], m["x"], m["y"]) for m in drawn if m["text"]) == [
        ("bottle_1", 4.01, 1.38), ("cup_1", 1.0, -2.0)]


def test_a_subscriber_that_disappears_mid_mission_does_not_disturb_the_bridge():
    with BridgeProcess("--backend", "dry", "--speed", "5") as bridge:
        bridge.up()
        with RosClient() as first:
            first.publish("stuart/mission", "go to the bathroom")
            # its mission under way: its intent out (before the next client listens) and the robot moving
            assert first.wait_for(lambda m: m.get("topic") == "/llm/task_intent", timeout=30) is not None
            assert first.wait_for(lambda m: m.get("topic") == "/robot_pose", timeout=30) is not None
            first.proc.kill()  # gone without a goodbye while poses and events stream to it
            first.proc.wait()
        with RosClient() as second:
            second.publish("audio_msg", "Hey Stuart, go to the kitchen instead")
            said = second.wait_for(lambda m: m.get("topic") == "/llm/response"
                                   and m["data"] == "Navigating to the kitchen", timeout=60)
        assert bridge.stop() == 0

    assert said is not None
    heard = [(i["action"], i["target"]) for i in intents(second)]
    assert heard == [("navigate_to_marker", "kitchen")], heard


def test_a_bad_namespace_domain_or_options_file_is_one_clear_line_and_nothing_starts(tmp_path):
    (tmp_path / "opts.yaml").write_text("gesturs: {}\n")
    bad_ns = BridgeProcess("--namespace", "lab robot!")
    bad_domain = BridgeProcess(env={**ros_env(), "ROS_DOMAIN_ID": "900"})
    bad_options = BridgeProcess("--daemon-options", str(tmp_path / "opts.yaml"))
    assert (bad_ns.proc.wait(60), bad_domain.proc.wait(60), bad_options.proc.wait(60)) == (1, 1, 1)
    for bad in (bad_ns, bad_domain, bad_options):
        bad.err.wait_for(lambda x: True, 5)

    assert len(bad_ns.err.lines) == 1 and bad_ns.err.lines[0].startswith("stuart-bt: bad --namespace 'lab robot!': ")
    assert bad_ns.err.lines[0].endswith("(try '/lab_robot_')")
    assert bad_domain.err.lines == ["stuart-bt: ROS_DOMAIN_ID must be a whole number from 0 to 232, not '900'"]
    assert len(bad_options.err.lines) == 1
    assert "unknown family 'gesturs' (did you mean 'gesture'?)" in bad_options.err.lines[0]
    assert bad_ns.out.lines == bad_domain.out.lines == bad_options.out.lines == []  # no node, no daemons


@pytest.mark.skipif(shutil.which("espeak-ng") is None, reason="espeak-ng is not installed (make test installs it)")
def test_what_the_bridge_hears_is_acted_on_once_and_published_on_audio_msg(tmp_path):
    pytest.importorskip("faster_whisper", reason="the 'hearing' extra is not installed (make test installs it)")
    import numpy as np

    from stuart_bt.hearing.audio import read_audio
    from stuart_bt.testing import speak

    clip = read_audio(speak("Hey Stuart, go to the bathroom", tmp_path / "go.wav", "en-gb+m3"))
    pcm = np.concatenate([np.zeros(8_000, np.int16), clip, np.zeros(24_000, np.int16)]).astype("<i2").tobytes()
    with BridgeProcess("--backend", "dry", "--speed", "20", "--hear", "-", stdin=subprocess.PIPE) as bridge:
        bridge.up()
        with RosClient() as client:
            client.proc.stdin.write(json.dumps({"sub": "audio_msg"}) + "\n")
            client.proc.stdin.flush()
            assert client.out.wait_for(lambda x: '"subscribed"' in x, 30) is not None
            bridge.feed(pcm)
            published = client.wait_for(lambda m: m.get("topic") == "/audio_msg")
            client.wait_for(lambda m: m.get("topic") == "/bt/events" and '"phase":"finished"' in m["data"], timeout=60)
            time.sleep(1.0)  # time enough for the bridge's own /audio_msg message to come back to it
            said = utterances(client)
        assert bridge.stop() == 0

    assert "bathroom" in published["data"].lower()
    assert [(u["source"], u["text"]) for u in said] == [("stdin", published["data"])], \
        "heard once, and the bridge's own /audio_msg message was not taken as a second command"
    assert [i["target"] for i in intents(client)] == ["bathroom"]


def test_the_rclpy_example_of_docs_ros_md_gets_the_intent_and_the_reply_from_a_bridge(tmp_path):
    """docs/ros.md shows rclpy first (the venv has no ros2 command): its example, run as written."""
    section = (Path(__file__).resolve().parent.parent / "docs" / "ros.md").read_text(encoding="utf-8")
    example = re.search(r"```python\n(.*?)```", section.split("## From Python (rclpy)", 1)[1], re.S)
    assert example is not None
    script = tmp_path / "kitchen_client.py"
    script.write_text(example.group(1), encoding="utf-8")
    with BridgeProcess("--backend", "dry") as bridge:
        bridge.up()
        try:
            done = subprocess.run([sys.executable, str(script)], env=ros_env(), capture_output=True, text=True,
                                  timeout=60)
        except subprocess.TimeoutExpired as e:  # run() has killed it
            raise AssertionError(f"the example did not finish: {e.stdout!r} {e.stderr!r}") from None
        assert bridge.stop() == 0
    assert done.returncode == 0, done.stderr
    printed = done.stdout.splitlines()
    [intent] = [line for line in printed if line.startswith("intent ")]
    assert "'action': 'navigate_to_marker'" in intent and "'target': 'kitchen'" in intent, intent
    assert any(line.startswith("says ") and "kitchen" in line.lower() for line in printed), printed
