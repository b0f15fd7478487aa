"""The map in a real browser: a marker added (click, drag for the heading) is saved to the marker
file and survives a reload; moved, renamed, walked to and deleted; click to walk to a point."""

from __future__ import annotations

import json
import math
import shutil
from importlib.resources import files
from pathlib import Path

import pytest

from web_support import Served, browser_tests, screenshot

browser_tests()

pytestmark = pytest.mark.slow
WAIT = 60_000


@pytest.fixture
def markers(tmp_path) -> Path:
    path = tmp_path / "markers.json"
    shutil.copy(Path(str(files("stuart_bt.sim").joinpath("maps/lab_markers.json"))), path)
    return path


def screen(page, x: float, y: float) -> tuple[float, float]:
    """Where map point (x, y) is on the page."""
    box = page.locator("#map-canvas").bounding_box()
    sx, sy = page.evaluate("([x, y]) => stuart.map.toScreen(x, y)", [x, y])
    return box["x"] + sx, box["y"] + sy


def drag(page, start: tuple[float, float], end: tuple[float, float]) -> None:
    page.mouse.move(*start)
    page.mouse.down()
    page.mouse.move((start[0] + end[0]) / 2, (start[1] + end[1]) / 2)
    page.mouse.move(*end)
    page.mouse.up()


def on_disk(path: Path) -> dict:
    return json.loads(path.read_text())["markers"]


def test_a_marker_added_on_the_map_survives_a_reload_and_can_be_walked_to(page, markers):
    with Served("trees/lab_tour.yaml", "--paused", "--speed", "20", "--markers", str(markers)) as served:
        page.goto(served.url + "#map")
        page.wait_for_selector('#marker-table tr[data-marker="kitchen"]')
        answers = iter(["coffee_corner", "Coffee corner"])
        page.on("dialog", lambda d: d.accept(next(answers, "")) if d.type == "prompt" else d.accept())

        page.check('input[name=map-mode][value=add]')
        at = screen(page, 2.0, 1.0)
        drag(page, at, (at[0] + 40, at[1] - 40))  # up and right on the screen: heading 45 degrees
        page.wait_for_selector('#marker-table tr[data-marker="coffee_corner"]')
        saved = on_disk(markers)["coffee_corner"]
        assert math.hypot(saved["x"] - 2.0, saved["y"] - 1.0) < 0.05
        assert saved["yaw"] == pytest.approx(math.pi / 4, abs=0.05) and saved["display_name"] == "Coffee corner"

        page.reload()
        page.wait_for_selector('#marker-table tr[data-marker="coffee_corner"]')

        page.check('input[name=map-mode][value=move]')
        drag(page, screen(page, 2.0, 1.0), screen(page, 2.5, 1.0))
        page.wait_for_function("stuart.map.markers.coffee_corner && stuart.map.markers.coffee_corner.x > 2.3")
        assert on_disk(markers)["coffee_corner"]["x"] == pytest.approx(2.5, abs=0.05)

        row = page.locator('#marker-table tr[data-marker="coffee_corner"]')
        row.locator('input[aria-label="name"]').fill("coffee")
        row.locator("text=Save").click()
        page.wait_for_selector('#marker-table tr[data-marker="coffee"]')
        assert "coffee" in on_disk(markers) and "coffee_corner" not in on_disk(markers)

        page.locator('#marker-table tr[data-marker="coffee"]').locator("text=Go").click()
        page.wait_for_function("stuart.map.pose && Math.hypot(stuart.map.pose.x - 2.5, stuart.map.pose.y - 1.0) < 0.2",
                               timeout=WAIT)
        page.wait_for_function("document.body.dataset.busy === 'no'", timeout=WAIT)

        page.check('input[name=map-mode][value=walk]')
        page.mouse.click(*screen(page, 1.0, -1.0))
        page.wait_for_function("stuart.map.pose && Math.hypot(stuart.map.pose.x - 1.0, stuart.map.pose.y + 1.0) < 0.2",
                               timeout=WAIT)
        page.wait_for_function("document.body.dataset.busy === 'no'", timeout=WAIT)
        assert page.evaluate("document.getElementById('robot-pose').textContent.startsWith("
                             "`x ${stuart.map.pose.x.toFixed(2)} m, y ${stuart.map.pose.y.toFixed(2)} m`)")
        screenshot(page, "map")

        page.locator('#marker-table tr[data-marker="coffee"]').locator("text=✕").click()
        page.wait_for_function("!document.querySelector('#marker-table tr[data-marker=\"coffee\"]')")
        assert "coffee" not in on_disk(markers) and "kitchen" in on_disk(markers)


