"""Package layout: ``skills/``, ``sim/`` and ``tasks/`` live at the top of the repository but are
imported as ``stuart_bt.skills``, ``stuart_bt.sim`` and ``stuart_bt.tasks``, never as generic
top-level names. The grammar's modules are compiled with mypyc (the list and the reason are in
stuart_bt/language/compiled.py; ``STUART_BT_PURE_PYTHON=1`` installs them as plain Python).
Everything else is in pyproject.toml."""

import ast
import os
from pathlib import Path

from setuptools import find_packages, setup

MAPPED = {"skills": "skills", "sim": "sim", "tasks": "tasks"}

packages = find_packages(include=["stuart_bt", "stuart_bt.*"])
package_dir = {}
for name, folder in MAPPED.items():
    packages.append(f"stuart_bt.{name}")
    packages += [f"stuart_bt.{name}.{sub}" for sub in find_packages(folder)]
    package_dir[f"stuart_bt.{name}"] = folder



def compiled_sources() -> list[str]:
    """The files named by ``COMPILED`` in stuart_bt/language/compiled.py (read, not imported: the
    package's dependencies are not installed yet)."""
    tree = ast.parse(Path("stuart_bt/language/compiled.py").read_text(encoding="utf-8"))
    names = next(ast.literal_eval(node.value) for node in tree.body if isinstance(node, ast.Assign)
                 and any(isinstance(t, ast.Name) and t.id == "COMPILED" for t in node.targets))
    return [os.path.join("stuart_bt", "language", *name.split(".")) + ".py" for name in names]


def extensions() -> list:
    if os.environ.get("STUART_BT_PURE_PYTHON"):
        return []
    from mypyc.build import mypycify  # a build requirement (pyproject.toml)

    return mypycify(compiled_sources(), opt_level="3")


setup(
    ext_modules=extensions(),
    packages=packages,
    package_dir=package_dir,
    package_data={
        "stuart_bt.skills": ["*.json"],
        "stuart_bt.sim": ["maps/*.json", "maps/*.png", "maps/*.yaml", "scenes/*.xml", "models/*.xml", "models/*.urdf"],
        "stuart_bt.tasks": ["*.yaml"],
        "stuart_bt.web": ["static/*"],
    },
    include_package_data=True,
)
