"""The map files: a ROS map_server map, a greyscale PNG plus a YAML that places it.

Black is occupied, white free, grey unknown (``mode: trinary``, ``negate: 0``); the PNG's row 0
is the highest y, so the picture looks like the room from above. The YAML has the map_server
keys (``image``, ``resolution``, ``origin``, thresholds) plus our ``inflation``: the robot radius
the map is meant to be planned with. Keeping that format means the same files work on the robot
(ROS tools, the vendor navigation) and in the simulator.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .grid import ROBOT_RADIUS, OccupancyGrid

FREE, UNKNOWN, OCCUPIED = 254, 205, 0  # PNG grey levels (map_server, negate 0)


def map_image(grid: OccupancyGrid) -> np.ndarray:
    """The map_server picture: row 0 at the top (highest y)."""
    pixels = np.full(grid.shape, FREE, dtype=np.uint8)
    if grid.known is not None:
        pixels[~grid.known] = UNKNOWN
    pixels[grid.occupied] = OCCUPIED
    return np.flipud(pixels)


def write_map(grid: OccupancyGrid, stem: str | Path, furniture: str | None = None) -> tuple[Path, Path]:
    """Write ``stem.png`` and ``stem.yaml`` (map_server format, plus our ``inflation`` and, when
    given, ``furniture``: the file next to it that names the obstacles, :mod:`.furniture`)."""
    from PIL import Image

    stem = Path(stem)
    png, yaml_path = stem.with_suffix(".png"), stem.with_suffix(".yaml")
    png.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(map_image(grid)).save(png, optimize=True)
    yaml_path.write_text(
        f"image: {png.name}\n"
        "mode: trinary\n"
        f"resolution: {grid.resolution:g}\n"
        f"origin: [{grid.origin[0]:.4f}, {grid.origin[1]:.4f}, 0.0]\n"
        "negate: 0\n"
        "occupied_thresh: 0.65\n"
        "free_thresh: 0.196\n"
        f"inflation: {grid.inflation:g}  # robot radius the map is planned with (not a map_server key)\n"
        + (f"furniture: {furniture}  # names of the obstacles (not a map_server key)\n" if furniture else ""),
        encoding="utf-8")
    return png, yaml_path


def read_map(yaml_path: str | Path, inflation: float | None = None) -> OccupancyGrid:
    """A map_server map: occupied where the occupancy ((255 - pixel) / 255, or pixel / 255 with
    ``negate``) is above ``occupied_thresh``, free below ``free_thresh``, unknown in between.
    ``inflation`` overrides the file's (default :data:`ROBOT_RADIUS` when it has none)."""
    import yaml
    from PIL import Image

    yaml_path = Path(yaml_path)
    meta = yaml.safe_load(yaml_path.read_text(encoding="utf-8"))
    pixels = np.flipud(np.asarray(Image.open(yaml_path.parent / meta["image"]).convert("L")))
    occupancy = pixels / 255.0 if meta.get("negate", 0) else (255.0 - pixels) / 255.0
    occupied = occupancy > float(meta.get("occupied_thresh", 0.65))
    free = occupancy < float(meta.get("free_thresh", 0.196))
    radius = float(meta.get("inflation", ROBOT_RADIUS)) if inflation is None else inflation
    origin = (float(meta["origin"][0]), float(meta["origin"][1]))
    return OccupancyGrid(occupied.copy(), float(meta["resolution"]), origin, radius, known=(occupied | free).copy())
