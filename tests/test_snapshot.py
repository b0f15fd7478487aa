"""The tree snapshot (docs/web.md) follows a run from the event stream alone, and from a saved log."""

import json

from stuart_bt.core.events import EventRecorder
from stuart_bt.run.session import RunOptions, Session
from stuart_bt.run.snapshot import FORMAT, TreeSnapshot
from stuart_bt.testing import lab_markers
from stuart_bt.tree.loader import load_tree_text

TREE = """
root:
  sequence:
    name: main
    children:
      - log: {name: hello, message: hi}
      - wait: {name: pause, seconds: 0.2}
      - log: {name: bye, message: bye}
"""


def test_snapshot_follows_a_run_and_replays_from_the_log():
    spec = load_tree_text(TREE, markers_file=lab_markers())
    session = Session(spec, RunOptions(backend="dry", speed=20.0))
    changes: list[int] = []
    snap = TreeSnapshot(session.events, on_change=lambda: changes.append(snap.seq))
    recorder = EventRecorder(session.events)
    seen_running: list[list[str]] = []
    with session:
        doc = snap.to_dict()
        assert doc["format"] == FORMAT and doc["tree"]["root"] == "main"
        assert [n["name"] for n in doc["nodes"]] == ["main", "hello", "pause", "bye"]
        assert all(n["status"] == "INVALID" for n in doc["nodes"])
        pause = doc["nodes"][2]
        assert pause["parent"] == "main" and pause["depth"] == 1 and pause["category"] == "leaf"
        assert doc["nodes"][0]["children"] == [n["path"] for n in doc["nodes"][1:]]
        session.executor.pre_tick.append(lambda: seen_running.append(snap.running_path()))
        session.run()
    final = snap.to_dict()
    assert ["main", pause["path"]] in seen_running  # the running path passed through the wait
    assert final["running"] == [] and snap.status("main") == "SUCCESS"
    assert final["nodes"][3]["last"]["outcome"] == "SUCCESS"
    assert final["seq"] > doc["seq"] and changes == sorted(changes)
    assert json.loads(snap.to_json())["seq"] == final["seq"]

    replayed = TreeSnapshot.from_events(recorder.events).to_dict()
    assert [n["status"] for n in replayed["nodes"]] == [n["status"] for n in final["nodes"]]
    assert replayed["seq"] == final["seq"]


def test_a_new_tree_event_replaces_the_structure():
    snap = TreeSnapshot()
    from stuart_bt.core.events import Event

    snap.apply(Event(0.0, "tree", data={"file": "a", "root": {"path": "a", "name": "a", "kind": "sequence",
                                                             "category": "composite", "children": []}}))
    snap.apply(Event(0.1, "status", "a", {"old": "INVALID", "new": "RUNNING"}))
    assert snap.running_path() == ["a"]
    snap.apply(Event(0.2, "tree", data={"file": "b", "root": {"path": "b", "name": "b", "kind": "selector",
                                                             "category": "composite", "children": []}}))
    assert snap.running_path() == [] and snap.to_dict()["tree"]["file"] == "b"
    assert not snap.apply(Event(0.3, "status", "a", {"new": "SUCCESS"}))  # a node no longer in the tree


def test_the_initial_blackboard_is_in_the_snapshot_and_the_log_before_the_first_tick(tmp_path):
    spec = load_tree_text("blackboard:\n  visitors: group\n  visits: {kitchen: 0}\n" + TREE, markers_file=lab_markers())
    log = tmp_path / "run.jsonl"
    session = Session(spec, RunOptions(backend="dry", speed=20.0, log=log))
    snap = TreeSnapshot(session.events)  # a view joins after the session was made, as serve's does
    with session:
        before = snap.to_dict()
        assert before["blackboard"] == {"visitors": "group", "visits": {"kitchen": 0}}
        assert all(n["status"] == "INVALID" for n in before["nodes"])
    logged = [json.loads(line) for line in log.read_text().splitlines()]
    written = [(e["key"], e["value"]) for e in logged if e["kind"] == "blackboard"]
    assert written == [("visitors", "group"), ("visits", {"kitchen": 0})]
