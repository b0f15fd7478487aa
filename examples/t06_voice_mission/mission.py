"""t06: a voice mission from Python. The mission executor parses what was said, plans it with
the HTN domain (tasks/domain.yaml), compiles the plan to a tree and runs it on daemons that stay
up between missions. ``submit`` is what a microphone, the web console or the ROS bridge calls.

    python examples/t06_voice_mission/mission.py
    stuart-bt mission "Hey Stuart, go to the kitchen and wave" --speed 20   # the same, as a command
"""

from __future__ import annotations

from stuart_bt.mission.executor import MissionExecutor, MissionOptions


def run(utterances: list[str], speed: float = 20.0) -> list[tuple[str, str | None]]:
    """Say each utterance in turn; (status, reason) of every mission."""
    with MissionExecutor(MissionOptions(backend="dry", speed=speed)) as robot:
        for text in utterances:
            command = robot.submit(text)
            print(f"{text!r}: heard as {command.kind}")
            robot.wait_idle(120)
        return [(m.status, m.reason) for m in robot.missions]


if __name__ == "__main__":
    for status, reason in run(["Hey Stuart, go to the kitchen and wave", "what a nice day",
                               "Hey Stuart, turn around"]):
        print(status, reason or "")
