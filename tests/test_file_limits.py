"""Files a tree names are read with limits: a regular file under the size cap, never a device or
a FIFO; includes only from the tree's folder, the working folder or STUART_BT_TREE_PATH, so an
error never quotes someone else's file. And the loader, fuzzed, only ever says what is wrong."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from stuart_bt.tree.errors import TreeLoadError
from stuart_bt.tree.loader import load_tree_text

REPO = Path(__file__).resolve().parents[1]


def validate(tree: Path, cwd: Path, **env: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "stuart_bt.cli", "validate", str(tree)], cwd=cwd,
                          capture_output=True, text=True, timeout=60, env={**os.environ, **env})


def write_tree(folder: Path, body: str, name: str = "t.yaml") -> Path:
    path = folder / name
    path.write_text(textwrap.dedent(body))
    return path


@pytest.mark.parametrize("special", ["/dev/zero", "/dev/urandom", "fifo"])
def test_a_marker_file_that_is_a_device_or_a_fifo_is_refused_at_once(tmp_path: Path, special: str):
    if special == "fifo":
        special = str(tmp_path / "markers.fifo")
        os.mkfifo(special)
    tree = write_tree(tmp_path, f"""\
        markers: {special}
        root:
          navigate: kitchen
        """)
    done = validate(tree, tmp_path)
    assert done.returncode == 1
    assert "not a regular file" in done.stdout + done.stderr
    assert "Traceback" not in done.stderr


def test_a_tree_file_that_is_a_fifo_is_refused_at_once(tmp_path: Path):
    fifo = tmp_path / "tree.yaml"
    os.mkfifo(fifo)
    done = validate(fifo, tmp_path)
    assert done.returncode == 1 and "not a regular file" in done.stdout + done.stderr


def test_an_include_outside_the_allowed_folders_is_refused_unread_and_not_quoted(tmp_path: Path):
    project = tmp_path / "project"
    project.mkdir()
    tree = write_tree(project, """\
        root:
          sequence:
            children:
              - include: /etc/passwd
        """)
    done = validate(tree, project)
    out = done.stdout + done.stderr
    assert done.returncode == 1
    assert "outside the folders trees may include from" in out and "STUART_BT_TREE_PATH" in out
    assert "root:x:" not in out  # not a line of it


def test_a_folder_on_the_tree_path_may_be_included_from(tmp_path: Path):
    shared, project = tmp_path / "shared", tmp_path / "project"
    shared.mkdir()
    project.mkdir()
    write_tree(shared, """\
        root:
          wait: 1
        """, "pause.yaml")
    tree = write_tree(project, f"""\
        root:
          sequence:
            children:
              - include: {shared / "pause.yaml"}
        """)
    assert validate(tree, project).returncode == 1  # not allowed by default ...
    done = validate(tree, project, STUART_BT_TREE_PATH=str(shared))
    assert done.returncode == 0, done.stdout + done.stderr  # ... allowed once declared


TOKENS = [*"abc:- \n\t[]{}!&*|>'\"#%@`,?0123456789", "root", "sequence", "children", "include", "navigate",
          "!!python/object", "markers", "/dev/zero", "\n  ", "\n    - "]
YAMLISH = st.lists(st.sampled_from(TOKENS), max_size=60).map("".join)


@settings(max_examples=300, deadline=None)
@given(YAMLISH)
def test_any_text_loads_or_fails_with_the_loaders_own_error(text: str):
    try:
        load_tree_text(text, "<fuzz>")
    except TreeLoadError as e:
        assert str(e)
