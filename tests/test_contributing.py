"""docs/contributing.md stays true: every repository path it names exists, and its snippets run
(the leaf test, the HTN domain and its plan, the grammar example)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
GUIDE = (REPO / "docs" / "contributing.md").read_text(encoding="utf-8")


def blocks(language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", GUIDE, re.DOTALL)


def test_every_path_the_guide_names_exists():
    named = set(re.findall(r"`((?:stuart_bt|skills|sim|tasks|tests|docs|bench|examples)/[\w/.<>]+)`", GUIDE))
    named = {p for p in named if "<" not in p}
    missing = sorted(p for p in named if not (REPO / p).exists())
    assert len(named) >= 15 and not missing, missing


def test_the_leaf_test_example_runs(monkeypatch):
    monkeypatch.chdir(REPO)  # its marker file is named from the repository's top
    exec(blocks("python")[0], {})


def test_the_htn_example_plans_as_the_guide_says():
    domain_yaml = blocks("yaml")[0]
    exec(blocks("python")[1], {"DOMAIN": domain_yaml})


def test_the_htn_example_walks_only_when_it_must():
    from stuart_bt.htn import Planner, TaskCall, load_domain_text

    domain = load_domain_text(blocks("yaml")[0])
    plan = Planner(domain).plan([TaskCall.parse("greet_at(entrance)")], domain.initial_state())
    assert [step.skill for step in plan.primitives()] == ["speak"]


def test_the_grammar_example_parses_as_the_guide_says():
    exec(blocks("python")[2], {})


@pytest.mark.parametrize("table", ["MOTION_VERBS"])
def test_the_lexicon_tables_the_guide_names_exist(table):
    from stuart_bt.language.grammar import lexicon

    assert table in GUIDE and isinstance(getattr(lexicon, table), frozenset)
