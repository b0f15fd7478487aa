"""The grammar runs compiled, and never from a compiled file older than its source.

The modules a parse runs through on every word (the grammar, the number reader and the wake
filter, :data:`COMPILED`) are compiled to C extensions with mypyc when the package is installed
(setup.py): a parse then takes about 40 % of the time it takes as Python (bench/parse.py), which
is what keeps its p99 inside the 50 µs budget. The Python source stays the truth: the same
files, type-checked, and the suite runs on whichever of the two is imported.

An extension module sits next to its ``.py`` file and Python's import prefers it. After an edit
the extension is out of date, and a developer would be running yesterday's grammar. So, like
Python's own ``.pyc`` files, an extension older than its source is not used: when any compiled
module's source is newer than its extension, every one of them is imported from source
(mypyc's modules call each other directly, so they are used all together or not at all), with
one line on stderr saying how to compile them again (``make``, or ``pip install -e .``).
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import importlib.util
import sys
from collections.abc import Sequence
from importlib.machinery import ModuleSpec
from pathlib import Path
from types import ModuleType

PACKAGE = "stuart_bt.language"
# module names under PACKAGE, compiled by setup.py (the lexicon is data: nothing to gain)
COMPILED = ("numbers", "wake", "grammar.tokens", "grammar.state", "grammar.forms", "grammar.nouns", "grammar.amounts",
            "grammar.gestures", "grammar.finding", "grammar.stopping", "grammar.motion", "grammar.picking",
            "grammar.light_verbs", "grammar.clauses", "grammar.driver", "grammar.coverage")
ROOT = Path(__file__).resolve().parent


def source_path(module: str, root: Path = ROOT) -> Path:
    """The ``.py`` file of a module named relative to the package."""
    return root.joinpath(*module.split(".")).with_suffix(".py")


def extension_path(module: str, root: Path = ROOT) -> Path | None:
    """The compiled extension beside the module's source, if there is one."""
    source = source_path(module, root)
    for suffix in importlib.machinery.EXTENSION_SUFFIXES:
        candidate = source.with_name(source.stem + suffix)
        if candidate.is_file():
            return candidate
    return None


def stale(modules: Sequence[str] = COMPILED, root: Path = ROOT) -> list[str]:
    """The modules whose source was changed after their extension was built."""
    out = []
    for module in modules:
        extension = extension_path(module, root)
        if extension is not None and source_path(module, root).stat().st_mtime > extension.stat().st_mtime:
            out.append(module)
    return out


def compiled(module: ModuleType) -> bool:
    """Whether ``module`` was imported from a compiled extension."""
    return not str(getattr(module, "__file__", "")).endswith(".py")


class _SourceFirst(importlib.abc.MetaPathFinder):
    """Imports the compiled modules from their ``.py`` files, ahead of the extensions."""

    def __init__(self, names: dict[str, Path]) -> None:
        self.names = names

    def find_spec(self, fullname: str, path: Sequence[str] | None = None,
                  target: ModuleType | None = None) -> ModuleSpec | None:
        source = self.names.get(fullname)
        return importlib.util.spec_from_file_location(fullname, source) if source is not None else None


def use_source_when_stale() -> list[str]:
    """Called before the package imports its modules: when any compiled module is out of date,
    import all of them from source and say so once. Returns the out-of-date modules."""
    out_of_date = stale()
    if out_of_date and not any(isinstance(f, _SourceFirst) for f in sys.meta_path):
        sys.meta_path.insert(0, _SourceFirst({f"{PACKAGE}.{m}": source_path(m) for m in COMPILED}))
        print(f"stuart_bt: the compiled grammar is older than its source ({', '.join(out_of_date)}); running the "
              "Python source instead (slower). `make` or `pip install -e .` compiles it again.", file=sys.stderr)
    return out_of_date
