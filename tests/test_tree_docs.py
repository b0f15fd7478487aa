"""docs/trees.md stays true: its generated reference matches the catalogue, and every YAML
example on the page loads (or, marked ``# wrong``, is refused)."""

from __future__ import annotations

import re
import shutil
import textwrap
from pathlib import Path

import pytest
import yaml

from stuart_bt.tree.docs import BEGIN, END, main, reference, update
from stuart_bt.tree.errors import TreeLoadError
from stuart_bt.tree.loader import load_tree

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


# --- the examples -----------------------------------------------------------------------------

REPO = TREES_MD.parent.parent
LAB_MARKERS = REPO / "sim" / "maps" / "lab_markers.json"
FILE_NAME = re.compile(r"#\s*(?:[\w./-]*/)?([\w.-]+\.yaml)\s*$")  # "# station.yaml", "# trees/welcome.yaml"
PATH_COMMENT = re.compile(r"#\s*([a-z_0-9]+(?:/[a-z_0-9]+)*)\s*$")  # "# tour/station_1"


def yaml_examples() -> list[tuple[int, str]]:
    """(line in docs/trees.md, text) of every ```yaml block."""
    text = TREES_MD.read_text(encoding="utf-8")
    return [(text.count("\n", 0, m.start()) + 1, m.group(1)) for m in re.finditer(r"```yaml\n(.*?)```", text, re.S)]


def file_name(line: int, example: str) -> str:
    """The name the example gives itself in a comment on one of its first lines, else its own."""
    for text in example.splitlines()[:3]:
        if match := FILE_NAME.search(text):
            return match.group(1)
    return f"example_line_{line}.yaml"


def as_tree(example: str) -> str:
    """A whole file as it is; a list of nodes in a sequence; one node as the root."""
    data = yaml.safe_load(example)
    if isinstance(data, dict) and "root" in data:
        return example
    indented = textwrap.indent(example, "    ")
    return f"root:\n  sequence:\n{indented}" if isinstance(data, list) else f"root:\n{textwrap.indent(example, '  ')}"


@pytest.fixture
def doc_folder(tmp_path: Path) -> Path:
    """A trees/ folder holding every example under its name, beside the lab's marker file (so
    an example's ``markers: ../sim/maps/lab_markers.json`` finds it)."""
    (tmp_path / "sim" / "maps").mkdir(parents=True)
    shutil.copy(LAB_MARKERS, tmp_path / "sim" / "maps")
    trees = tmp_path / "trees"
    trees.mkdir()
    for line, example in yaml_examples():
        if yaml.safe_load(example) is not None:
            (trees / file_name(line, example)).write_text(as_tree(example), encoding="utf-8")
    return trees


def test_the_page_has_yaml_examples_and_they_name_themselves_apart():
    examples = yaml_examples()
    assert len(examples) >= 8
    names = [file_name(line, text) for line, text in examples]
    assert len(set(names)) == len(names), names


@pytest.mark.parametrize(("line", "example"), yaml_examples(), ids=[f"line {n}" for n, _ in yaml_examples()])
def test_every_yaml_example_loads_or_fails_as_the_page_says(doc_folder: Path, line: int, example: str):
    if yaml.safe_load(example) is None:  # the editor's schema line on its own
        assert all(not t.strip() or t.lstrip().startswith("#") for t in example.splitlines()), example
        return
    tree = doc_folder / file_name(line, example)
    markers = None if "markers" in (yaml.safe_load(example) or {}) else LAB_MARKERS
    if "# wrong" in example:
        with pytest.raises(TreeLoadError):
            load_tree(tree, markers_file=markers)
        return
    try:
        spec = load_tree(tree, markers_file=markers)
    except TreeLoadError as e:
        raise AssertionError(f"the example at docs/trees.md:{line} does not load:\n{e}") from None
    written = {m.group(1) for text in example.splitlines()[1:] if (m := PATH_COMMENT.search(text))}
    assert written <= {n.path for n in spec.walk()}, f"docs/trees.md:{line}: paths in comments that the tree lacks"
