"""A bare "Hey Stuart" holds the robot's attention for what is said next (people call, wait,
then ask; a segmenter may cut "Hey Stuart, ... stop" in two), once, for a few seconds."""

from __future__ import annotations

from stuart_bt.language.parse import Parser
from stuart_bt.mission.attention import Attention
from stuart_bt.mission.commands import IGNORE, STOP, TASKS, interpret
from stuart_bt.mission.executor import MissionExecutor, MissionOptions


class Clock:
    def __init__(self) -> None:
        self.t = 100.0

    def __call__(self) -> float:
        return self.t


def test_a_bare_wake_phrase_holds_attention_for_the_next_utterance_only():
    parser, clock = Parser(), Clock()
    attention = Attention(hold_s=5.0, now=clock)
    attention.after(interpret(parser, "Hey Stuart."))
    clock.t += 3.0
    assert attention.held() and attention.take()
    assert not attention.take(), "the hold is used up by the utterance that took it"


def test_the_hold_ends_after_its_time_and_a_whole_command_does_not_hold():
    parser, clock = Parser(), Clock()
    attention = Attention(hold_s=5.0, now=clock)
    attention.after(interpret(parser, "Hey Stuart"))
    clock.t += 5.5
    assert not attention.take()
    attention.after(interpret(parser, "Hey Stuart, go to the kitchen"))
    assert not attention.take()
    attention.after(interpret(parser, "go to the kitchen"))  # no wake phrase at all
    assert not attention.take()


def test_after_hey_stuart_a_command_without_the_wake_phrase_is_acted_on_once():
    with MissionExecutor(MissionOptions(backend="dry", speed=50.0)) as robot:
        robot.submit("Hey Stuart.")
        first = robot.submit("wave")
        second = robot.submit("stop")
        assert robot.wait_idle(30)
    assert first.kind == TASKS and [i.action for i in first.intents] == ["gesture"]
    assert second.kind == IGNORE, "the hold is for one utterance"
    said = [e.data for e in robot.session.recorder.events if e.kind == "utterance"]
    assert [d.get("wake_held", False) for d in said] == [False, True, False]


def test_a_held_stop_is_a_stop():
    with MissionExecutor(MissionOptions(backend="dry", speed=50.0)) as robot:
        robot.submit("Hey Stuart")
        assert robot.submit("stop").kind == STOP
