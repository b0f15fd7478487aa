"""Resolution: spoken targets -> the lab's markers and object labels, or a reason and the
closest names, so the robot can say what it did not understand before anything moves."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from stuart_bt.language.intents import TaskIntent
from stuart_bt.language.parse import parse
from stuart_bt.language.resolve import DEFAULT_OBJECTS, Resolver, load_object_labels, normalise

REPO = Path(__file__).resolve().parents[1]
MARKERS = REPO / "sim" / "maps" / "lab_markers.json"


@pytest.fixture(scope="module")
def lab() -> Resolver:
    return Resolver.from_files(MARKERS, REPO / "skills" / "objects.json")


@pytest.mark.parametrize("spoken,name", [
    ("kitchen", "kitchen"), ("the bathroom", "bathroom"), ("Kitchen", "kitchen"), ("kitchen area", "kitchen"),
    ("the kitchen table", "kitchen"), ("station three", "station_3"), ("station 3", "station_3"),
    ("the third station", "station_3"), ("station number three", "station_3"), ("station_3", "station_3"),
    ("station3", "station_3"), ("the charging dock", "charging_dock"), ("your dock", "charging_dock"),
    ("charger", "charging_dock"), ("home", "charging_dock"), ("drone cage", "station_3"),
    ("the 3d printers", "station_2"), ("3D printer", "station_2"), ("printers", "station_2"),
    ("robot arms", "station_1"), ("reading room", "station_6"), ("electronics bench", "station_4"),
    ("the humanoid corner", "station_5"), ("toilet", "bathroom"), ("front door", "entrance"),
    ("work bench", "workbench"), ("bathrom", "bathroom"), ("kichen", "kitchen"),
])
def test_markers(lab: Resolver, spoken: str, name: str) -> None:
    r = lab.marker(spoken)
    assert r.ok and r.name == name, r
    assert r.say() == ""


@pytest.mark.parametrize("spoken,name", [
    ("the 3D printing station", "station_2"), ("the printing room", "station_2"), ("the arms station", "station_1"),
    ("the drone station", "station_3"), ("the reading station", "station_6"),
])
def test_a_station_named_by_another_form_of_its_words_is_that_station(lab: Resolver, spoken: str, name: str) -> None:
    assert lab.marker(spoken).name == name
    assert lab.marker("the station").name is None  # which one? still asked


def test_unknown_place_says_so_with_the_closest_names(lab: Resolver) -> None:
    r = lab.marker("the garage")
    assert not r.ok and r.how == "unknown" and r.candidates
    assert r.say().startswith("I don't know where the garage is.")
    assert all(c in lab.markers for c in r.candidates)


def test_a_number_that_does_not_exist_is_unknown_not_a_misspelling(lab: Resolver) -> None:
    r = lab.marker("station seven")
    assert not r.ok and r.how == "unknown"


def test_ambiguous_place_lists_the_candidates(lab: Resolver) -> None:
    r = lab.marker("the station")
    assert r.how == "ambiguous" and r.candidates == tuple(f"station_{i}" for i in range(1, 7))
    assert r.say().startswith("Which station do you mean:") and "Drone cage (station 3)" in r.say()


def test_an_object_is_not_a_place(lab: Resolver) -> None:
    r = lab.marker("the bottle")
    assert not r.ok and "object" in r.reason


def test_going_to_an_object_walks_up_to_it_and_a_place_wins_over_an_object(lab: Resolver) -> None:
    to_mug = lab.resolve(TaskIntent("navigate_to_marker", "the mug"))
    assert to_mug is not None and (to_mug.kind, to_mug.name) == ("object", "cup")
    to_kitchen = lab.resolve(TaskIntent("navigate_to_marker", "the kitchen"))
    assert to_kitchen is not None and (to_kitchen.kind, to_kitchen.name) == ("marker", "kitchen")
    nowhere = lab.resolve(TaskIntent("navigate_to_marker", "the garage"))
    assert nowhere is not None and nowhere.kind == "marker" and not nowhere.ok  # the place error is what is said


@pytest.mark.parametrize("spoken,label", [
    ("bottle", "bottle"), ("the red cup", "cup"), ("cups", "cup"), ("a mug", "cup"), ("water bottle", "bottle"),
    ("screw driver", "screwdriver"), ("botle", "bottle"), ("the green apple", "apple"), ("book", "book"),
])
def test_objects(lab: Resolver, spoken: str, label: str) -> None:
    r = lab.object(spoken)
    assert r.ok and r.name == label, r


def test_unknown_object(lab: Resolver) -> None:
    r = lab.object("banana")
    assert not r.ok and r.say().startswith("I don't know any banana.")
    assert lab.object("kitchen").reason == "'kitchen' is a place, not an object"


def test_people_can_be_found_but_not_picked_up(lab: Resolver) -> None:
    assert lab.resolve(TaskIntent("find", "someone")).name == "person"  # type: ignore[union-attr]
    assert not lab.resolve(TaskIntent("pick_up", "someone")).ok  # type: ignore[union-attr]


def test_find_falls_back_to_places(lab: Resolver) -> None:
    r = lab.resolve(TaskIntent("find", "the drone cage"))
    assert r is not None and r.kind == "marker" and r.name == "station_3"


def test_gestures(lab: Resolver) -> None:
    assert lab.gesture("wave").name == "high wave"
    assert lab.gesture("shake hand").name == "shake hand"
    assert not lab.gesture("dance").ok


def test_resolve_every_intent_of_a_parse(lab: Resolver) -> None:
    result = parse("Hey Stuart, go to the kitchen area, pick up the mug, turn left and wave")
    got = lab.resolve_all(result.intents)
    assert [r.name if r else None for r in got] == ["kitchen", "cup", None, "high wave"]


def test_other_maps(tmp_path: Path) -> None:
    doc = {"markers": {"lobby": {"x": 0, "y": 0}, "lab_2": {"x": 1, "y": 1, "display_name": "Robotics lab"}}}
    path = tmp_path / "m.json"
    path.write_text(json.dumps(doc))
    r = Resolver.from_files(path)
    assert r.marker("lab two").name == "lab_2" and r.marker("the robotics lab").name == "lab_2"
    assert r.marker("the lobby area").name == "lobby"
    assert not r.marker("kitchen").ok
    assert Resolver(["kitchen"]).marker("the kitchen").name == "kitchen"
    assert Resolver().marker("kitchen").reason == "no marker file loaded"


def test_object_label_files(tmp_path: Path) -> None:
    assert load_object_labels(REPO / "skills" / "objects.json") == ("bottle", "apple", "cup", "screwdriver", "book")
    assert set(load_object_labels(REPO / "sim" / "scenes" / "lab.xml")) == {"bottle", "apple", "cup", "book"}
    assert set(load_object_labels(REPO / "sim" / "scenes" / "lab.xml")) <= set(DEFAULT_OBJECTS)
    (tmp_path / "l.json").write_text('["mug", "pen"]')
    assert load_object_labels(tmp_path / "l.json") == ("mug", "pen")
    (tmp_path / "bad.json").write_text("{")
    with pytest.raises(ValueError):
        load_object_labels(tmp_path / "bad.json")


def test_normalise() -> None:
    assert normalise("The Third Station") == ("3", "station")
    assert normalise("your charging_dock") == ("charging", "dock")
