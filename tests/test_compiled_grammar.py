"""The grammar is compiled with mypyc at install time (stuart_bt/language/compiled.py), and a
compiled module older than its source is never the one that runs."""

from __future__ import annotations

import importlib.machinery
import os
import sys

import pytest

from stuart_bt.language import compiled
from stuart_bt.language.grammar import driver

SUFFIX = importlib.machinery.EXTENSION_SUFFIXES[0]


def _module_pair(root, name: str, source_time: float, extension_time: float) -> None:
    source = root / "grammar" / f"{name}.py"
    source.parent.mkdir(exist_ok=True)
    source.write_text("X = 1\n")
    extension = source.with_name(name + SUFFIX)
    extension.write_bytes(b"")
    os.utime(source, (source_time, source_time))
    os.utime(extension, (extension_time, extension_time))


def test_an_extension_older_than_its_source_is_stale(tmp_path):
    _module_pair(tmp_path, "edited", source_time=2_000_000, extension_time=1_000_000)
    _module_pair(tmp_path, "built", source_time=1_000_000, extension_time=2_000_000)
    assert compiled.stale(["grammar.edited", "grammar.built"], tmp_path) == ["grammar.edited"]


def test_a_module_without_an_extension_is_never_stale(tmp_path):
    (tmp_path / "grammar").mkdir()
    (tmp_path / "grammar" / "plain.py").write_text("X = 1\n")
    assert compiled.extension_path("grammar.plain", tmp_path) is None
    assert compiled.stale(["grammar.plain"], tmp_path) == []


def test_the_source_first_finder_imports_a_compiled_module_from_its_py_file():
    name = f"{compiled.PACKAGE}.grammar.tokens"
    finder = compiled._SourceFirst({name: compiled.source_path("grammar.tokens")})
    spec = finder.find_spec(name)
    assert spec is not None and spec.origin is not None and spec.origin.endswith("tokens.py")
    assert isinstance(spec.loader, importlib.machinery.SourceFileLoader)
    assert finder.find_spec("json") is None  # anything else is left to the usual finders


def test_every_compiled_module_has_its_source_in_the_package():
    for name in compiled.COMPILED:
        assert compiled.source_path(name).is_file(), name


def test_the_installed_grammar_runs_compiled():
    if os.environ.get("STUART_BT_PURE_PYTHON"):
        pytest.skip("STUART_BT_PURE_PYTHON is set: the grammar was installed as plain Python")
    if compiled.stale():
        pytest.skip(f"the compiled grammar is older than its source ({compiled.stale()}): run make to compile it")
    assert compiled.compiled(driver), f"{driver.__file__}: not compiled (setup.py did not build the extensions)"
    assert all(compiled.compiled(sys.modules[f"{compiled.PACKAGE}.{name}"]) for name in compiled.COMPILED
               if f"{compiled.PACKAGE}.{name}" in sys.modules)
