"""Talking to the robot during a tour: a question is answered at a pause and the tour goes on;
"stop" holds it with the motion stopped until "continue"; a command waits for the tour."""

from __future__ import annotations

from typing import Any

from stuart_bt.language import Parser, Resolver
from stuart_bt.mission.tour_talk import BUSY_WITH_TOUR, COULD_NOT_ANSWER, TourTalk
from stuart_bt.testing import lab_markers, run_tree


class Visitor:
    """Says ``lines`` in turn, each when ``when(live)`` first holds, from the tick thread's hook
    (as a person would, mid-run); the TourTalk is made on the first tick."""

    def __init__(self, *lines: tuple[Any, str]) -> None:
        self.lines = list(lines)
        self.talk: TourTalk | None = None
        self.said_at: list[float] = []

    def __call__(self, live: Any) -> None:
        if self.talk is None:
            self.talk = TourTalk(live.session, live.session.executor, Parser(), Resolver.from_files(lab_markers()))
        if self.lines and self.lines[0][0](live):
            _, text = self.lines.pop(0)
            self.said_at.append(live.t)
            self.talk.submit(text)


def at(marker: str):
    return lambda live: live.session.blackboard.world.last_marker == marker


def test_a_question_during_the_tour_is_answered_at_a_pause_and_the_tour_goes_on():
    visitor = Visitor((at("station_1"), "Hey Stuart, what happens in the drone cage?"))
    result = run_tree("trees/lab_tour.yaml", speed=40, on_tick=visitor)

    result.assert_success()
    assert result.report["visited"] == [f"station_{i}" for i in range(1, 7)]
    [reply] = [e for e in result.events("command") if e.get("path") == "reply"]
    assert "netted cage" in reply["args"]["text"]
    [hold] = result.events("hold")
    [resume] = result.events("resume")
    assert hold["reason"] == "answering a question" and hold["t"] <= reply["t"] <= resume["t"]


class BrokenFacts:
    """A fault that cannot be caused otherwise: the facts fail while answering."""

    def answer(self, question: str, situation: Any) -> str | None:
        raise RuntimeError("the facts file went away")


def test_a_question_that_cannot_be_answered_still_gets_a_reply_and_a_warning_says_why():
    visitor = Visitor((at("station_1"), "Hey Stuart, what happens in the drone cage?"))

    def on_tick(live: Any) -> None:
        visitor(live)
        if visitor.talk is not None and not isinstance(visitor.talk.facts, BrokenFacts):
            visitor.talk.facts = BrokenFacts()  # type: ignore[assignment]

    result = run_tree("trees/lab_tour.yaml", speed=40, on_tick=on_tick)

    result.assert_success()
    assert [e["args"]["text"] for e in result.events("command") if e.get("path") == "reply"] == [COULD_NOT_ANSWER]
    assert any("the facts file went away" in e["message"] for e in result.events("warning"))


def test_stop_holds_the_tour_with_nothing_moving_until_continue():
    visitor = Visitor((at("station_2"), "Hey Stuart, stop"),
                      (lambda live: live.t > visitor.said_at[0] + 5.0, "Hey Stuart, continue"))
    result = run_tree("trees/lab_tour.yaml", speed=40, on_tick=visitor)

    result.assert_success()
    assert result.report["visited"] == [f"station_{i}" for i in range(1, 7)]
    [hold] = result.events("hold")
    [resume] = result.events("resume")
    assert hold["reason"].startswith("stop said") and resume["t"] - hold["t"] >= 4.5
    sent_while_held = [e["cmd"] for e in result.events("command") if hold["t"] < e["t"] < resume["t"]]
    assert set(sent_while_held) <= {"stop", "cancel"} and "stop" in sent_while_held  # nothing that moves


def test_a_command_during_the_tour_is_not_run_and_the_robot_says_why():
    visitor = Visitor((at("station_1"), "Hey Stuart, go to the kitchen"))
    result = run_tree("trees/lab_tour.yaml", speed=40, on_tick=visitor)

    result.assert_success()
    assert "kitchen" not in result.report["visited"]
    assert [e["args"]["text"] for e in result.events("command") if e.get("path") == "reply"] == [BUSY_WITH_TOUR]


def test_run_talk_answers_a_question_typed_on_standard_input(tmp_path):
    import json
    import subprocess
    import sys
    from pathlib import Path

    repo = Path(__file__).resolve().parents[1]
    log = tmp_path / "run.jsonl"
    done = subprocess.run([sys.executable, "-m", "stuart_bt.cli", "run", str(repo / "trees" / "lab_tour.yaml"),
                           "--backend", "dry", "--speed", "30", "--view", "none", "--talk", "--log", str(log)],
                          input="Hey Stuart, who looks after the drone cage?\n", capture_output=True, text=True,
                          timeout=120, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    events = [json.loads(line) for line in log.read_text().splitlines()]
    said = [e["args"]["text"] for e in events if e["kind"] == "command" and e.get("path") == "reply"]
    assert said == ["Tom Becker is the drone pilot, looks after the drone cage."]
    assert [e["reason"] for e in events if e["kind"] == "hold"] == ["answering a question"]
