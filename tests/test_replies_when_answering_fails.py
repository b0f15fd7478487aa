"""A question the conversation backend fails on still gets a spoken reply, and a warning says why:
the answer is made on a thread of its own, where an error would vanish and nobody answer."""

from __future__ import annotations

from typing import Any

from stuart_bt.conversation.reply import CannedConversation, Reply
from stuart_bt.mission.executor import MissionExecutor, MissionOptions
from stuart_bt.mission.replies import COULD_NOT_ANSWER


class FailingModel(CannedConversation):
    """A fault that cannot be caused otherwise on demand: the model's server goes away mid-answer."""

    def reply(self, text: str, context: dict[str, Any]) -> Reply:
        raise ConnectionError("the model's server went away")


def test_a_reply_the_model_fails_on_is_said_as_sorry_and_a_warning_says_why():
    events: list[Any] = []
    with MissionExecutor(MissionOptions(speed=50.0), conversation=FailingModel()) as robot:
        robot.events.subscribe(events.append)
        robot.submit("Hey Stuart, tell me a joke")
        assert robot.wait_idle(30)
        robot.submit("Hey Stuart, go to the kitchen")  # the robot still takes commands after it
        assert robot.wait_idle(60)
    said = [e.data["args"]["text"] for e in events if e.kind == "command" and e.data.get("cmd") == "say"]
    assert COULD_NOT_ANSWER in said
    assert any("the model's server went away" in e.data.get("message", "") for e in events if e.kind == "warning")
    assert [m.status for m in robot.missions] == ["succeeded"]
