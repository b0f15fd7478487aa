"""The occupancy grid made from the scene, the committed map files, and the scene's layout rules."""

from __future__ import annotations

import json
from pathlib import Path

import mujoco
import numpy as np
import pytest

from stuart_bt.maps.files import read_map, write_map
from stuart_bt.maps.grid import OccupancyGrid
from stuart_bt.maps.markers import load_markers
from stuart_bt.maps.picture import draw_map_png
from stuart_bt.sim.world.occupancy import clearance, grid_from_model, scene_grid, static_footprints
from stuart_bt.sim.world.scene import MAPS_DIR, build_scene, default_robot_path, scene_path

STANDIN = Path(__file__).parent / "data" / "standin_robot.xml"
ROBOT = None if default_robot_path().is_file() else STANDIN
MARKERS = load_markers(MAPS_DIR / "lab_markers.json")


@pytest.fixture(scope="module")
def grid() -> OccupancyGrid:
    return scene_grid("lab")


@pytest.mark.parametrize("x, y, what", [
    (-1.55, 0.0, "west wall"), (8.55, 1.0, "east wall"), (3.5, -3.65, "south wall"), (3.5, 4.45, "north wall"),
    (6.0, 3.0, "bathroom wall"), (7.9, 1.9, "bathroom south wall"),
    (4.31, 1.5, "kitchen table"), (1.0, -3.16, "workbench"), (3.0, -1.75, "printer bench"),
    (6.15, -1.55, "drone cage"), (1.5, 1.3, "arm pedestal"), (1.25, 2.5, "bookshelf"),
])
def test_walls_and_furniture_are_occupied(grid, x, y, what):
    assert grid.is_occupied(x, y), what
    assert not grid.is_free(x, y), what


@pytest.mark.parametrize("name", sorted(MARKERS))
def test_every_marker_is_free_with_clearance(grid, name):
    marker = MARKERS[name]
    assert grid.is_free(marker.x, marker.y), name
    footprints = static_footprints(mujoco.MjModel.from_xml_path(str(scene_path("lab"))))
    assert clearance(footprints, marker.x, marker.y) >= 0.4 - 1e-9, name


def test_doorway_is_open_and_the_bathroom_reachable(grid):
    assert grid.is_free(6.65, 1.9)  # the doorway (its lintel is above the robot)
    row, col = grid.world_to_cell(MARKERS["bathroom"].x, MARKERS["bathroom"].y)
    assert grid.known[row, col]  # the flood fill from the entrance got in
    outside = grid.world_to_cell(-1.8, 0.0)
    assert not grid.known[outside]  # beyond the walls is unknown


def test_moving_things_are_not_in_the_map():
    model = build_scene("lab", ROBOT).model  # with the robot attached
    grid = grid_from_model(model)
    assert grid.is_free(0.0, 0.0)  # the robot stands here
    bottle = grid.world_to_cell(4.01, 1.38)
    assert grid.occupied[bottle]  # ...only because the table is under it
    reference = scene_grid("lab")
    assert np.array_equal(grid.occupied, reference.occupied)


def test_committed_map_matches_the_scene(grid):
    committed = read_map(MAPS_DIR / "lab.yaml")
    assert committed.resolution == grid.resolution
    assert committed.origin == pytest.approx(grid.origin)
    assert np.array_equal(committed.occupied, grid.occupied), \
        "sim/maps/lab.png is stale: run python -m stuart_bt.sim.world.occupancy --scene lab"
    assert np.array_equal(committed.known, grid.known)
    assert committed.inflation == pytest.approx(0.3)


def test_save_load_round_trip_and_conversions(grid, tmp_path):
    png, yaml_path = write_map(grid, tmp_path / "m")
    loaded = read_map(yaml_path)
    assert np.array_equal(loaded.occupied, grid.occupied)
    row, col = grid.world_to_cell(2.01, 1.01)
    x, y = grid.cell_to_world(row, col)
    assert abs(x - 2.01) <= grid.resolution / 2 and abs(y - 1.01) <= grid.resolution / 2
    assert grid.world_to_cell(x, y) == (row, col)
    assert not grid.is_free(100.0, 100.0)  # off the map


def test_map_picture(grid, tmp_path):
    out = draw_map_png(grid, MARKERS, [(0.0, 0.0), (1.0, 0.5), (3.5, 1.5)],
                       {"bottle": {"x": 4.1, "y": 1.35, "z": 0.85}}, tmp_path / "map.png")
    from PIL import Image

    with Image.open(out) as image:
        assert image.size == (grid.shape[1] * 4, grid.shape[0] * 4)
        pixels = np.asarray(image.convert("RGB"))
    assert (np.abs(pixels.astype(int) - (30, 110, 230)).sum(axis=2) == 0).any()  # the path is drawn


def test_marker_file_is_untouched_and_consistent():
    data = json.loads((MAPS_DIR / "lab_markers.json").read_text())
    assert data["frame"] == "map" and {"entrance", "kitchen", "bathroom", "workbench"} <= set(data["markers"])
