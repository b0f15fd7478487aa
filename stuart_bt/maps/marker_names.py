"""Finding a marker by what a person writes: its name (``station_4``) or its display name
("Electronics bench"), with case, spaces, ``_`` and ``-`` not mattering.

Tree files are written by people who read the map's display names, so ``navigate: Electronics
bench`` means ``station_4``. The tree loader resolves names this way (and writes the marker's
name into the tree), and so does the ``navigate`` leaf for names that only arrive at run time
(a ``$target`` from the blackboard). A name that matches nothing says which markers there are.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from ..core.errors import StuartError
from ..core.suggest import closest
from ..core.world import Marker

MAX_LISTED = 30  # markers named in an "unknown marker" message; more are counted


class UnknownMarker(StuartError, LookupError):
    """No marker, or more than one, goes by the name written."""


def marker_key(text: str) -> str:
    """How names are compared: ``"Electronics bench"``, ``"electronics_bench"`` and
    ``"ElectronicsBench"`` are the same."""
    return re.sub(r"[\s_\-]+", "", text).casefold()


def find_marker(text: str, markers: Mapping[str, Marker]) -> str:
    """The name of the marker ``text`` names (itself when it is a marker name); raises
    :class:`UnknownMarker` when none does, or several do."""
    if text in markers:
        return text
    key = marker_key(text)
    found = sorted(name for name, m in markers.items() if key and key in (marker_key(name), marker_key(m.display_name)))
    if len(found) == 1:
        return found[0]
    if found:
        raise UnknownMarker(f"marker {text!r} could be any of {', '.join(_listed(markers[n]) for n in found)}; "
                            "write the marker's name")
    raise UnknownMarker(unknown_marker_message(text, markers))


def unknown_marker_message(text: str, markers: Mapping[str, Marker]) -> str:
    """``unknown marker 'kitchn' (did you mean 'kitchen'?); the markers are ...``."""
    if not markers:
        return f"unknown marker {text!r}: the marker file has no markers"
    shown = [m.display_name for m in markers.values() if marker_key(m.display_name) not in ("", marker_key(m.name))]
    best = closest(text, [*shown, *markers])
    hint = f" (did you mean {best!r}?)" if best else ""
    listed = [_listed(m) for m in markers.values()]
    more = f" and {len(listed) - MAX_LISTED} more" if len(listed) > MAX_LISTED else ""
    return f"unknown marker {text!r}{hint}; the markers are {', '.join(listed[:MAX_LISTED])}{more}"


def _listed(marker: Marker) -> str:
    """``station_4 "Electronics bench"``; just ``kitchen`` when the display name says the same."""
    if not marker.display_name or marker_key(marker.display_name) == marker_key(marker.name):
        return marker.name
    return f'{marker.name} "{marker.display_name}"'
