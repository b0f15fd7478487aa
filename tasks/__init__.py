"""The project's own HTN domain: tasks/domain.yaml (tasks, methods, primitives) and the Python
hooks it names (tasks/hooks.py). The planner (:mod:`stuart_bt.htn`) knows nothing of this
folder; missions and ``stuart-bt plan`` ask for it here."""

from __future__ import annotations

from functools import lru_cache
from importlib.resources import files
from pathlib import Path

from stuart_bt.htn.domain import Domain
from stuart_bt.htn.load import load_domain

PROJECT_DOMAIN = "domain.yaml"


@lru_cache(maxsize=1)
def project_domain() -> Domain:
    """tasks/domain.yaml with the project's hooks (tasks/hooks.py), loaded once per process."""
    from .hooks import HOOKS

    return load_domain(Path(str(files(__name__).joinpath(PROJECT_DOMAIN))), HOOKS)
