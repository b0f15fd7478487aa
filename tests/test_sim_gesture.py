"""Gestures on the simulated arms: every library gesture moves the joints and ends where it
should; recorded keyframe files play; a file past a joint limit is refused before any motion.

Every library gesture plays in one sim run (held gestures each followed by "release arm"), and
the parametrised tests below read that one run's world timeline.
"""

from __future__ import annotations

import json
from itertools import pairwise
from pathlib import Path

import pytest

from stuart_bt.core import gestures
from stuart_bt.skills.gesture.keyframes import NEUTRAL, end_pose
from stuart_bt.testing import RunResult, is_arm_joint, run_tree

pytestmark = pytest.mark.sim

DATA = Path(__file__).parent / "data" / "sim"
PLAYED = [g.name for g in gestures.LIBRARY.values() if g.name != "release arm"]
MOVES = 0.2  # rad: some arm joint must move at least this far during a gesture
AT_REST = 0.01  # rad: how close the arms end to the expected pose


def slug(name: str) -> str:
    return name.replace(" ", "_").replace("-", "_")


def every_gesture_tree() -> str:
    """Each gesture by name, and after a held one, "release arm" (node release_after_<name>)."""
    lines = ["root:", "  sequence:", "    name: library", "    children:"]
    for name in PLAYED:
        lines.append(f'      - gesture: {{name: {slug(name)}, sequence: ["{name}"]}}')
        if gestures.LIBRARY[name].holds:
            lines.append(f'      - gesture: {{name: release_after_{slug(name)}, sequence: ["release arm"]}}')
    return "\n".join(lines) + "\n"


@pytest.fixture(scope="module")
def library_run() -> RunResult:
    result = run_tree(text=every_gesture_tree(), backend="sim")
    result.assert_success()
    return result


def span(result: RunResult, node: str) -> dict:
    (played,) = [g for g in result.report["gestures"] if g["path"] == f"library/{node}"]
    return played


def arm_joints(state: dict) -> dict[str, float]:
    return {k: v for k, v in state["joints"].items() if is_arm_joint(k)}


def largest_difference(a: dict[str, float], b: dict[str, float]) -> tuple[str, float]:
    name = max(b, key=lambda k: abs(a[k] - b[k]))
    return name, abs(a[name] - b[name])


@pytest.mark.parametrize("name", PLAYED)
def test_library_gesture_moves_the_sim_arms_while_it_plays(library_run: RunResult, name: str):
    played = span(library_run, slug(name))
    before = arm_joints(library_run.state_at(played["start"]))
    during = library_run.samples(since=played["start"], until=played["end"])
    assert len(during) > 10, f"only {len(during)} world samples while {name!r} played"
    joint, moved = max((largest_difference(arm_joints(s), before) for s in during), key=lambda jm: jm[1])
    assert moved >= MOVES, f"{name!r}: the arms moved at most {moved:.3f} rad ({joint})"


@pytest.mark.parametrize("name", PLAYED)
def test_library_gesture_ends_in_its_held_pose_or_at_neutral(library_run: RunResult, name: str):
    played = span(library_run, slug(name))
    expected = end_pose(name) if gestures.LIBRARY[name].holds else NEUTRAL
    after = arm_joints(library_run.state_at(played["end"]))
    joint, error = largest_difference(after, expected)
    where = "its held pose" if gestures.LIBRARY[name].holds else "neutral"
    assert error <= AT_REST, f"{name!r} ended {error:.3f} rad from {where} ({joint} = {after[joint]:.3f})"


@pytest.mark.parametrize("name", [n for n in PLAYED if gestures.LIBRARY[n].holds])
def test_release_arm_after_a_held_gesture_returns_to_neutral(library_run: RunResult, name: str):
    released = span(library_run, f"release_after_{slug(name)}")
    held = arm_joints(library_run.state_at(released["start"]))
    assert largest_difference(held, NEUTRAL)[1] > MOVES  # it really started from the held pose
    joint, error = largest_difference(arm_joints(library_run.state_at(released["end"])), NEUTRAL)
    assert error <= AT_REST, f"release after {name!r} ended {error:.3f} rad from neutral ({joint})"


def closest_sample(samples: list[dict], joints: dict[str, float]) -> tuple[dict, float]:
    """The sample nearest to a keyframe's joint angles, and its largest joint error."""
    def error(s: dict) -> float:
        return max(abs(s["joints"][j] - angle) for j, angle in joints.items())
    best = min(samples, key=error)
    return best, error(best)


def test_recorded_gesture_file_plays_through_its_keyframes(stuart_sim):
    frames = json.loads((DATA / "gestures" / "point_forward.json").read_text())["keyframes"]

    result = stuart_sim(DATA / "recorded_gesture.yaml")

    result.assert_success()
    result.assert_gestured("recorded")
    played = result.report["gestures"][0]
    samples, passed_at = result.samples(since=played["start"], until=played["end"]), []
    for frame in frames:  # the arms passed through every keyframe, in order and on time
        sample, error = closest_sample([s for s in samples if not passed_at or s["t"] > passed_at[-1]], frame["joints"])
        assert error <= 0.05, f"the arms came no closer than {error:.3f} rad to the keyframe at t={frame['t']}"
        passed_at.append(sample["t"])
    keyframe_gaps = [f1["t"] - f0["t"] for f0, f1 in pairwise(frames)]
    assert [b - a for a, b in pairwise(passed_at)] == pytest.approx(keyframe_gaps, abs=0.1)
    final = result.final_world["joints"]
    assert {j: round(final[j], 3) for j in frames[-1]["joints"]} == frames[-1]["joints"]


def test_recorded_gesture_past_a_joint_limit_is_refused_before_any_motion(stuart_sim):
    result = stuart_sim(DATA / "gesture_beyond_limit.yaml")

    assert result.status == "FAILURE"
    reason = result.assert_failed("bad_elbow", "bad_request")
    assert "keyframe 1: right_elbow_joint = 2.5000 rad is outside its limits [-1.0472, 2.0944]" in reason
    result.assert_arms_did_not_move()
    assert result.report["gestures"] == []
