"""Every example in examples/ works as its README says: each tree validates and runs to
SUCCESS on the dry backend, the pytest example passes under pytest, the mission example's
missions succeed, and examples/README.md lists every example folder."""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import pytest

from stuart_bt.testing import run_tree
from stuart_bt.tree.loader import load_tree

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
TREES = sorted(EXAMPLES.glob("t*/tree.yaml"))


def test_the_readme_lists_every_example_in_order():
    folders = sorted(p.name for p in EXAMPLES.iterdir() if p.is_dir() and re.match(r"t\d\d_", p.name))
    listed = re.findall(r"^\| \[(t\d\d_\w+)\]", (EXAMPLES / "README.md").read_text(encoding="utf-8"), re.MULTILINE)
    assert listed == folders and len(folders) >= 6


@pytest.mark.parametrize("tree", TREES, ids=lambda p: p.parent.name)
def test_each_example_tree_validates_and_runs_to_success(tree):
    load_tree(tree)  # raises with file:line on any mistake
    result = run_tree(tree, speed=100)
    assert result.status == "SUCCESS", result.report.get("failures")


def test_the_pytest_example_passes_under_pytest():
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "--rootdir",
                           str(EXAMPLES), str(EXAMPLES / "t05_test_your_tree")],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    assert "2 passed" in done.stdout


def test_the_mission_example_runs_its_missions():
    path = EXAMPLES / "t06_voice_mission" / "mission.py"
    spec = importlib.util.spec_from_file_location("t06_mission", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    outcomes = module.run(["Hey Stuart, go to the kitchen and wave", "what a nice day", "Hey Stuart, turn around"],
                          speed=50)
    assert outcomes == [("succeeded", None), ("succeeded", None)]  # the chatter without a wake word is no mission
