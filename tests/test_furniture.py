"""What the obstacles on a map are called (stuart_bt.maps.furniture): the furniture file next to
the map, the names at a point, and the lab's file, written from the scene's bodies."""

from __future__ import annotations

import numpy as np
import pytest

from stuart_bt.maps.files import read_map, write_map
from stuart_bt.maps.furniture import (
    Furniture,
    FurnitureCells,
    FurnitureFileError,
    Piece,
    circle_outline,
    furniture_for_map,
    ranked,
    read_furniture,
    write_furniture,
)
from stuart_bt.maps.grid import Grid, OccupancyGrid
from stuart_bt.sim.world.scene import MAPS_DIR

TABLE = Piece("kitchen table", (((3.91, 0.9), (4.71, 0.9), (4.71, 2.1), (3.91, 2.1)),))
STOOL = Piece("stool", (circle_outline(5.5, 1.5, 0.2),))


def test_a_point_on_or_near_a_piece_gets_its_name_and_a_point_in_the_open_none():
    furniture = Furniture((TABLE, STOOL))
    assert furniture.at(4.3, 1.5) == "kitchen table"
    assert furniture.at(4.8, 1.5) is None and furniture.at(4.8, 1.5, within=0.1) == "kitchen table"
    assert furniture.at(5.5, 1.69) == "stool", "the circle's polygon cut the round stool short"
    assert furniture.at(2.0, 0.0, within=0.5) is None
    assert Furniture().at(4.3, 1.5, within=1.0) is None and not Furniture()


def test_names_laid_on_a_grid_agree_with_the_outlines_everywhere():
    furniture = Furniture((TABLE, STOOL))
    grid = Grid(np.zeros((60, 70), dtype=bool), 0.05, (3.0, 0.0))
    cells = FurnitureCells(furniture, grid, reach=0.4)
    rng = np.random.default_rng(7)
    for _ in range(400):
        row, col = int(rng.integers(0, 60)), int(rng.integers(0, 70))
        x, y = grid.cell_to_world(row, col)
        within = float(rng.uniform(0.0, 0.4))
        assert cells.at(x, y, within) == furniture.at(x, y, within), (x, y, within)
    assert cells.at(100.0, 100.0, 1.0) is None, "off the grid"


def test_what_was_in_the_way_most_often_is_named_first_and_unnamed_obstacles_not_at_all():
    assert ranked(["wall", "kitchen table", None, "kitchen table", None, "wall", "kitchen table"]) == [
        "kitchen table", "wall"]
    assert ranked([None, None]) == []


def test_a_furniture_file_round_trips_and_the_map_yaml_names_it(tmp_path):
    path = write_furniture([TABLE, STOOL], tmp_path / "room_furniture.json")
    read = read_furniture(path)
    assert [p.name for p in read.pieces] == ["kitchen table", "stool"]
    assert read.at(4.3, 1.5) == "kitchen table"
    grid = OccupancyGrid(np.zeros((4, 4), dtype=bool), 0.05, (0.0, 0.0))
    _, yaml_path = write_map(grid, tmp_path / "room", furniture=path.name)
    assert furniture_for_map(yaml_path).at(5.5, 1.5) == "stool"
    assert read_map(yaml_path).shape == (4, 4), "the extra key upset the map reader"
    _, plain = write_map(grid, tmp_path / "plain")
    assert not furniture_for_map(plain), "a map without a furniture file knows no names"


@pytest.mark.parametrize(("text", "says"), [
    ('{"frame": "map"}', "expected an object with a 'furniture' list"),
    ('{"furniture": [{"outlines": [[[0, 0]]]}]}', "furniture[0]: needs a 'name'"),
    ('{"furniture": [{"name": "box", "outlines": []}]}', "furniture[0] (box): 'outlines' must be a non-empty list"),
    ('{"furniture": [{"name": "box", "outlines": [[["a", 0]]]}]}', "an outline is not a list of [x, y] points"),
    ('{"furniture": [}', "not valid JSON"),
])
def test_a_broken_furniture_file_is_one_clear_message_naming_the_file(tmp_path, text, says):
    path = tmp_path / "bad.json"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(FurnitureFileError) as failed:
        read_furniture(path)
    assert str(failed.value).startswith(str(path)) and says in str(failed.value)


def test_the_committed_lab_furniture_file_matches_the_scene_and_names_what_people_call_things():
    from stuart_bt.sim.world.occupancy import scene_furniture

    committed = furniture_for_map(MAPS_DIR / "lab.yaml")
    scene = scene_furniture("lab")
    assert [(p.name, len(p.outlines)) for p in committed.pieces] == [(p.name, len(p.outlines)) for p in scene], \
        "sim/maps/lab_furniture.json is stale: run python -m stuart_bt.sim.world.occupancy --scene lab"
    for mine, theirs in zip(committed.pieces, scene, strict=True):
        for a, b in zip(mine.outlines, theirs.outlines, strict=True):
            assert np.allclose(a, b, atol=1e-4), mine.name
    assert committed.at(4.31, 1.5) == "kitchen table"
    assert committed.at(1.0, -3.16) == "workbench"
    assert committed.at(-1.55, 0.0) == "wall"
    assert all("_" not in p.name and not p.name[-1].isdigit() for p in committed.pieces), \
        [p.name for p in committed.pieces]
