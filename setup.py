"""Package layout: ``skills/``, ``sim/`` and ``tasks/`` live at the top of the repository but are
imported as ``stuart_bt.skills``, ``stuart_bt.sim`` and ``stuart_bt.tasks``, never as generic
top-level names. Everything else is in pyproject.toml."""

from setuptools import find_packages, setup

MAPPED = {"skills": "skills", "sim": "sim", "tasks": "tasks"}

packages = find_packages(include=["stuart_bt", "stuart_bt.*"])
package_dir = {}
for name, folder in MAPPED.items():
    packages.append(f"stuart_bt.{name}")
    packages += [f"stuart_bt.{name}.{sub}" for sub in find_packages(folder)]
    package_dir[f"stuart_bt.{name}"] = folder

setup(
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
