"""Drawing trees: text trees, Graphviz, pictures, YAML, and a clear error without Graphviz."""

from __future__ import annotations

import re
import shutil
import subprocess
import textwrap
from pathlib import Path

import pytest

from stuart_bt.tree import render as render_module
from stuart_bt.tree.layout import legibility, misfit
from stuart_bt.tree.loader import load_tree, load_tree_text
from stuart_bt.tree.render import RenderError, render
from stuart_bt.tree.spec import TreeSpec

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


def _svg_size(svg: str | bytes) -> tuple[float, float]:
    """Width and height in points, as Graphviz writes them on the <svg> element."""
    text = svg if isinstance(svg, str) else svg.decode()
    found = re.search(r'<svg width="([\d.]+)pt" height="([\d.]+)pt"', text)
    assert found, text[:300]
    return float(found[1]), float(found[2])


def _sequence(leaves: int) -> TreeSpec:
    """One sequence of ``leaves`` steps: as wide as it gets, one level deep."""
    steps = "\n".join(f"      - speak: step {i} of the list" for i in range(leaves))
    return load_tree_text(f"root:\n  sequence:\n    name: steps\n    children:\n{steps}\n")


def _chain(depth: int) -> TreeSpec:
    """``depth`` decorators nested over one leaf: as deep as it gets, one node wide."""
    node = "wait: 1"
    for _ in range(depth):
        node = "retry:\n  times: 2\n  child:\n" + textwrap.indent(node, "    ")
    return load_tree_text("root:\n" + textwrap.indent(node, "  ") + "\n")


def _blocks(blocks: int, leaves: int) -> TreeSpec:
    """A sequence of ``blocks`` sequences of ``leaves`` steps each."""
    body = "\n".join(f"      - sequence:\n          name: block_{b}\n          children:\n"
                     + "\n".join("            - gesture: wave" for _ in range(leaves)) for b in range(blocks))
    return load_tree_text(f"root:\n  sequence:\n    name: blocks\n    children:\n{body}\n")


SHAPES = {
    "the lab tour": lambda: load_tree(Path(__file__).parents[1] / "trees" / "lab_tour.yaml"),
    "all constructs": lambda: load_tree(TREES / "all_constructs.yaml"),
    "a list of 3 steps": lambda: _sequence(3),
    "a list of 12 steps": lambda: _sequence(12),
    "a list of 40 steps": lambda: _sequence(40),
    "4 blocks of 5 steps": lambda: _blocks(4, 5),
    "8 nested decorators": lambda: _chain(8),
    "3 nested decorators": lambda: _chain(3),
}


@needs_dot
@pytest.mark.parametrize("shape", SHAPES)
def test_the_direction_chosen_gives_the_picture_that_fits_a_screen_better(shape: str) -> None:
    """Graphviz's real picture both ways: the one chosen shows its labels at least as large once
    shrunk to a screen, and when both fit whole it is shaped more like the screen."""
    spec = SHAPES[shape]()
    chosen = render_module.direction(spec.root)
    other = {"LR": "tb", "TB": "lr"}[chosen]
    mine, theirs = _svg_size(render(spec, "svg")), _svg_size(render(spec, "svg", direction=other))
    assert legibility(mine) >= legibility(theirs), (chosen, mine, theirs)
    if legibility(theirs) == 1.0:
        assert misfit(mine) <= misfit(theirs), (chosen, mine, theirs)


@needs_dot
def test_a_wide_shallow_tree_is_drawn_left_to_right_so_its_picture_is_not_a_strip():
    for spec in (load_tree(Path(__file__).parents[1] / "trees" / "lab_tour.yaml"), _sequence(12), _blocks(4, 5)):
        assert "rankdir=LR" in render(spec, "dot")
        width, height = _png_size(render(spec, "png"))
        strip_width, strip_height = _png_size(render(spec, "png", direction="tb"))
        assert strip_width / strip_height > 5  # top to bottom it would be a strip ...
        assert max(width, height) / min(width, height) < 3, (width, height)  # ... left to right it is not


def test_a_deep_narrow_tree_is_drawn_top_to_bottom():
    assert render_module.direction(_chain(8).root) == "TB"
    assert "rankdir=TB" in render(_chain(8), "dot")


def test_the_direction_can_be_forced_either_way():
    wide, deep = _sequence(12), _chain(8)
    assert "rankdir=TB" in render(wide, "dot", direction="tb")
    assert "rankdir=LR" in render(deep, "dot", direction="lr")
    with pytest.raises(RenderError, match="unknown direction 'up'; expected one of auto, tb, lr"):
        render(wide, "dot", direction="up")
