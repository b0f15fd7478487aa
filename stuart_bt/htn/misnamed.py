"""The one wording of a "no such name" error in a domain file: what was written, the closest
known name, and (where the list is short enough to help) every name that would do.

Every reader of the domain file builds these messages here, so a wrong key, type, skill, hook,
task or parameter reads the same way wherever it is written, and the tests that assert the
file:line messages pin one format rather than ten.
"""

from __future__ import annotations

from collections.abc import Iterable

from ..core.suggest import did_you_mean


def misnamed(lead: str, name: object, known: Iterable[str], listing: str | None = None) -> str:
    """``{lead} 'name' (did you mean 'x'?) ({listing}: a, b, c)``.

    ``name`` is shown as its ``repr`` (so a missing keyword name shows as ``None``), matched as
    text; ``listing`` names the list of known names, which is left out when it is None and shown
    as ``none`` when there are no names at all.
    """
    names = list(known)
    message = f"{lead} {name!r}{did_you_mean(str(name), names)}"
    if listing is not None:
        message += f" ({listing}: {', '.join(names) or 'none'})"
    return message
