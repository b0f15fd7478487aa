"""``python -m stuart_bt.sim.robot [--check]``: write sim/models/g1.xml and g1.urdf from the
description, or (``--check``) exit 1 if the committed files differ from what would be written.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import MJCF_PATH, URDF_PATH, g1
from .mjcf import to_mjcf
from .urdf import to_urdf


def generated() -> dict[Path, str]:
    """Each model file and the text it should hold."""
    robot = g1()
    return {MJCF_PATH: to_mjcf(robot), URDF_PATH: to_urdf(robot)}


def stale() -> list[Path]:
    """The model files that are missing or differ from the description."""
    return [path for path, text in generated().items()
            if not path.exists() or path.read_text(encoding="utf-8") != text]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m stuart_bt.sim.robot", description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if the committed files are out of date")
    args = parser.parse_args(argv)
    if args.check:
        out_of_date = stale()
        for path in out_of_date:
            print(f"{path} is out of date: run python -m stuart_bt.sim.robot", file=sys.stderr)
        return 1 if out_of_date else 0
    for path, text in generated().items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
