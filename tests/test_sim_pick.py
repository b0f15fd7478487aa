"""Picking on the simulated lab, judged by the physics: the bottle must rise with the hand and
come down when released; unreachable picks and a pick while holding refuse before the arm
moves; both IK solvers grasp; the confirmation gate holds the arm until confirmed.

Lab (docs/sim.md): 'kitchen' (3.5, 1.5) faces the kitchen table; the bottle stands on it about
0.5 m ahead, on the right arm's side: out of reach until Stuart steps up 0.18 m.
"""

from __future__ import annotations

import pytest

from stuart_bt.testing import LiveRun, at, when

WORKBENCH_X, WORKBENCH_Y, WORKBENCH_TOP = (0.2, 1.8), (-3.51, -2.81), 0.85  # the bench's outline and top (m)
STEP_UP_AND_PICK = """
root:
  sequence:
    - navigate: {name: step_up, dx: 0.18}
    - pick: {name: grab, object: bottle, arm: right}
"""


def test_fetch_bottle_lifts_the_bottle_with_the_hand_and_puts_it_down_at_the_workbench(stuart_sim):
    result = stuart_sim("trees/fetch_bottle.yaml")

    result.assert_success()
    result.assert_visited("kitchen", "workbench")
    result.assert_object_raised("bottle", by=0.05)  # world heights while a hand held it
    result.assert_holding(None)
    bottle = result.object_position("bottle")
    assert WORKBENCH_X[0] < bottle["x"] < WORKBENCH_X[1] and WORKBENCH_Y[0] < bottle["y"] < WORKBENCH_Y[1], bottle
    assert bottle["z"] > WORKBENCH_TOP, f"the bottle is below the bench top: {bottle}"


@pytest.mark.parametrize("label", ["bottle", "cup"], ids=["without_stepping_up", "across_the_room"])
def test_unreachable_pick_fails_before_any_arm_joint_moves(stuart_sim, label: str):
    result = stuart_sim(text=f"root: {{pick: {{name: grab, object: {label}, arm: right}}}}", start="kitchen")

    assert result.status == "FAILURE"
    assert "beyond the right arm's reach" in result.assert_failed("grab", "unreachable")
    result.assert_arms_did_not_move()
    result.assert_holding(None)


@pytest.mark.parametrize("solver", ["pin", "placo"])
def test_both_ik_solvers_grasp_and_lift_the_bottle(stuart_sim, solver: str):
    result = stuart_sim(text=STEP_UP_AND_PICK, start="kitchen", daemon_options={"pick": {"solver": solver}})

    result.assert_success()
    result.assert_object_raised("bottle", by=0.05)
    result.assert_holding("bottle")
    assert result.final_world["held"] == {"left": None, "right": "bottle"}


def test_release_puts_the_bottle_down_and_empties_the_hand(stuart_sim):
    result = stuart_sim(text=STEP_UP_AND_PICK + "    - release: {name: put_down}\n", start="kitchen")

    result.assert_success()
    lifted = result.assert_object_raised("bottle", by=0.05)
    released_at = result.commands("release")[0]["t"]
    held_z = result.state_at(released_at)["objects"]["bottle"]["z"]
    start_z = result.initial_world["objects"]["bottle"]["z"]
    final_z = result.object_position("bottle")["z"]
    assert final_z < held_z - 0.05, f"the bottle stayed up: z {held_z:.3f} -> {final_z:.3f} (lifted {lifted:.3f})"
    assert final_z == pytest.approx(start_z, abs=0.01)  # standing on the table again
    result.assert_holding(None)


def test_pick_while_the_tree_holds_something_is_refused_without_a_command(stuart_sim):
    result = stuart_sim(text=STEP_UP_AND_PICK + "    - pick: {name: again, object: apple}\n", start="kitchen")

    assert result.status == "FAILURE"
    assert "already holding 'bottle'" in result.assert_failed("again")
    assert [c["args"]["object"] for c in result.commands("pick")] == ["bottle"]
    result.assert_holding("bottle")


def apple_slipped_into_the_right_hand(run: LiveRun) -> None:
    """The world's hand holds something the tree does not know about."""
    x, y, z = run.world.latest["hand_points"]["right"]
    run.world.move_object("apple", x, y, z)
    run.world.call("hand", side="right", closed=True)


def test_pick_while_a_hand_holds_something_fails_with_already_holding(stuart_sim):
    result = stuart_sim(text="root: {sequence: [{wait: 1}, {pick: {name: grab, object: bottle}}]}", start="kitchen",
                        on_tick=at(0.0, apple_slipped_into_the_right_hand))

    assert result.status == "FAILURE"
    assert "'apple'" in result.assert_failed("grab", "already_holding")
    result.assert_arms_did_not_move(since=result.commands("pick")[0]["t"])
    assert result.final_world["held"]["right"] == "apple"


def awaiting_confirmation(run: LiveRun) -> bool:
    return any(r.cmd == "pick" and (r.accepted_data or {}).get("awaiting_confirm")
               for r in run.daemon("pick").in_flight)


def test_confirmation_gate_holds_the_arm_until_confirm_reaches_the_pick_daemon(stuart_sim):
    confirm = when(awaiting_confirmation, lambda run: run.daemon("pick").request("confirm", {}), held_for=2.0)

    result = stuart_sim(text=STEP_UP_AND_PICK, start="kitchen", on_tick=confirm,
                        daemon_options={"pick": {"confirm": True}})

    result.assert_success()
    assert confirm.fired, "the pick never waited for confirmation"
    pick_sent = result.commands("pick")[0]["t"]
    result.assert_arms_did_not_move(since=pick_sent, until=confirm.fired_at)
    (picked,) = result.report["picks"]
    assert picked["end"] > confirm.fired_at + 2.0  # the grasp ran after the confirmation
    result.assert_object_raised("bottle", by=0.05)
