"""``--speed``: what each command's sessions get from it, and what its help says.

A person talking to the simulated robot (``chat``, ``listen``, ``ros``, ``serve``) gets real time
unless they ask otherwise, so "stop" comes before the robot has arrived; batch commands (``run``,
``mission``) leave the simulator free-running.
"""

from __future__ import annotations

import argparse
import importlib

import pytest

from stuart_bt.cli.main import build_parser
from stuart_bt.cli.speed import REAL_TIME, speed_for
from stuart_bt.mission.executor import MissionExecutor

TALKING = ("chat", "listen", "ros")  # commands whose robot a person talks to, built from MissionOptions
EVERY_SPEED_COMMAND = ("run", "serve", "chat", "listen", "ros", "mission")
REQUIRED = {"listen": ["--source", "mic"], "run": ["tree.yaml"], "serve": ["--mission"]}


def parse(command: str, *words: str) -> argparse.Namespace:
    return build_parser(command).parse_args([command, *REQUIRED.get(command, []), *words])


def session_options(command: str, *words: str):
    """The MissionOptions the command would start its robot with (nothing is started)."""
    module = importlib.import_module(f"stuart_bt.cli.{'chat' if command == 'listen' else command}")
    return module.mission_options(parse(command, *words), {})


def subcommand(command: str) -> argparse.ArgumentParser:
    parser = build_parser(command)
    choices = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices
    return choices[command]


def option(p: argparse.ArgumentParser, flag: str) -> argparse.Action:
    return next(a for a in p._actions if flag in a.option_strings)


@pytest.mark.parametrize("command", TALKING)
def test_a_person_talking_to_the_simulated_robot_gets_real_time_by_default(command: str) -> None:
    assert session_options(command, "--backend", "sim").speed == REAL_TIME


@pytest.mark.parametrize("command", TALKING)
def test_a_speed_asked_for_is_kept_even_zero_for_as_fast_as_possible(command: str) -> None:
    assert session_options(command, "--backend", "sim", "--speed", "0").speed == 0.0
    assert session_options(command, "--backend", "sim", "--speed", "3").speed == 3.0


@pytest.mark.parametrize("command", TALKING)
def test_the_dry_backend_keeps_its_own_default(command: str) -> None:
    assert session_options(command).speed is None  # the session's dry clock runs at 1


def test_the_web_console_and_the_talking_commands_share_one_rule() -> None:
    args = parse("serve", "--backend", "sim")
    assert speed_for(args.backend, args.speed, interactive=True) == REAL_TIME


@pytest.mark.parametrize("command", ("run", "mission"))
def test_batch_commands_leave_the_simulator_free_running(command: str) -> None:
    args = parse(command, *(["hello"] if command == "mission" else []), "--backend", "sim")
    assert args.speed is None  # RunOptions: sim None is 0, as fast as the tree keeps up
    assert speed_for(args.backend, args.speed, interactive=False) is None


def test_a_negative_speed_is_one_clear_sentence() -> None:
    with pytest.raises(ValueError, match="--speed must not be negative"):
        speed_for("sim", -1.0, interactive=True)


@pytest.mark.parametrize("command", EVERY_SPEED_COMMAND)
def test_the_speed_help_says_what_it_does_for_every_backend_the_command_offers(command: str) -> None:
    p = subcommand(command)
    backends = option(p, "--backend").choices
    text = option(p, "--speed").help or ""
    assert backends and all(f"{backend}:" in text for backend in backends), (backends, text)
    assert "default" in text.partition("sim:")[2]  # the simulator's default is stated


def test_a_chat_on_the_simulator_starts_a_world_that_keeps_real_time() -> None:
    options = session_options("chat", "--backend", "sim")
    with MissionExecutor(options) as robot:
        assert robot.session.world.ready["speed"] == REAL_TIME  # what the world server itself says
