"""``stuart-bt mission``: one utterance (and later ones at clock times) end to end on the dry
backend, judged by the exit status and the report."""

from __future__ import annotations

import argparse
import io
import json
from pathlib import Path

from stuart_bt.cli.chat import cmd_chat
from stuart_bt.cli.main import build_parser
from stuart_bt.cli.mission import add_command


def mission(*argv: str) -> int:
    parser = argparse.ArgumentParser(prog="stuart-bt")
    add_command(parser.add_subparsers())
    args = parser.parse_args(["mission", *argv])
    return args.func(args)


def test_compound_mission_exits_0_and_reports_what_was_said_and_done(tmp_path: Path, capsys):
    report = tmp_path / "r.json"

    status = mission("Hey Stuart, wave and then go to the kitchen", "--speed", "50", "--report", str(report))

    assert status == 0
    doc = json.loads(report.read_text())
    assert doc["status"] == "SUCCESS"
    assert doc["missions"][0]["status"] == "succeeded"
    assert doc["visited"] == ["kitchen"]
    assert "says      'Doing a wave'" in capsys.readouterr().out


def test_stop_then_continue_from_the_command_line_finishes_the_mission(tmp_path: Path, capsys):
    report = tmp_path / "r.json"

    status = mission("Hey Stuart, go to the bathroom", "--speed", "50", "--report", str(report),
                     "--then", "Hey Stuart, stop", "--at", "2", "--then", "Hey Stuart, carry on", "--at", "4")

    assert status == 0
    out = capsys.readouterr().out
    assert out.index("mission 1 stopped") < out.index("mission 1 resumed") < out.index("mission 1 finished")
    assert json.loads(report.read_text())["missions"][0]["status"] == "succeeded"


def test_unknown_place_exits_1_after_saying_so(capsys):
    assert mission("go to the garage", "--no-wake", "--speed", "50") == 1
    assert "says      \"I don't know where the garage is." in capsys.readouterr().out


def test_mission_prints_the_plan_line_chat_prints_for_the_same_words(capsys):
    said = "Hey Stuart, wave and then go to the kitchen"
    assert mission(said, "--speed", "50") == 0
    mission_plans = [line for line in capsys.readouterr().out.splitlines() if "plan      mission" in line]
    chat_out = io.StringIO()
    args = build_parser("chat").parse_args(["chat", "--speed", "50"])
    assert cmd_chat(args, stdin=io.StringIO(said + "\n"), out=chat_out) == 0
    chat_plans = [line for line in chat_out.getvalue().splitlines() if "plan      mission" in line]

    assert len(mission_plans) == 1 and mission_plans == chat_plans
    tasks = mission_plans[0].split("plan      mission 1: ")[1].split("; ")
    assert [t.split(" [")[0] for t in tasks] == ["gesture", "navigate_to_marker"]  # each task with its skills
    assert all(t.endswith("]") for t in tasks), tasks
