"""t05: test a tree with pytest. ``run_tree`` loads a tree, runs it on the daemons (here the dry
backend; ``backend="sim"`` or the ``stuart_sim`` fixture for the MuJoCo world) and returns the
result to assert on: status, events, the report, where the robot went.

    pytest examples/t05_test_your_tree
"""

from pathlib import Path

from stuart_bt.testing import run_tree

HERE = Path(__file__).parent
FIRST_TREE = HERE.parent / "t01_first_tree" / "tree.yaml"


def test_the_first_tree_says_hello_and_ends_in_the_kitchen():
    result = run_tree(FIRST_TREE)
    assert result.status == "SUCCESS"
    assert [u["text"] for u in result.utterances()] == ["Hello! I'm Stuart. Follow me to the kitchen."]
    assert [a["marker"] for a in result.arrivals()] == ["kitchen"]
    assert result.commands("play")  # the wave went to the gesture daemon


def test_a_fallback_walks_to_the_dock_when_the_battery_is_low():
    tree = """
    markers: ../../sim/maps/lab_markers.json
    blackboard: {battery: 10}
    root:
      selector:
        - sequence:
            - condition: "battery < 20"
            - navigate: charging_dock
        - speak: "All good."
    """
    result = run_tree(text=tree.replace("../../sim", str(HERE.parents[1] / "sim")))
    assert result.status == "SUCCESS"
    assert [a["marker"] for a in result.arrivals()] == ["charging_dock"]
    assert result.commands("say") == []  # the second choice never ran
