"""stuart_bt.maps on its own (no simulator): inflation, the planning grid, map and marker files."""

from __future__ import annotations

import numpy as np
import pytest

from stuart_bt.core.world import Marker
from stuart_bt.maps.files import read_map, write_map
from stuart_bt.maps.grid import OccupancyGrid
from stuart_bt.maps.inflation import inflate, radius_in_cells
from stuart_bt.maps.markers import MarkerFileError, load_markers, save_markers


def test_inflation_is_a_disc_of_whole_cells():
    mask = np.zeros((9, 9), dtype=bool)
    mask[4, 4] = True
    grown = inflate(mask, 2)
    assert grown.sum() == 13  # the cells within 2 of the centre: no corners
    assert grown[4, 2] and grown[2, 4] and not grown[2, 2]
    assert radius_in_cells(0.3, 0.05) == 6 and radius_in_cells(0.31, 0.05) == 7  # rounded up


def test_planning_grid_grows_obstacles_by_the_asked_radius():
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[10, 10] = True
    grid = OccupancyGrid.from_obstacles(occupied, 0.05, (0.0, 0.0), inflation=0.2)
    assert np.array_equal(grid.planning_grid().occupied, inflate(occupied, 4))
    assert np.array_equal(grid.planning_grid(0.1).occupied, inflate(occupied, 2))
    assert grid.planning_grid().cell_to_world(10, 10) == grid.cell_to_world(10, 10)


def test_map_files_round_trip_and_an_inflation_override(tmp_path):
    occupied = np.zeros((12, 16), dtype=bool)
    occupied[:, 0] = occupied[:, -1] = occupied[0, :] = occupied[-1, :] = True
    occupied[6, 1:15] = True  # a wall: the upper half is unknown from the seed
    grid = OccupancyGrid.from_obstacles(occupied, 0.1, (-0.5, -0.3), 0.25, seeds=[(0.3, 0.0)])
    _, yaml_path = write_map(grid, tmp_path / "room")
    loaded = read_map(yaml_path)
    assert np.array_equal(loaded.occupied, occupied) and np.array_equal(loaded.known, grid.known)
    assert loaded.origin == pytest.approx(grid.origin) and loaded.inflation == pytest.approx(0.25)
    assert read_map(yaml_path, inflation=0.4).inflation == 0.4


def test_marker_files_round_trip_and_refuse_a_bad_one(tmp_path):
    path = tmp_path / "markers.json"
    save_markers(path, {"dock": Marker("dock", 1.0, -2.0, 0.5, "Dock")})
    assert load_markers(path) == {"dock": Marker("dock", 1.0, -2.0, 0.5, "Dock")}
    path.write_text('{"markers": {"dock": {"x": "near"}}}')
    with pytest.raises(MarkerFileError, match="'dock' needs numeric x and y"):
        load_markers(path)
