"""``stuart-bt`` and every subcommand, one module each (``validate``, ``show``, ``run`` and
``schema`` in :mod:`.main`). The only place that parses command-line arguments."""

from .main import main

__all__ = ["main"]
