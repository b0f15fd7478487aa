"""Drawing trees: text trees, Graphviz, pictures, YAML, and a clear error without Graphviz."""

from __future__ import annotations

import shutil
import subprocess
import textwrap
from pathlib import Path

import pytest

from stuart_bt.tree import render as render_module
from stuart_bt.tree.loader import load_tree, load_tree_text
from stuart_bt.tree.render import RenderError, render

TREES = Path(__file__).parent / "data" / "trees"
needs_dot = pytest.mark.skipif(shutil.which("dot") is None, reason="graphviz not installed (make installs it)")

TOUR = load_tree_text(textwrap.dedent("""\
    root:
      sequence:
        name: tour
        children:
          - navigate: station_1
          - selector:
              name: recover
              children:
                - condition: "battery > 20"
                - speak: {text: "Low \\"battery\\"", name: warn}
          - retry: {times: 3, child: {pick: cup}}
          - parallel: {policy: one, children: [{wait: 5}, {gesture: wave}]}
    """))


def test_unicode_tree_shows_glyphs_names_and_key_params():
    assert render(TOUR, "unicode") == textwrap.dedent("""\
        [->] tour
        ├── navigate marker=station_1
        ├── [?] recover
        │   ├── condition expr="battery > 20"
        │   └── speak text="Low \\"battery\\"" (warn)
        ├── <retry times=3>
        │   └── pick object=cup
        └── [=>] parallel policy=one
            ├── wait seconds=5
            └── gesture play=wave
        """)


def test_ascii_tree_uses_plain_characters():
    text = render(TOUR, "ascii")
    assert text.splitlines()[:3] == ["[->] tour", "|-- navigate marker=station_1", "|-- [?] recover"]
    assert "`-- [=>] parallel policy=one" in text
    assert text.isascii()


def test_statuses_mark_nodes():
    statuses = {"tour": "RUNNING", "tour/navigate": "SUCCESS", "tour/recover/warn": "FAILURE"}
    unicode = render(TOUR, "unicode", statuses).splitlines()
    assert unicode[0] == "▶ [->] tour"
    assert unicode[1] == "├── ✔ navigate marker=station_1"
    assert unicode[4] == "│   └── ✘ speak text=\"Low \\\"battery\\\"\" (warn)"
    assert render(TOUR, "ascii", statuses).splitlines()[1] == "|-- (+) navigate marker=station_1"


def test_included_subtrees_name_their_file():
    text = render(load_tree(TREES / "tour.yaml"), "ascii")
    assert f"|-- [->] station_1  <- {TREES / 'station.yaml'}" in text


def test_long_values_are_shortened():
    spec = load_tree_text("root: {speak: \"" + "word " * 30 + "\"}\n")
    assert render(spec, "unicode") == 'speak text="' + ("word " * 8)[:38] + "… (root)\n"
    assert render(spec, "ascii") == 'speak text="' + ("word " * 8)[:36] + "... (root)\n"


def test_dot_keys_nodes_by_path_with_shapes_and_escaped_labels():
    dot = render(TOUR, "dot")
    assert dot.startswith('digraph "tour" {')
    assert '"tour/recover" [label="[?] recover", shape=box' in dot
    assert '"tour/retry" [label="<retry times=3>", shape=hexagon' in dot
    assert '"tour/navigate" [label="navigate marker=station_1", shape=ellipse' in dot
    assert r'"tour/recover/warn" [label="speak text=\"Low \\\"battery\\\"\" (warn)"' in dot
    assert '"tour" -> "tour/recover";' in dot


def test_dot_fills_nodes_by_status():
    dot = render(TOUR, "dot", {"tour/navigate": "SUCCESS", "tour/retry": "FAILURE", "tour": "RUNNING"})
    line = {ln.split(" [")[0].strip(): ln for ln in dot.splitlines() if " [label=" in ln}
    assert 'fillcolor="#b7e1a1"' in line['"tour/navigate"']
    assert 'fillcolor="#f4a6a6"' in line['"tour/retry"']
    assert 'fillcolor="#ffe08a"' in line['"tour"']
    assert "fillcolor=\"#" not in line['"tour/recover"'].split("shape")[1]


@needs_dot
def test_dot_output_is_valid_graphviz():
    for spec in (TOUR, load_tree(TREES / "all_constructs.yaml")):
        done = subprocess.run(["dot", "-Tsvg"], input=render(spec, "dot", {spec.root.path: "FAILURE"}).encode(),
                              capture_output=True, check=False)
        assert done.returncode == 0, done.stderr.decode()
        assert done.stderr == b""


@needs_dot
def test_svg_and_png_are_drawn_by_graphviz():
    svg = render(TOUR, "svg")
    assert isinstance(svg, str) and "<svg" in svg and "recover" in svg
    png = render(TOUR, "png")
    assert isinstance(png, bytes) and png.startswith(b"\x89PNG")


def test_missing_graphviz_says_how_to_install_it(monkeypatch):
    monkeypatch.setattr(render_module.shutil, "which", lambda name: None)
    with pytest.raises(RenderError, match=r"install graphviz \(make installs it\)"):
        render(TOUR, "svg")


def test_yaml_format_is_the_expanded_tree():
    text = render(load_tree(TREES / "tour.yaml"), "yaml")
    assert "include:" not in text and "name: station_2" in text


def test_unknown_format_is_an_error():
    with pytest.raises(RenderError, match="unknown format 'jpeg'; expected one of unicode, ascii, dot, svg, png, yaml"):
        render(TOUR, "jpeg")


def _png_size(png: bytes) -> tuple[int, int]:
    """Width and height from a PNG's IHDR chunk."""
    return int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")


@needs_dot
def test_a_wide_tree_is_drawn_left_to_right_so_its_picture_is_not_a_strip():
    tour = load_tree(Path(__file__).parents[1] / "trees" / "lab_tour.yaml")
    assert render_module.direction(tour.root) == "LR"
    width, height = _png_size(render(tour, "png"))
    assert max(width, height) / min(width, height) < 4, (width, height)


def test_a_tree_as_deep_as_it_is_wide_is_drawn_top_to_bottom():
    assert render_module.direction(TOUR.root) == "TB"
    assert "rankdir=TB" in render(TOUR, "dot")
