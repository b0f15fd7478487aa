"""The mission console in a real browser: an utterance typed starts a mission; the page shows how
it was heard, the queue, the compiled plan and what the robot says; stop and continue."""

from __future__ import annotations

import pytest

from web_support import Served, browser_tests, screenshot

browser_tests()

pytestmark = pytest.mark.slow
WAIT = 60_000


def say(page, text: str) -> None:
    page.fill("#say-input", text)
    page.press("#say-input", "Enter")


def test_an_utterance_typed_in_the_console_starts_a_mission(page):
    with Served("--mission", "--backend", "dry", "--speed", "5") as served:  # slow enough to stop a walk
        page.goto(served.url + "#console")
        page.wait_for_selector("#conn.ok")
        say(page, "Hey Stuart, go to the kitchen and wave")
        page.wait_for_selector('#queue-table tr[data-mission="1"]', timeout=WAIT)
        log = page.locator("#console-log")
        log.locator("li.heard").first.wait_for()
        assert "navigate_to_marker(target=kitchen)" in log.locator("li.heard").first.text_content()
        page.wait_for_selector('#queue-table tr[data-mission="1"][data-status="succeeded"]', timeout=WAIT)
        assert "navigate go_to marker=kitchen" in page.text_content("#plan-view")
        assert "Navigating to the kitchen" in log.text_content()
        assert page.input_value("#say-input") == ""  # sent, ready for the next one
        screenshot(page, "console")

        say(page, "Hey Stuart, go to the bathroom")
        page.wait_for_selector('#queue-table tr[data-mission="2"][data-status="running"]', timeout=WAIT)
        page.click("#btn-stop")
        page.wait_for_selector('#queue-table tr[data-mission="2"][data-status="stopped"]', timeout=WAIT)
        page.wait_for_function("document.getElementById('btn-continue').disabled === false", timeout=WAIT)
        page.click("#btn-continue")
        page.wait_for_selector('#queue-table tr[data-mission="2"][data-status="succeeded"]', timeout=WAIT)


def test_an_empty_utterance_is_refused_with_one_sentence(page):
    with Served("--mission", "--backend", "dry", "--speed", "20") as served:
        page.goto(served.url + "#console")
        page.wait_for_selector("#conn.ok")
        say(page, "   ")
        assert page.locator("#console-log li").count() == 0
        response = page.request.post(served.url + "api/say", data={"text": ""})
        assert response.status == 400 and response.json() == {"error": "type something to say"}


def test_a_mission_server_opens_on_the_console(page):
    with Served("--mission", "--backend", "dry", "--speed", "20") as served:
        page.goto(served.url)  # no #view in the address
        page.wait_for_selector("#conn.ok")
        page.wait_for_selector("#view-console.active")
        assert page.eval_on_selector("#tabs button.active", "b => b.dataset.view") == "console"
        assert not page.is_visible("#view-tree")
        say(page, "Hey Stuart, wave")  # the box to type in is there at once
        page.wait_for_selector('#queue-table tr[data-mission="1"]', timeout=WAIT)


def test_the_node_details_clear_when_a_new_mission_brings_a_new_tree(page):
    with Served("--mission", "--backend", "dry", "--speed", "20") as served:
        page.goto(served.url + "#console")
        page.wait_for_selector("#conn.ok")
        say(page, "Hey Stuart, wave")
        page.wait_for_selector('#queue-table tr[data-mission="1"][data-status="succeeded"]', timeout=WAIT)
        page.click('#tabs button[data-view="tree"]')
        trees = page.locator("#tree-select option").count()
        first = page.locator(".node").first
        path = first.get_attribute("data-path")
        first.click()
        assert path in page.text_content("#node-details")
        assert page.locator(".node.selected").count() == 1

        response = page.request.post(served.url + "api/say", data={"text": "Hey Stuart, go to the kitchen"})
        assert response.ok
        page.wait_for_function(f"document.querySelectorAll('#tree-select option').length > {trees}", timeout=WAIT)
        assert page.input_value("#tree-select") == str(trees)  # the new tree is the one shown
        assert path not in page.text_content("#node-details")
        assert page.text_content("#node-details").startswith("Click a node")
        assert page.locator(".node.selected").count() == 0


def test_serving_a_tree_the_console_talks_to_it_and_shows_the_answer_the_hold_and_the_going_on(page):
    # Slow enough that a loaded machine still says stop before the tour's ~130 simulated seconds end.
    with Served("trees/lab_tour.yaml", "--backend", "dry", "--speed", "10", "--paused") as served:
        page.goto(served.url + "#console")
        page.wait_for_selector("#conn.ok")
        assert "drone cage" in page.get_attribute("#say-input", "placeholder")
        page.click("#btn-run")
        page.wait_for_function("document.getElementById('run-state').textContent === 'busy: run'", timeout=WAIT)
        say(page, "Hey Stuart, stop")
        log = page.locator("#console-log")
        log.locator("li.hold").first.wait_for(timeout=WAIT)
        assert "the tree is held: stop said: stop" in log.locator("li.hold").first.text_content()
        page.wait_for_function("document.getElementById('run-state').textContent === 'held: stop said: stop'",
                               timeout=WAIT)
        page.wait_for_function("document.getElementById('btn-continue').disabled === false", timeout=WAIT)

        say(page, "Hey Stuart, what happens in the drone cage?")  # answered while held; it stays held
        log.locator("li.reply").first.wait_for(timeout=WAIT)
        reply = log.locator("li.reply").first.text_content()
        assert "netted cage" in reply and "(from facts)" in reply
        log.locator("li.says", has_text="netted cage").first.wait_for(timeout=WAIT)
        page.click("#btn-continue")
        log.locator("li.resume").first.wait_for(timeout=WAIT)
        log.locator("li.run", has_text="run ended: SUCCESS").wait_for(timeout=WAIT)
        assert [k.text_content() for k in log.locator("li.heard .kind").all()] == ["heard"] * 3
