"""The tree view in a real browser: the lab tour ticking in the simulator, stop and continue, the
details of a node, the timeline; a saved log replayed with collapse and zoom; no two boxes
overlap whatever the tree's shape; the initial blackboard is there before the first tick."""

from __future__ import annotations

import json
import random
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from web_support import REPO, Served, browser_tests, screenshot

browser_tests()

pytestmark = [pytest.mark.slow, pytest.mark.timeout(300)]  # the simulator on a loaded machine
WAIT = 90_000  # ms: a loaded two-core machine runs the world more slowly


def node(page, path: str):
    return page.locator(f'.node[data-path="{path}"]')


def box_fill(page, path: str) -> str:
    return page.eval_on_selector(f'.node[data-path="{path}"] rect.box', "r => getComputedStyle(r).fill")


def scrub_to(page, position: int) -> None:
    page.eval_on_selector("#tl-range", "(r, v) => { r.value = v; r.dispatchEvent(new Event('input')); }", position)


def test_the_tour_ticks_in_the_browser_and_stops_and_continues(page):
    pytest.importorskip("mujoco", reason="the tour runs in the simulator (the sim extra)")
    with Served("trees/lab_tour.yaml", "--backend", "sim", "--speed", "3", "--paused") as served:
        page.goto(served.url)
        node(page, "tour").wait_for()
        assert page.locator(".node").count() == page.locator('.node[data-status="INVALID"]').count() >= 40
        page.click("#btn-run")
        node(page, "tour/welcome").and_(page.locator('[data-status="RUNNING"]')).wait_for(timeout=WAIT)
        station = node(page, "tour/station_1").element_handle()
        not_ticked = box_fill(page, "tour/station_1")
        page.wait_for_function("n => n.dataset.status === 'RUNNING'", arg=station, timeout=WAIT)
        # the same element changed colour: the page was not redrawn
        assert station.evaluate("n => n.isConnected")
        assert box_fill(page, "tour/station_1") != not_ticked
        assert node(page, "tour/welcome").get_attribute("data-status") == "SUCCESS"
        on_path = page.eval_on_selector_all(".node.onpath", "ns => ns.map(n => n.dataset.path)")
        assert on_path[:2] == ["tour", "tour/station_1"] or set(on_path) >= {"tour", "tour/station_1"}
        node(page, "tour/station_1/go/walk").click()
        assert "station_1" in page.text_content("#node-details")
        screenshot(page, "tree")

        page.click("#btn-stop")
        page.wait_for_function("document.getElementById('btn-continue').disabled === false", timeout=WAIT)
        assert page.locator('.node[data-status="RUNNING"]').count() == 0
        assert "run ended: STOPPED" in page.text_content("#console-log")

        page.click("#btn-continue")
        node(page, "tour/station_1").and_(page.locator('[data-status="RUNNING"]')).wait_for(timeout=WAIT)
        assert node(page, "tour/welcome").count() == 0  # finished steps are not done again
        page.click("#btn-stop")
        page.wait_for_function("document.getElementById('btn-continue').disabled === false", timeout=WAIT)
        code = served.close()
        output = served.output_text
    assert code == 0
    assert "every daemon is down" in output


def test_a_saved_log_replays_with_timeline_collapse_and_zoom(page, tmp_path):
    log = tmp_path / "greet.jsonl"
    subprocess.run([sys.executable, "-m", "stuart_bt.cli", "run", "trees/greet.yaml", "--backend", "dry",
                    "--speed", "50", "--view", "none", "--log", str(log)],
                   cwd=REPO, check=True, capture_output=True, timeout=120)
    with Served("--replay", str(log)) as served:
        page.goto(served.url)
        node(page, "greet").wait_for()
        assert node(page, "greet").get_attribute("data-status") == "SUCCESS"
        page.wait_for_function("document.getElementById('run-state').textContent === 'replay'")
        assert page.is_disabled("#btn-run") and page.is_disabled("#btn-stop")
        changes = int(page.get_attribute("#tl-range", "max"))
        assert changes > 5

        scrub_to(page, 0)
        assert page.locator(".node").count() == page.locator('.node[data-status="INVALID"]').count()
        assert "replay" in page.text_content("#tl-label")
        scrub_to(page, 2)
        assert page.locator('.node[data-status="RUNNING"]').count() >= 1
        page.click("#tl-play")
        page.wait_for_function("document.querySelector('.node[data-path=\"greet\"]').dataset.status === 'SUCCESS'",
                               timeout=30_000)

        total = page.locator(".node").count()
        page.click('.node[data-path="greet/hello"] .toggler')
        assert page.locator(".node").count() < total
        assert "+" in page.text_content('.node[data-path="greet/hello"]')
        page.click("#expand-all")
        assert page.locator(".node").count() == total

        before = page.get_attribute("#tree-g", "transform")
        page.click("#zoom-in")
        assert page.get_attribute("#tree-g", "transform") != before


# -- tree shapes for the layout: nodes as the tree file writes them (JSON is YAML) ----------------
def leaf(name: str) -> dict[str, Any]:
    return {"log": {"name": name, "message": name}}


