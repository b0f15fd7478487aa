"""`validate` warns about a tree that walks while a gesture may still hold the arms up."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from stuart_bt.cli import main
from stuart_bt.core import gestures
from stuart_bt.tree.lint import tree_warnings
from stuart_bt.tree.loader import load_tree_text

REPO = Path(__file__).resolve().parent.parent
HOLDING = sorted(name for name, g in gestures.LIBRARY.items() if g.holds)
FREEING = sorted(name for name, g in gestures.LIBRARY.items() if not g.holds)


def warnings(text: str, file: str = "t.yaml") -> list[str]:
    return [str(w) for w in tree_warnings(load_tree_text(textwrap.dedent(text), file=file))]


def test_a_walk_after_a_hug_is_a_warning_naming_both_nodes():
    assert warnings("""\
        root:
          sequence:
            - gesture: hug
            - speak: Bye
            - navigate: {x: 1, y: 0}
        """) == ["t.yaml:5:7: t/navigate: warning: navigate while the arms may still hold the 'hug' pose of "
                 "t/gesture (line 3); put 'gesture: release arm' between them"]


@pytest.mark.parametrize("gesture", HOLDING)
def test_every_holding_gesture_warns_before_every_kind_of_walk(gesture):
    found = warnings(f"""\
        root:
          sequence:
            - gesture: {gesture}
            - navigate: {{dx: 1}}
            - turn: 1.0
            - approach: {{x: 1, y: 1}}
        """)
    assert [w.split(": warning:")[0] for w in found] == [
        "t.yaml:4:7: t/navigate", "t.yaml:5:7: t/turn", "t.yaml:6:7: t/approach"]


@pytest.mark.parametrize("between", ["release arm", "release", *[g for g in FREEING if g != "release arm"][:3]])
def test_release_arm_or_any_gesture_that_ends_free_in_between_is_fine(between):
    assert warnings(f"""\
        root:
          sequence:
            - gesture: high five
            - gesture: {between}
            - navigate: {{dx: 1}}
        """) == []


def test_a_gesture_list_counts_by_its_last_gesture():
    ends_holding = "root:\n  sequence:\n    - gesture: {sequence: [clap, high five]}\n    - turn: 1\n"
    ends_free = "root:\n  sequence:\n    - gesture: {sequence: [high five, release arm]}\n    - turn: 1\n"
    assert [w.split(" pose")[0][-26:] for w in warnings(ends_holding)] == ["still hold the 'high five'"]
    assert warnings(ends_free) == []


def test_a_gesture_known_only_at_run_time_or_recorded_is_not_guessed():
    assert warnings("""\
        blackboard: {move: hug}
        root:
          sequence:
            - gesture: $move
            - navigate: {dx: 1}
        """) == []


def test_a_walk_before_the_gesture_or_in_a_branch_that_ran_instead_is_fine():
    assert warnings("""\
        root:
          sequence:
            - navigate: {dx: 1}
            - selector:
                - gesture: hug
                - navigate: {dx: -1}
        """) == []


def test_a_later_branch_of_a_selector_runs_after_an_earlier_one_failed_part_way():
    assert [w.split(": warning")[0] for w in warnings("""\
        root:
          selector:
            - sequence:
                - gesture: hands up
                - condition: "battery > 20"
            - navigate: {x: 0, y: 0}
        """)] == ["t.yaml:6:7: t/navigate"]


def test_a_loop_walks_again_after_the_gesture_of_its_last_round():
    assert [w.split(": warning")[0] for w in warnings("""\
        root:
          repeat:
            times: 3
            child:
              sequence:
                - navigate: {dx: 1}
                - gesture: heart
        """)] == ["t.yaml:6:11: t/sequence/navigate"]


def test_the_gesture_and_the_walk_may_be_in_different_files(tmp_path):
    (tmp_path / "greet.yaml").write_text("root:\n  sequence:\n    - speak: Hello\n    - gesture: shake hand\n")
    (tmp_path / "tour.yaml").write_text("root:\n  sequence:\n    - include: greet.yaml\n    - navigate: {dx: 2}\n")
    tree = tmp_path / "tour.yaml"
    assert warnings(tree.read_text(), file=str(tree)) == [
        f"{tree}:4:7: tour/navigate: warning: navigate while the arms may still hold the 'shake hand' pose of "
        "tour/greet/gesture (line 4); put 'gesture: release arm' between them"]


def test_the_lab_tour_releases_its_held_gestures_and_warns_when_it_does_not():
    tour = REPO / "trees" / "lab_tour.yaml"
    text = tour.read_text(encoding="utf-8")
    assert warnings(text, file=str(tour)) == []
    without = text.replace("gestures: [heart, release arm]", "gestures: [heart]")
    assert without != text
    [warning] = warnings(without, file=str(tour))
    assert ": warning: navigate while the arms may still hold the 'heart' pose of " in warning
    assert "put 'gesture: release arm' between them" in warning


def test_validate_prints_warnings_and_still_succeeds(tmp_path, capsys):
    tree = tmp_path / "hug.yaml"
    tree.write_text("root:\n  sequence:\n    - gesture: hug\n    - navigate: {dx: 1}\n")
    assert main(["validate", str(tree)]) == 0
    out, err = capsys.readouterr()
    assert out == f"{tree}: ok (1 warning)\n"
    assert err == (f"{tree}:4:7: hug/navigate: warning: navigate while the arms may still hold the 'hug' pose of "
                   "hug/gesture (line 3); put 'gesture: release arm' between them\n")
