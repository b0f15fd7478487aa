"""The gesture recorder in a real browser, on the simulator: a slider moves the arm live,
keyframes are added, re-timed and reordered, saved as a gesture file the gesture skill loads,
played by the robot, and loaded back."""

from __future__ import annotations

import time

import pytest

from web_support import Served, browser_tests, screenshot

browser_tests()
pytest.importorskip("mujoco", reason="the pose is applied in the simulator (the sim extra)")

from stuart_bt.skills.gesture.keyframes import load_gesture_file  # noqa: E402

pytestmark = [pytest.mark.slow, pytest.mark.timeout(300)]  # the simulator on a loaded machine
WAIT = 120_000  # ms: the world runs slower on a loaded two-core machine
JOINT = "right_shoulder_pitch_joint"


def slide(page, joint: str, value: float) -> None:
    page.eval_on_selector(f'input[data-joint="{joint}"]',
                          "(s, v) => { s.value = v; s.dispatchEvent(new Event('input')); }", value)


def world_joint(page, url: str, joint: str) -> float:
    return page.request.get(url + "api/pose").json()["joints"][joint]


def wait_for_joint(page, url: str, joint: str, value: float, timeout: float = 120.0) -> float:
    end = time.monotonic() + timeout
    now = world_joint(page, url, joint)
    while abs(now - value) > 0.02 and time.monotonic() < end:
        time.sleep(0.1)
        now = world_joint(page, url, joint)
    return now


def test_a_recorded_gesture_saves_plays_and_loads_again(page, tmp_path):
    folder = tmp_path / "gestures"
    with Served("trees/greet.yaml", "--backend", "sim", "--speed", "2", "--paused",
                "--gestures", str(folder)) as served:
        page.goto(served.url + "#gestures")
        page.wait_for_selector(f'input[data-joint="{JOINT}"]')
        assert "follows the sliders" in page.text_content("#g-live")

        slide(page, JOINT, -1.2)  # the arm follows the slider in the sim
        assert wait_for_joint(page, served.url, JOINT, -1.2) == pytest.approx(-1.2, abs=0.02)
        page.click("#kf-add")
        slide(page, JOINT, -0.4)
        page.click("#kf-add")
        page.fill('#kf-table tr[data-frame="1"] input', "1.5")
        page.dispatch_event('#kf-table tr[data-frame="1"] input', "change")
        page.click('#kf-table tr[data-frame="0"] button[title="later"]')  # swap the two poses
        page.fill("#g-name", "big_wave")
        screenshot(page, "gestures")

        page.click("#g-play")  # saves, then the robot plays the file
        page.wait_for_selector('.node[data-path="play"][data-status="SUCCESS"]', state="attached", timeout=WAIT)
        gesture = load_gesture_file(folder / "big_wave.json")
        assert gesture.name == "big_wave"
        assert [k.t for k in gesture.keyframes] == [1.0, 1.5]
        slider_step = 0.01
        assert [k.joints[JOINT] for k in gesture.keyframes] == [pytest.approx(-0.4, abs=slider_step),
                                                                 pytest.approx(-1.2, abs=slider_step)]
        assert wait_for_joint(page, served.url, JOINT, -1.2) == pytest.approx(-1.2, abs=0.02)  # the last keyframe

        page.reload()
        page.wait_for_selector('#g-load-select option[value="big_wave"]', state="attached")
        page.click("#g-load")
        page.wait_for_selector('#kf-table tr[data-frame="1"]')
        assert page.input_value("#g-name") == "big_wave"
        assert page.input_value('#kf-table tr[data-frame="1"] input') == "1.5"


def test_a_bad_gesture_is_refused_with_its_problems_and_not_written(page, tmp_path):
    folder = tmp_path / "gestures"
    with Served("trees/greet.yaml", "--paused", "--gestures", str(folder)) as served:
        page.goto(served.url + "#gestures")
        page.wait_for_selector(f'input[data-joint="{JOINT}"]')
        assert "Recording only" in page.text_content("#g-live")  # dry: nothing to move
        answer = page.request.post(served.url + "api/gestures/big_wave",
                                   data={"keyframes": [{"t": 1.0, "joints": {JOINT: 9.0, "left_elbo_joint": 0.1}}]})
        assert answer.status == 400
        problems = answer.json()["problems"]
        assert any("outside its limits" in p for p in problems)
        assert any("did you mean 'left_elbow_joint'" in p for p in problems)
        assert not (folder / "big_wave.json").exists()
        assert page.request.post(served.url + "api/gestures/Big Wave", data={"keyframes": []}).status == 400