def test_a_marker_on_an_obstacle_is_refused_and_nothing_is_written(page, markers):
    before = markers.read_bytes()
    with Served("trees/greet.yaml", "--paused", "--markers", str(markers)) as served:
        page.goto(served.url + "#map")
        page.wait_for_selector('#marker-table tr[data-marker="kitchen"]')
        page.on("dialog", lambda d: d.accept("on_the_table"))
        page.check('input[name=map-mode][value=add]')
        page.mouse.click(*screen(page, 4.2, 1.5))  # the kitchen table
        page.wait_for_selector("#toast.error")
        assert "not free space" in page.text_content("#toast")
    assert markers.read_bytes() == before


def test_the_name_column_fits_the_longest_marker_name(page, markers):
    with Served("trees/greet.yaml", "--paused", "--markers", str(markers)) as served:
        longest = "wm" * 20  # the widest name the rule allows: 40 characters, the widest letters
        answer = page.request.post(served.url + "api/markers", data={"op": "add", "name": longest, "x": 2.0, "y": 1.0,
                                                                     "yaw": 0.0, "display_name": "By the WWW Museum"})
        assert answer.ok, answer.text()
        page.goto(served.url + "#map")
        page.wait_for_selector(f'#marker-table tr[data-marker="{longest}"]')
        columns = '#marker-table input[aria-label="name"], #marker-table input[aria-label="label"]'
        cells = page.eval_on_selector_all(columns, "is => is.map(i => [i.value, i.scrollWidth, i.clientWidth])")
        assert len(cells) == 2 * len(on_disk(markers))
        clipped = [(text, needs, has) for text, needs, has in cells if needs > has]
        assert clipped == []


def test_a_walk_or_go_that_fails_shows_a_toast_with_the_reason(page, markers, tmp_path):
    pytest.importorskip("mujoco", reason="only the simulator's planner finds no way there (the sim extra)")
    tree = tmp_path / "walk.yaml"
    tree.write_text(f"markers: {markers}\nroot:\n  navigate: kitchen\n")
    with Served(str(tree), "--paused", "--backend", "sim", "--markers", str(markers)) as served:
        # free on the map, but closer to the wall than the robot is wide: nowhere to stand
        answer = page.request.post(served.url + "api/markers", data={
            "op": "add", "name": "by_the_wall", "x": -1.42, "y": 0.375, "yaw": 0.0})
        assert answer.ok, answer.text()
        page.goto(served.url + "#map")
        page.wait_for_selector('#marker-table tr[data-marker="by_the_wall"]')

        page.check('input[name=map-mode][value=walk]')
        page.mouse.click(*screen(page, 4.2, 1.5))  # the kitchen table: accepted, then no way there
        page.wait_for_selector("#toast.error", timeout=WAIT)
        toast = page.text_content("#toast")
        assert toast.startswith("walk to (4.20, 1.50) failed: unreachable") and "inside an obstacle" in toast
        page.wait_for_function("document.body.dataset.busy === 'no'", timeout=WAIT)

        page.locator('#marker-table tr[data-marker="by_the_wall"]').locator("text=Go").click()
        page.wait_for_function("document.getElementById('toast').textContent.startsWith('go to by_the_wall failed')",
                               timeout=WAIT)
        assert "unreachable" in page.text_content("#toast") and page.locator("#toast.error").count() == 1
        assert page.locator('.node[data-path="go_to"][data-status="FAILURE"]').count() == 1


def test_a_go_the_mission_console_cannot_take_shows_what_the_robot_answered(page, markers):
    with Served("--mission", "--backend", "dry", "--speed", "20", "--markers", str(markers)) as served:
        answer = page.request.post(served.url + "api/markers", data={
            "op": "add", "name": "coffee_corner", "x": 2.0, "y": 1.0, "yaw": 0.0})
        assert answer.ok, answer.text()
        page.goto(served.url + "#map")
        page.locator('#marker-table tr[data-marker="coffee_corner"]').locator("text=Go").click()
        page.wait_for_selector("#toast.error", timeout=WAIT)
        assert "coffee corner" in page.text_content("#toast")
