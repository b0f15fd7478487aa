"""Loading a YAML tree file (and its includes) into a validated :class:`TreeSpec`.

Everything is checked before anything runs: all problems in all files are collected and raised
together as one :class:`TreeLoadError`. See docs/trees.md for the language.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..maps.marker_names import UnknownMarker, find_marker
from ..maps.markers import MarkerFileError, load_markers
from .errors import ErrorLog, TreeError, TreeLoadError
from .include_params import Scope, base_dir_of, defaults
from .nodes import NodeReader
from .spec import Location, NodeSpec, TreeSpec
from .treefile import TreeFile, read_tree_file
from .yaml_source import MAX_DEPTH, Source, read_file, read_text


def load_tree(path: str | Path, *, markers_file: str | Path | None = None) -> TreeSpec:
    """Load the tree file at ``path``; ``markers_file`` overrides the tree's ``markers:`` key."""
    source = read_file(Path(path), str(path))
    return _Session(markers_file).load(source, Path(path).resolve() if source.root is not None else None)


def load_tree_text(text: str, file: str = "<string>", *, markers_file: str | Path | None = None) -> TreeSpec:
    """Load a tree from text; ``file`` names it in errors and is where relative paths start
    (the current directory for the default ``<string>``)."""
    resolved = None if file.startswith("<") or "\0" in file else Path(file).resolve()
    return _Session(markers_file).load(read_text(text, file), resolved)


class _Session:
    """One load: the files read so far, merged blackboard values and the marker file in force."""

    def __init__(self, markers_file: str | Path | None) -> None:
        self.log = ErrorLog()
        self.files: dict[Path, TreeFile | None] = {}
        self.blackboard: dict[str, Any] = {}
        self.markers_file = str(markers_file) if markers_file is not None else None
        self.markers_location: Location | None = None

    def load(self, source: Source, resolved: Path | None) -> TreeSpec:
        try:
            return self._load(source, resolved)
        except RecursionError:
            raise TreeLoadError([*self.log.in_reading_order(), TreeError(None, f"{source.file}: tree nested too deeply "
                                                                   f"(more than {MAX_DEPTH} levels)")]) from None

    def _load(self, source: Source, resolved: Path | None) -> TreeSpec:
        tree = read_tree_file(source, self.log)
        root: NodeSpec | None = None
        if tree is not None:
            self._adopt(tree)
            if resolved is not None:
                self.files[resolved] = tree
            reader = NodeReader(self.log, self.open_include)
            if tree.root is not None:
                chain = ((resolved, source.file),) if resolved is not None else ()
                scope = Scope(source.file, base_dir_of(source.file), defaults(tree.declared, source.file), chain)
                default_name = "root" if source.file.startswith("<") else Path(source.file).stem
                root = reader.root(tree.root, scope, default_name)
            self._check_markers(reader)
        if self.log or root is None or tree is None:
            raise TreeLoadError(self.log.in_reading_order())
        return TreeSpec(
            root=root,
            file=source.file,
            markers_file=self.markers_file,
            blackboard=self.blackboard,
            params={name: d.as_written() for name, d in tree.declared.items()},
            description=tree.description,
        )

    def open_include(self, resolved: Path, shown: str) -> TreeFile | None:
        """An included file's top level, read once however often it is included."""
        if resolved not in self.files:
            tree = read_tree_file(read_file(resolved, shown), self.log)
            self.files[resolved] = tree
            if tree is not None:
                self._adopt(tree)
        return self.files[resolved]

    def _adopt(self, tree: TreeFile) -> None:
        """Includers are read first, so their blackboard values and marker file win."""
        for key, value in tree.blackboard.items():
            self.blackboard.setdefault(key, value)
        if self.markers_file is None and tree.markers is not None:
            self.markers_file, self.markers_location = tree.markers, tree.markers_location

    def _check_markers(self, reader: NodeReader) -> None:
        if self.markers_file is None:
            return
        try:
            markers = load_markers(self.markers_file)
        except MarkerFileError as e:
            self.log.add(self.markers_location, str(e))
            return
        for use in reader.markers:
            try:
                use.spec.params[use.param] = find_marker(use.name, markers)
            except UnknownMarker as e:
                self.log.add(use.location, f"{use.what}: {e}", use.spec.path)
