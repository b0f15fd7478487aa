"""The utterance corpus (tests/data/utterances/*.jsonl) through the whole pipeline.

Each line: ``{"utterance": ..., "intents": [{"action", "target", "x", "y", "yaw"}, ...]}``, with
``"wake": false`` when the utterance must not wake the robot, and ``"conversational": true``
when it wakes it but holds no command. An utterance counts as right when wake, and the exact
intent sequence (action, target, and x/y/yaw within 1e-3) match.

Goals: >= 98 % right overall, and every non-command (no intents expected) gives no intents: a
robot that moves when it was only talked to is the failure that matters most. Misses are printed
(run with ``-s`` to see them when everything passes).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

from stuart_bt.language.intents import ACTIONS, TaskIntent
from stuart_bt.language.parse import Parser, ParseResult

CORPUS = Path(__file__).parent / "data" / "utterances"
GOAL = 0.98


@dataclass(frozen=True)
class Case:
    file: str
    line: int
    utterance: str
    wake: bool
    intents: tuple[TaskIntent, ...]

    @property
    def where(self) -> str:
        return f"{self.file}:{self.line}"


def load() -> list[Case]:
    cases = []
    for path in sorted(CORPUS.glob("*.jsonl")):
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if not line.strip():
                continue
            row: dict[str, Any] = json.loads(line)
            intents = tuple(TaskIntent.from_dict(i) for i in row["intents"])
            cases.append(Case(path.name, n, row["utterance"], bool(row.get("wake", True)), intents))
    return cases


CASES = load()


def right(case: Case, got: ParseResult) -> bool:
    return (got.wake == case.wake and len(got.intents) == len(case.intents)
            and all(a.same_as(b) for a, b in zip(got.intents, case.intents, strict=True)))


def _show(intents: Any) -> str:
    return "[" + ", ".join(f"{i.action}({i.target!r}, x={i.x:.3g}, y={i.y:.3g}, yaw={i.yaw:.3g})"
                           for i in intents) + "]"


def test_corpus_is_big_and_covers_everything() -> None:
    assert len(CASES) >= 300
    non_commands = [c for c in CASES if not c.intents]
    assert len(non_commands) >= 70
    assert sum(1 for c in non_commands if c.wake) >= 30 and sum(1 for c in non_commands if not c.wake) >= 30
    seen = {i.action for c in CASES for i in c.intents}
    assert seen == set(ACTIONS)
    assert sum(1 for c in CASES if len(c.intents) > 1) >= 40  # compounds
    assert len({c.utterance for c in CASES}) == len(CASES), "duplicate utterances"


def test_corpus_accuracy() -> None:
    parser = Parser()
    misses = []
    for case in CASES:
        got = parser.parse(case.utterance)
        if not right(case, got):
            misses.append(f"{case.where}: {case.utterance!r}\n    want wake={case.wake} {_show(case.intents)}\n"
                          f"    got  wake={got.wake} {_show(got.intents)}")
        else:  # woken with no command is conversation; no wake is neither
            assert got.conversational == (case.wake and not case.intents), case.where
    accuracy = 1 - len(misses) / len(CASES)
    print(f"\ncorpus: {len(CASES)} utterances, {len(misses)} missed, accuracy {accuracy:.1%}")
    for m in misses:
        print(m)
    assert accuracy >= GOAL, f"accuracy {accuracy:.1%} < {GOAL:.0%}:\n" + "\n".join(misses)


@pytest.mark.parametrize("case", [c for c in CASES if not c.intents], ids=lambda c: c.where)
def test_non_commands_never_give_intents(case: Case) -> None:
    got = Parser().parse(case.utterance)
    assert got.intents == [], f"{case.utterance!r} is not a command but gave {_show(got.intents)}"
    assert got.wake == case.wake
