"""The tree view in a real browser: the lab tour ticking in the simulator, stop and continue, the
details of a node, the timeline; and a saved log replayed with collapse and zoom."""

from __future__ import annotations

import subprocess
import sys

import pytest

from web_support import REPO, Served, browser_tests, screenshot

browser_tests()
pytest.importorskip("mujoco", reason="the tour runs in the simulator (the sim extra)")

pytestmark = [pytest.mark.slow, pytest.mark.timeout(300)]  # the simulator on a loaded machine
WAIT = 90_000  # ms: a loaded two-core machine runs the world more slowly


def node(page, path: str):
    return page.locator(f'.node[data-path="{path}"]')


def box_fill(page, path: str) -> str:
    return page.eval_on_selector(f'.node[data-path="{path}"] rect.box', "r => getComputedStyle(r).fill")


def scrub_to(page, position: int) -> None:
    page.eval_on_selector("#tl-range", "(r, v) => { r.value = v; r.dispatchEvent(new Event('input')); }", position)


def test_the_tour_ticks_in_the_browser_and_stops_and_continues(page):
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
