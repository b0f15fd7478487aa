"""bench/hearing.py counts what the robot would do with what it heard, decided as the mission
executor decides it: a task heard in doubt is asked about (nothing done), a stop stops anyway."""

from __future__ import annotations

import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
if str(REPO) not in sys.path:  # bench/ is a folder of the checkout, not an installed package
    sys.path.insert(0, str(REPO))

from bench.hearing import _done  # noqa: E402
from stuart_bt.language.parse import Parser  # noqa: E402
from stuart_bt.language.resolve import Resolver  # noqa: E402
from stuart_bt.testing import lab_markers  # noqa: E402

PARSER = Parser()
RESOLVER = Resolver.from_files(lab_markers())


def test_a_task_heard_with_confidence_is_done():
    assert [m[:2] for m in _done(PARSER, RESOLVER, "Hey Stuart, go to the kitchen", 0.8, False)] == [
        ("navigate_to_marker", "kitchen")]


def test_a_task_heard_with_low_confidence_is_asked_about_so_nothing_is_done():
    assert _done(PARSER, RESOLVER, "Hey Stuart, go to the kitchen", 0.2, False) == []


def test_a_task_with_a_rival_reading_is_asked_about_so_nothing_is_done():
    assert _done(PARSER, RESOLVER, "Hey Stuart, go to the kitchen", 0.8, True) == []


def test_a_stop_heard_with_low_confidence_still_stops():
    assert [m[0] for m in _done(PARSER, RESOLVER, "Stuart, stop.", 0.2, False)] == ["stop"]


def test_a_stop_in_doubt_stops_but_the_task_after_it_is_asked_about():
    assert [m[0] for m in _done(PARSER, RESOLVER, "Hey Stuart, stop and go to the kitchen", 0.2, False)] == ["stop"]


def test_talk_does_nothing():
    assert _done(PARSER, RESOLVER, "the kitchen is closed today", 0.9, False) == []
