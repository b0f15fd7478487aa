"""Marker edits from the map page: validated, applied to the file as it is now (edits of different
markers never overwrite each other), refused when the marker changed meanwhile, written atomically."""

from __future__ import annotations

import json
import math
import shutil
import threading
from importlib.resources import files
from pathlib import Path

import pytest

from stuart_bt.maps.markers import load_markers
from stuart_bt.web.mapfile import MapFile, default_map
from stuart_bt.web.markers import MarkerConflict, MarkerEditError, MarkerStore

LAB_MARKERS = Path(str(files("stuart_bt.sim").joinpath("maps/lab_markers.json")))


@pytest.fixture
def store(tmp_path) -> MarkerStore:
    path = tmp_path / "markers.json"
    shutil.copy(LAB_MARKERS, path)
    return MarkerStore(path, MapFile.load(default_map()).bounds())


def test_an_added_marker_is_in_the_file_and_loads_as_a_marker(store):
    doc = store.edit({"op": "add", "name": "coffee", "x": 2.0, "y": 1.0, "yaw": 4.0, "display_name": "Coffee"})
    assert doc["markers"]["coffee"] == {"x": 2.0, "y": 1.0, "yaw": round(4.0 - 2 * math.pi, 4),
                                        "display_name": "Coffee"}
    marker = load_markers(store.path)["coffee"]
    assert (marker.x, marker.y, marker.label) == (2.0, 1.0, "Coffee")


def test_edits_of_different_markers_from_stale_pages_are_both_kept(store):
    seen = store.load()["markers"]  # two pages loaded the same version
    store.edit({"op": "update", "name": "kitchen", "x": 3.4, "expect": seen["kitchen"]})
    store.edit({"op": "update", "name": "bathroom", "y": 3.1, "expect": seen["bathroom"]})
    markers = store.load()["markers"]
    assert markers["kitchen"]["x"] == 3.4 and markers["bathroom"]["y"] == 3.1


def test_an_edit_of_a_marker_changed_meanwhile_is_refused_with_the_current_file(store):
    seen = store.load()["markers"]["kitchen"]
    store.edit({"op": "update", "name": "kitchen", "x": 3.3, "expect": seen})
    with pytest.raises(MarkerConflict) as e:
        store.edit({"op": "delete", "name": "kitchen", "expect": seen})
    assert e.value.current["markers"]["kitchen"]["x"] == 3.3
    assert "kitchen" in load_markers(store.path)


def test_concurrent_adds_from_many_threads_lose_nothing(store):
    def add(i: int) -> None:
        store.edit({"op": "add", "name": f"spot_{i}", "x": 1.0 + i * 0.05, "y": 0.0})

    threads = [threading.Thread(target=add, args=(i,)) for i in range(12)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert {f"spot_{i}" for i in range(12)} <= set(load_markers(store.path))
    assert not list(store.path.parent.glob(".markers.json.*"))  # no temporary file left


@pytest.mark.parametrize("request_, message", [
    ({"op": "add", "name": "Kitchen 2", "x": 1, "y": 1}, "must be lower-case letters"),
    ({"op": "add", "name": "kitchen", "x": 1, "y": 1}, "exists already"),
    ({"op": "add", "name": "far", "x": 40.0, "y": 1}, "outside the map"),
    ({"op": "add", "name": "table", "x": 4.2, "y": 1.5}, "not free space"),  # the kitchen table
    ({"op": "add", "name": "beyond", "x": -1.8, "y": 0.0}, "not free space"),  # outside the walls
    ({"op": "add", "name": "nan", "x": float("nan"), "y": 0.0}, "finite number"),
    ({"op": "update", "name": "kitchn", "x": 1}, "did you mean 'kitchen'"),
    ({"op": "rename", "name": "kitchen", "new_name": "bathroom"}, "exists already"),
    ({"op": "updat", "name": "kitchen"}, "did you mean 'update'"),
])
def test_a_bad_edit_says_why_and_changes_nothing(store, request_, message):
    before = store.path.read_bytes()
    with pytest.raises(MarkerEditError, match=message):
        store.edit(request_)
    assert store.path.read_bytes() == before


def test_rename_keeps_the_values(store):
    before = json.loads(store.path.read_text())["markers"]["kitchen"]
    doc = store.edit({"op": "rename", "name": "kitchen", "new_name": "galley"})
    assert "kitchen" not in doc["markers"] and doc["markers"]["galley"] == before
