"""Blackboard expressions: what parses, what is refused (never eval), how values are found."""

from __future__ import annotations

import pytest

from stuart_bt.core import expr
from stuart_bt.core.blackboard import Blackboard


@pytest.fixture
def bb() -> Blackboard:
    board = Blackboard(initial={"battery": 42, "mode": "tour", "visits": {"kitchen": 2}, "queue": [1, 2]})
    board.world.held = "bottle"
    return board


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("battery > 20", True),
        ("battery > 20 and mode == 'demo'", False),
        ("battery > 20 or mode == 'demo'", True),
        ("not world.holding", False),
        ("world.held == 'bottle'", True),
        ("visits.kitchen >= 2", True),
        ("visits['kitchen'] + 1 == 3", True),
        ("mode in ['tour', 'demo']", True),
        ("len(queue) == 2", True),
        ("10 < battery <= 42", True),
        ("world.pose.x == 0", True),
        ("true and not false", True),
        ("world.held is not null", True),
        ("-battery < 0", True),
        ("battery % 10 == 2", True),
    ],
)
def test_expressions_evaluate_on_the_blackboard(bb: Blackboard, text: str, expected: bool) -> None:
    assert expr.parse(text).evaluate(bb.get) is expected


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("__import__('os').system('true')", "only these functions"),
        ("open('/etc/passwd')", "only these functions"),
        ("(lambda: 1)", "Lambda"),
        ("world.__class__", "private name"),
        ("[x for x in queue]", "ListComp"),
        ("a = 1", "syntax error"),
        ("battery >", "syntax error"),
        ("visits[mode]", "constant indexes"),
        ("", "empty"),
        ("x" * 2000, "longer than"),
    ],
)
def test_unsafe_or_broken_expressions_are_refused_at_parse_time(text: str, fragment: str) -> None:
    with pytest.raises(expr.ExprError) as info:
        expr.parse(text)
    assert fragment in info.value.message


def test_parse_error_reports_the_column():
    with pytest.raises(expr.ExprError) as info:
        expr.parse("battery > 20 and open('x')")
    assert info.value.column == 18


def test_missing_key_and_type_mismatch_are_evaluation_errors_not_crashes(bb: Blackboard) -> None:
    with pytest.raises(expr.ExprError, match="no key 'fuel'"):
        expr.parse("fuel > 1").evaluate(bb.get)
    with pytest.raises(expr.ExprError, match="cannot evaluate"):
        expr.parse("mode > 3").evaluate(bb.get)


def test_names_lists_the_blackboard_keys_read():
    assert expr.parse("world.pose.x > 1 and battery < world.pose.y or len(queue)").names == [
        "world.pose.x", "battery", "world.pose.y", "queue",
    ]
