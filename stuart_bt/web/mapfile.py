"""The occupancy map the map page draws: a map_server PNG + YAML (sim/maps/lab.* by default).

The browser gets the picture as it is and the numbers to place it (resolution, origin, size);
the server keeps the pixels to refuse markers on obstacles. Row 0 of the PNG is the highest y
(map_server convention), the origin is the map-frame corner of the bottom-left cell.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib.resources import files
from pathlib import Path
from typing import Any

import yaml

from .markers import MapBounds

FREE_ABOVE = 255 * (1 - 0.196)  # grey levels lighter than this are free space (free_thresh 0.196)


def default_map() -> Path:
    return Path(str(files("stuart_bt.sim").joinpath("maps/lab.yaml")))


@dataclass
class MapFile:
    png: Path
    resolution: float
    origin: tuple[float, float]
    width: int
    height: int
    pixels: Any = None  # rows of grey levels, or None without Pillow

    @classmethod
    def load(cls, yaml_path: str | Path) -> MapFile:
        yaml_path = Path(yaml_path)
        meta = yaml.safe_load(yaml_path.read_text(encoding="utf-8"))
        png = yaml_path.parent / meta["image"]
        width = height = 0
        pixels = None
        try:
            from PIL import Image

            with Image.open(png) as image:
                grey = image.convert("L")
                width, height = grey.size
                pixels = grey.load()
        except ImportError:  # without the sim extra: draw the map, skip the obstacle check
            width, height = _png_size(png)
        return cls(png, float(meta["resolution"]), (float(meta["origin"][0]), float(meta["origin"][1])),
                   width, height, pixels)

    def info(self) -> dict[str, Any]:
        """What the browser needs to put map coordinates on the picture."""
        return {"resolution": self.resolution, "origin": list(self.origin), "width": self.width, "height": self.height}

    def occupied(self, x: float, y: float) -> bool:
        """True where the robot cannot stand: an obstacle, unknown space, or off the picture."""
        if self.pixels is None:
            return False
        col = int((x - self.origin[0]) / self.resolution)
        row = self.height - 1 - int((y - self.origin[1]) / self.resolution)
        if not (0 <= col < self.width and 0 <= row < self.height):
            return True
        return self.pixels[col, row] <= FREE_ABOVE

    def bounds(self) -> MapBounds:
        ox, oy = self.origin
        return MapBounds(ox, oy, ox + self.width * self.resolution, oy + self.height * self.resolution, self.occupied)


def _png_size(png: Path) -> tuple[int, int]:
    header = png.read_bytes()[:24]
    return int.from_bytes(header[16:20], "big"), int.from_bytes(header[20:24], "big")
