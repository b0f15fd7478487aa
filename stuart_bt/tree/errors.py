"""Load-time problems in tree files, each tied to a place so editors and people can jump to it.

The loader never stops at the first problem: it collects every :class:`TreeError` it can find
across the tree file and its includes, then raises one :class:`TreeLoadError` carrying them all,
so a user fixes a file in one pass instead of one error per run.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..core.errors import StuartError
from .spec import Location


@dataclass(frozen=True)
class TreeError:
    """One problem: where it is, which node it concerns (when known) and what was expected."""

    location: Location | None
    message: str
    path: str | None = None

    def __str__(self) -> str:
        text = f"{self.path}: {self.message}" if self.path else self.message
        return f"{self.location}: {text}" if self.location else text


class TreeLoadError(StuartError):
    """The tree could not be loaded; ``errors`` lists every problem found, in reading order."""

    def __init__(self, errors: list[TreeError]) -> None:
        self.errors = list(errors)
        super().__init__("\n".join(str(e) for e in self.errors))


class ErrorLog:
    """Collects problems while loading; the same problem reached twice (a subtree included
    several times) is kept once."""

    def __init__(self) -> None:
        self.errors: list[TreeError] = []
        self._seen: set[tuple[Location | None, str]] = set()

    def add(self, location: Location | None, message: str, path: str | None = None) -> None:
        key = (location, message)
        if key not in self._seen:
            self._seen.add(key)
            self.errors.append(TreeError(location, message, path))

    def extend(self, errors: list[TreeError]) -> None:
        for e in errors:
            self.add(e.location, e.message, e.path)

    def in_reading_order(self) -> list[TreeError]:
        """Errors file by file (in the order files were reached), then by line and column."""
        files: dict[str, int] = {}
        for e in self.errors:
            if e.location is not None:
                files.setdefault(e.location.file, len(files))

        def key(e: TreeError) -> tuple[int, int, int]:
            if e.location is None:
                return (-1, 0, 0)
            return (files[e.location.file], e.location.line, e.location.column)

        return sorted(self.errors, key=key)

    def __bool__(self) -> bool:
        return bool(self.errors)
