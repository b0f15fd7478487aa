"""The generated reference in docs/trees.md matches the catalogue."""

from __future__ import annotations

from pathlib import Path

import pytest

from stuart_bt.tree.docs import BEGIN, END, main, reference, update

TREES_MD = Path(__file__).parent.parent / "docs" / "trees.md"


def test_committed_reference_section_is_current():
    text = TREES_MD.read_text(encoding="utf-8")
    assert update(text) == text, "run: python -m stuart_bt.tree.docs"


def test_reference_lists_every_kind_with_its_parameters():
    text = reference()
    for kind in ("sequence", "parallel", "retry", "guard", "navigate", "gesture", "set", "log"):
        assert f"#### `{kind}`" in text
    assert "| `policy` | choice (all / one / selected) |  | `\"all\"` | all \\| one \\| selected |" in text
    assert "Shorthand `navigate: <marker>`; one of `marker` | `x, y, yaw` | `dx, dy, dyaw`" in text


def test_update_rewrites_only_the_marked_section():
    text = f"intro\n{BEGIN}\nSTALE TEXT\n{END}\noutro\n"
    new = update(text)
    assert new.startswith(f"intro\n{BEGIN}\n") and new.endswith(f"{END}\noutro\n")
    assert "STALE TEXT" not in new and "#### `navigate`" in new
    with pytest.raises(ValueError, match="markers not found"):
        update("no markers here")


def test_check_mode_reports_an_outdated_file(tmp_path, capsys):
    stale = tmp_path / "trees.md"
    stale.write_text(f"{BEGIN}\nstale\n{END}\n", encoding="utf-8")
    assert main([str(stale), "--check"]) == 1
    assert "out of date" in capsys.readouterr().out
    assert main([str(stale)]) == 0
    assert main([str(stale), "--check"]) == 0
