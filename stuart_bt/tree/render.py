"""Drawing a loaded tree: text trees for terminals, Graphviz for pictures, YAML for reading back.

``statuses`` (node path -> SUCCESS/FAILURE/RUNNING/INVALID) marks each node, so the same
drawing shows a tree at rest (``stuart-bt show``) or as it ran (a report, the web view).

Glyphs: ``[->]`` sequence, ``[?]`` selector, ``[=>]`` parallel, ``<kind ...>`` decorator,
``kind params`` leaf; a node's name follows when it differs from its kind.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from typing import Any

from ..core.catalogue import COMPOSITES, DECORATORS
from ..core.errors import StuartError
from .export import to_yaml
from .layout import DIRECTIONS, choose_direction, node_width
from .spec import NodeSpec, TreeSpec

FORMATS = ("unicode", "ascii", "dot", "svg", "png", "yaml")
GLYPHS = {"sequence": "[->]", "selector": "[?]", "parallel": "[=>]"}
STATUS_MARKS = {
    "unicode": {"SUCCESS": "✔", "FAILURE": "✘", "RUNNING": "▶", "INVALID": "·"},
    "ascii": {"SUCCESS": "(+)", "FAILURE": "(x)", "RUNNING": "(*)", "INVALID": "(-)"},
}
BRANCHES = {
    "unicode": ("├── ", "└── ", "│   ", "    "),
    "ascii": ("|-- ", "`-- ", "|   ", "    "),
}
FILL = {"SUCCESS": "#b7e1a1", "FAILURE": "#f4a6a6", "RUNNING": "#ffe08a", "INVALID": "#e0e0e0"}
SHAPES = {"composite": "box", "decorator": "hexagon", "leaf": "ellipse"}
MAX_VALUE = 40


class RenderError(StuartError, RuntimeError):
    """A drawing could not be made (unknown format, Graphviz missing or failing)."""


def render(spec: TreeSpec, fmt: str, statuses: dict[str, str] | None = None, direction: str = "auto") -> str | bytes:
    """The tree drawn in ``fmt``; bytes for png, text for the others. ``direction`` (dot, svg,
    png): ``tb`` top to bottom, ``lr`` left to right, ``auto`` from the tree's shape."""
    statuses = statuses or {}
    if fmt in ("unicode", "ascii"):
        return _text(spec.root, fmt, statuses)
    if fmt == "dot":
        return _dot(spec, statuses, direction)
    if fmt in ("svg", "png"):
        image = _graphviz(_dot(spec, statuses, direction), fmt)
        return image.decode("utf-8") if fmt == "svg" else image
    if fmt == "yaml":
        return to_yaml(spec)
    raise RenderError(f"unknown format {fmt!r}; expected one of {', '.join(FORMATS)}")


def label(node: NodeSpec, ascii_only: bool = False) -> str:
    """One-line description: glyph or kind, name when it differs from the kind, key params."""
    text = _label(node, ascii_only)
    return text.encode("ascii", "backslashreplace").decode("ascii") if ascii_only else text


def _label(node: NodeSpec, ascii_only: bool) -> str:
    params = " ".join(f"{k}={_value(v, ascii_only)}" for k, v in node.params.items())
    if node.kind in COMPOSITES:
        text = f"{GLYPHS[node.kind]} {node.name}"
        return f"{text} {params}" if params else text
    if node.kind in DECORATORS:
        head = f"<{node.kind} {params}>" if params else f"<{node.kind}>"
        return head if node.name == node.kind else f"{head} {node.name}"
    text = f"{node.kind} {params}" if params else node.kind
    return text if node.name == node.kind else f"{text} ({node.name})"


def _value(value: Any, ascii_only: bool) -> str:
    if isinstance(value, str):
        text = value if value and all(c.isalnum() or c in "_-.$/" for c in value) else json.dumps(
            value, ensure_ascii=ascii_only)
    elif isinstance(value, bool) or value is None:
        text = json.dumps(value)
    elif isinstance(value, float):
        text = f"{value:g}"
    else:
        text = json.dumps(value, ensure_ascii=ascii_only, default=str)
    if len(text) > MAX_VALUE:
        text = text[:MAX_VALUE - 3] + "..." if ascii_only else text[:MAX_VALUE - 1] + "…"
    return text