def decorated(kinds: list[str], child: dict[str, Any], name: str) -> dict[str, Any]:
    """``kinds`` wrapped around ``child``, outermost first."""
    options = {"retry": {"times": 2}, "repeat": {"times": 2}, "timeout": {"seconds": 5}}
    for depth, kind in enumerate(reversed(kinds)):
        child = {kind: {"name": f"{name}_{depth}", **options.get(kind, {}), "child": child}}
    return child


def composite(kind: str, name: str, children: list[dict[str, Any]]) -> dict[str, Any]:
    return {kind: {"name": name, "children": children}}


def random_tree(rng: random.Random, name: str = "n", depth: int = 0) -> dict[str, Any]:
    roll = rng.random() if depth < 5 else 1.0
    if roll < 0.35:
        kind = rng.choice(["sequence", "selector", "parallel"])
        return composite(kind, name, [random_tree(rng, f"{name}{i}", depth + 1) for i in range(rng.randint(1, 4))])
    if roll < 0.6:
        return decorated([rng.choice(["retry", "inverter", "timeout", "force_success"])],
                         random_tree(rng, f"{name}d", depth + 1), name)
    return leaf(name)


def random_shape(seed: int) -> dict[str, Any]:
    rng = random.Random(seed)
    return composite("sequence", "random", [random_tree(rng, f"n{i}_", 1) for i in range(5)])


SHAPES = {
    "the issue's: a decorator over a leaf, then a leaf": composite("sequence", "go", [
        decorated(["retry"], leaf("walk"), "go"), leaf("log")]),
    "deep decorators": composite("sequence", "deep", [
        decorated(["retry", "timeout", "inverter", "force_success", "repeat"], leaf("a"), "chain"),
        leaf("b"), decorated(["inverter"], leaf("c"), "one"), leaf("d"),
        decorated(["retry", "timeout"], composite("sequence", "inner", [leaf("e"), leaf("f")]), "pair"), leaf("g")]),
    "wide sequences": composite("sequence", "wide", [
        *[composite("sequence", f"s{i}", [leaf(f"s{i}_{j}") for j in range(8)]) for i in range(3)],
        *[leaf(f"top{j}") for j in range(10)]]),
    "mixed": composite("selector", "mixed", [
        composite("parallel", "both", [decorated(["retry"], composite("sequence", "try", [leaf("a"), leaf("b")]), "r"),
                                       leaf("c")]),
        decorated(["inverter"], composite("selector", "either", [leaf("d"), decorated(["timeout"], leaf("e"), "t")]),
                  "not"),
        leaf("f"),
        composite("sequence", "last", [decorated(["retry"], leaf("g"), "g"), leaf("h"),
                                       composite("sequence", "one", [leaf("i")])])]),
    **{f"random, seed {seed}": random_shape(seed) for seed in (1, 2, 3)},
}


def count_nodes(node: dict[str, Any]) -> int:
    options = next(iter(node.values()))
    below = options.get("children", []) + ([options["child"]] if "child" in options else [])
    return 1 + sum(count_nodes(c) for c in below)


OVERLAPS = """() => {
  const boxes = [...document.querySelectorAll('.node rect.box')]
    .map((r) => [r.parentNode.dataset.path, r.getBoundingClientRect()]);
  const out = [];
  for (let i = 0; i < boxes.length; i++) for (let j = i + 1; j < boxes.length; j++) {
    const [p, a] = boxes[i], [q, b] = boxes[j];
    if (a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom) out.push([p, q]);
  }
  return out;
}"""


@pytest.mark.parametrize("shape", SHAPES)
def test_no_two_node_boxes_overlap_whatever_the_shape_of_the_tree(page, tmp_path: Path, shape: str):
    root = SHAPES[shape]
    tree = tmp_path / "shape.yaml"
    tree.write_text(json.dumps({"description": shape, "root": root}))
    with Served(str(tree), "--paused") as served:
        page.goto(served.url)
        page.locator(".node").first.wait_for()
        assert page.locator(".node").count() == count_nodes(root)
        assert page.evaluate(OVERLAPS) == []
        parents = page.eval_on_selector_all(".node .toggler", "ts => ts.map(t => t.parentNode.dataset.path)")
        page.click(f'.node[data-path="{parents[len(parents) // 2]}"] .toggler')  # a collapsed subtree is one row
        assert page.locator(".node").count() < count_nodes(root)
        assert page.evaluate(OVERLAPS) == []


def test_the_initial_blackboard_is_shown_before_the_first_tick(page, tmp_path: Path):
    tree = tmp_path / "visit.yaml"
    tree.write_text("blackboard:\n  visitors: school group\n  rounds: {kitchen: 2}\n"
                    "root:\n  sequence:\n    name: visit\n    children:\n      - log: welcome\n")
    with Served(str(tree), "--paused") as served:
        page.goto(served.url)
        node(page, "visit").wait_for()
        page.locator('#bb-table tr[data-key="rounds"]').wait_for()
        rows = page.eval_on_selector_all("#bb-table tr", "rs => rs.map(r => [...r.cells].map(c => c.textContent))")
        assert rows == [["rounds", '{"kitchen":2}'], ["visitors", "school group"]]
        assert node(page, "visit").get_attribute("data-status") == "INVALID"  # nothing ticked yet
