"""Which way a tree picture runs: top to bottom or left to right, from the tree's shape.

Graphviz draws a tree top to bottom by default: each level of depth is a row and the leaves sit
side by side, so a wide, shallow tree (a tour of six stations) becomes a strip thousands of
points wide and a few hundred high, whose labels are unreadable once it is shrunk to a screen.
Left to right, levels are columns and the leaves stack down the page.

The rule: estimate the picture's size both ways (Graphviz's own node sizes and spacings for the
labels, :func:`picture_size`), shrink each to fit a landscape screen, and take the one whose
labels stay larger; when both fit whole, the one shaped more like the screen. So a wide,
shallow tree runs left to right, a deep, narrow one top to bottom, whatever its size. Only the
tree's shape and its labels decide, so any tree gets the same treatment.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from .spec import NodeSpec

DIRECTIONS = ("auto", "tb", "lr")  # what people may ask for (show --direction)
SCREEN = (1440.0, 810.0)  # points: a 1920 x 1080 pixel screen at 96 dpi, the size a picture should fit

# Graphviz's geometry for the drawing's attributes (Helvetica 11 pt; sizes in points): the
# defaults nodesep 0.25 in, ranksep 0.5 in, node height 0.5 in, minimum width 0.75 in, and how much
# wider than its text each shape is (measured with dot -Tplain).
CHAR_WIDTH = 5.9  # an average character of Helvetica at 11 pt
NODE_HEIGHT, MIN_WIDTH = 36.0, 54.0
NODE_GAP, LEVEL_GAP = 18.0, 36.0
MARGIN = 8.0
SHAPE_WIDTH = {"box": (1.0, 16.0), "ellipse": (1.2, 20.0), "hexagon": (1.4, 19.0)}  # text * a + b


def node_width(text: str, shape: str) -> float:
    """About how wide Graphviz draws a node with this label and shape."""
    factor, padding = SHAPE_WIDTH[shape]
    return max(MIN_WIDTH, factor * CHAR_WIDTH * len(text) + padding)


def picture_size(root: NodeSpec, width: Callable[[NodeSpec], float], rankdir: str) -> tuple[float, float]:
    """(width, height) in points of the tree drawn ``TB`` or ``LR``; ``width`` gives a node's width.

    Each level of depth is a row (``TB``) or a column (``LR``). A row is as long as its nodes side
    by side; a column is as wide as its widest node and as tall as its nodes stacked. Graphviz
    lets subtrees of different depths share the room across, so the longest row (or tallest
    column) is what the picture needs across."""
    levels: list[list[float]] = []
    stack = [(root, 0)]
    while stack:
        node, level = stack.pop()
        if level == len(levels):
            levels.append([])
        levels[level].append(width(node))
        stack += [(child, level + 1) for child in node.children]
    deep = len(levels)
    if rankdir == "TB":
        across = max(sum(row) + NODE_GAP * (len(row) - 1) for row in levels)
        return across + MARGIN, deep * NODE_HEIGHT + (deep - 1) * LEVEL_GAP + MARGIN
    across = max(len(column) * NODE_HEIGHT + NODE_GAP * (len(column) - 1) for column in levels)
    return sum(max(column) for column in levels) + (deep - 1) * LEVEL_GAP + MARGIN, across + MARGIN


def legibility(size: tuple[float, float]) -> float:
    """How large the labels stay when the picture is shrunk to fit the screen (1: full size)."""
    return min(1.0, SCREEN[0] / size[0], SCREEN[1] / size[1])


def misfit(size: tuple[float, float]) -> float:
    """How far the picture's shape is from the screen's (0: the same proportions), either way."""
    return abs(math.log((size[0] / size[1]) / (SCREEN[0] / SCREEN[1])))


def choose_direction(root: NodeSpec, width: Callable[[NodeSpec], float], asked: str = "auto") -> str:
    """Graphviz's ``rankdir``: ``TB`` or ``LR`` as asked, or for ``auto`` the one whose picture
    fits a screen better: its labels larger once shrunk to fit, or, when both fit whole, its
    shape closer to the screen's (a strip is hard to take in even when its labels are legible)."""
    if asked != "auto":
        return asked.upper()
    across, down = picture_size(root, width, "LR"), picture_size(root, width, "TB")
    if legibility(across) != legibility(down):
        return "LR" if legibility(across) > legibility(down) else "TB"
    return "LR" if misfit(across) < misfit(down) else "TB"