def _text(root: NodeSpec, fmt: str, statuses: dict[str, str]) -> str:
    tee, last, pipe, blank = BRANCHES[fmt]
    marks = STATUS_MARKS[fmt]
    lines: list[str] = []

    def line(node: NodeSpec, prefix: str, branch: str) -> None:
        mark = marks.get(statuses.get(node.path, "").upper(), "")
        text = label(node, ascii_only=fmt == "ascii")
        include = f"  <- {node.include}" if node.include else ""
        lines.append(f"{prefix}{branch}{mark + ' ' if mark else ''}{text}{include}")

    def walk(node: NodeSpec, prefix: str) -> None:
        for i, child in enumerate(node.children):
            final = i == len(node.children) - 1
            line(child, prefix, last if final else tee)
            walk(child, prefix + (blank if final else pipe))

    line(root, "", "")
    walk(root, "")
    return "\n".join(lines) + "\n"


def category(node: NodeSpec) -> str:
    """composite, decorator or leaf: how a node is drawn (and named in the tree snapshot)."""
    if node.kind in COMPOSITES:
        return "composite"
    return "decorator" if node.kind in DECORATORS else "leaf"


def _quote(text: str) -> str:
    """A Graphviz double-quoted string; backslashes and quotes escaped, newlines as line breaks."""
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def direction(root: NodeSpec, asked: str = "auto") -> str:
    """Graphviz's ``rankdir`` for a picture of the tree: as ``asked`` (``tb``, ``lr``), or for
    ``auto`` from its shape (stuart_bt.tree.layout: a wide, shallow tree runs left to right)."""
    if asked not in DIRECTIONS:
        raise RenderError(f"unknown direction {asked!r}; expected one of {', '.join(DIRECTIONS)}")
    return choose_direction(root, lambda node: node_width(label(node), SHAPES[category(node)]), asked)


def _dot(spec: TreeSpec, statuses: dict[str, str], asked: str) -> str:
    out = [
        f"digraph {_quote(spec.root.name)} {{",
        f'  graph [rankdir={direction(spec.root, asked)}, fontname="Helvetica"];',
        '  node [fontname="Helvetica", fontsize=11, style=filled, fillcolor="#ffffff"];',
        '  edge [arrowsize=0.6];',
    ]
    for node in spec.walk():
        attrs = [f"label={_quote(label(node))}", f"shape={SHAPES[category(node)]}"]
        status = statuses.get(node.path, "").upper()
        if status in FILL:
            attrs.append(f"fillcolor={_quote(FILL[status])}")
            attrs.append(f"tooltip={_quote(f'{node.path}: {status}')}")
        if category(node) == "composite":
            attrs.append('style="filled,rounded"')
        out.append(f"  {_quote(node.path)} [{', '.join(attrs)}];")
        out.extend(f"  {_quote(node.path)} -> {_quote(child.path)};" for child in node.children)
    out.append("}")
    return "\n".join(out) + "\n"


def _graphviz(dot_text: str, fmt: str) -> bytes:
    dot = shutil.which("dot")
    if dot is None:
        raise RenderError(f"drawing {fmt} needs the Graphviz 'dot' program: install graphviz (make installs it)")
    try:
        done = subprocess.run([dot, f"-T{fmt}"], input=dot_text.encode("utf-8"), capture_output=True, timeout=60,
                              check=False)
    except (OSError, subprocess.TimeoutExpired) as e:
        raise RenderError(f"Graphviz 'dot' failed: {e}") from None
    if done.returncode != 0:
        raise RenderError(f"Graphviz 'dot' failed: {done.stderr.decode('utf-8', 'replace').strip()}")
    return done.stdout
