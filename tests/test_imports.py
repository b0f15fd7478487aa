"""The package's structure stays as docs/architecture.md draws it: every import points down the
list of layers below, no two modules import each other (directly or round a circle), and
nothing in the package imports the repository's bench/.

The imports are read from the source (every ``import`` and ``from ... import``, also inside
functions; only those under ``if TYPE_CHECKING:`` are left out, as they never run).
"""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
MAPPED = {"skills": "stuart_bt.skills", "sim": "stuart_bt.sim", "tasks": "stuart_bt.tasks"}  # as in setup.py

# Bottom first: a part may import itself and the parts above it in this list, never one below.
LAYERS = (
    "core",          # clock, events, blackboard, world state, expressions, catalogue, errors, JSON files
    "maps",          # occupancy grid, inflation, A* paths, map and marker files (core and numpy only)
    "daemon",        # the line protocol, the supervisor, the daemon client
    "hearing",       # sound sources, voice activity, speech recognition
    "tree",          # YAML trees: loading, checking, building, drawing
    "language",      # wake filter, numbers, the grammar, resolving names
    "conversation",  # the reply interface and its backends
    "sim",           # the MuJoCo world server and the robot description
    "perception",    # camera, detector, depth, spatial memory
    "skills",        # the daemon programs and their backends
    "leaves",        # the tree's skill leaves
    "htn",           # the task domain language and the planner
    "tasks",         # the project's own domain
    "run",           # executor, session, report, views
    "mission",       # queue, understanding, planning, repair
    "web",           # the browser view
    "ros",           # the ROS 2 bridge
    "cli",           # every stuart-bt command
    "testing",       # the pytest helpers people use
    "pytest_plugin",
)


def module_name(path: Path) -> str:
    parts = list(path.relative_to(REPO).with_suffix("").parts)
    if parts[0] in MAPPED:
        parts = MAPPED[parts[0]].split(".") + parts[1:]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def package_files() -> Iterator[Path]:
    for root in ("stuart_bt", *MAPPED):
        yield from sorted((REPO / root).rglob("*.py"))


def runtime_imports(tree: ast.AST) -> Iterator[ast.Import | ast.ImportFrom]:
    """Import statements, skipping the bodies of ``if TYPE_CHECKING:``."""
    stack = [tree]
    while stack:
        node = stack.pop()
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            stack.extend(node.orelse)
            continue
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node
        stack.extend(ast.iter_child_nodes(node))


def imported(path: Path, modules: set[str]) -> set[str]:
    """The package modules a file imports (a name that is a module counts as that module)."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found: set[str] = set()
    for node in runtime_imports(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        else:
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[: len(parts) - node.level + 1] + ([node.module] if node.module else []))
            targets = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base for alias in node.names]
        found.update(t for t in targets if t in modules or t.startswith("bench"))
    found.discard(name)
    return found


@pytest.fixture(scope="module")
def graph() -> dict[str, set[str]]:
    files = list(package_files())
    modules = {module_name(p) for p in files}
    return {module_name(p): imported(p, modules) for p in files}


def part_of(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else parts[0]


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected groups of more than one module (Tarjan's algorithm, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    found: list[list[str]] = []
    for start in graph:
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next((c for c in children if c in graph), None)
            if child is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    group = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        group.append(member)
                        if member == node:
                            break
                    if len(group) > 1:
                        found.append(sorted(group))
            elif child not in index:
                index[child] = low[child] = len(index)
                stack.append(child)
                on_stack.add(child)
                work.append((child, iter(sorted(graph[child]))))
            elif child in on_stack:
                low[node] = min(low[node], index[child])
    return found


def test_every_part_of_the_package_has_a_place_in_the_layers(graph):
    parts = {part_of(m) for m in graph if m != "stuart_bt"}
    assert parts <= set(LAYERS), f"parts with no layer (add them to LAYERS and docs/architecture.md): " \
                                 f"{sorted(parts - set(LAYERS))}"


def test_imports_only_point_down_the_layers(graph):
    rank = {part: n for n, part in enumerate(LAYERS)}
    upward = sorted(f"{m} -> {t}" for m, targets in graph.items() for t in targets
                    if not t.startswith("bench") and m != "stuart_bt" and t != "stuart_bt"
                    and rank[part_of(t)] > rank[part_of(m)])
    assert not upward, "imports that point up the layers:\n  " + "\n  ".join(upward)


def test_no_modules_import_each_other_round_a_circle(graph):
    assert circles(graph) == []


def test_nothing_in_the_package_imports_the_benchmarks(graph):
    assert not [f"{m} -> {t}" for m, targets in graph.items() for t in targets if t.startswith("bench")]


def test_the_circle_finder_finds_a_circle():
    assert circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert circles({"a": {"b"}, "b": set()}) == []
