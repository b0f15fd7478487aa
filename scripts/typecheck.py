"""Type-check the whole package as it is imported: ``stuart_bt`` with ``skills/``, ``sim/`` and
``tasks/`` inside it (setup.py maps those top-level folders to ``stuart_bt.skills`` and so on).

mypy finds modules by folder, so it is shown a package view: a temporary folder whose
``stuart_bt`` holds links to every entry of ``stuart_bt/`` and to the three mapped folders.
Paths in mypy's report are given back as the repository's own. Exit status: mypy's.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
MAPPED = ("skills", "sim", "tasks")  # as in setup.py


def package_view(root: Path) -> Path:
    view = root / "stuart_bt"
    view.mkdir()
    for entry in (REPO / "stuart_bt").iterdir():
        if entry.name != "__pycache__" and entry.name not in MAPPED:  # a checkout may link them already
            (view / entry.name).symlink_to(entry)
    for name in MAPPED:
        (view / name).symlink_to(REPO / name)
    return view


def main() -> int:
    from mypy import api

    with tempfile.TemporaryDirectory(prefix="stuart-typecheck-") as tmp:
        view = package_view(Path(tmp))
        out, err, status = api.run(["--config-file", str(REPO / "pyproject.toml"), "--no-incremental",
                                    "--python-executable", sys.executable, str(view)])
    for name in MAPPED:
        out = out.replace(f"{view}/{name}/", f"{name}/")
    out = out.replace(f"{view}/", "stuart_bt/")
    sys.stdout.write(out)
    sys.stderr.write(err)
    return status


if __name__ == "__main__":
    sys.exit(main())
