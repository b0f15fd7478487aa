"""One base for the errors the framework expects and can explain.

A :class:`StuartError` carries a short machine-readable ``code`` and ``reason``, one sentence for
people; ``str(error)`` is what a person reads. The command line prints any of them as one line
with no traceback (``stuart-bt: <reason>``); anything else is a bug and says so. Errors that
cross a process boundary (the daemons' and the world server's line protocols) are
:class:`CodedError`: made as ``(code, reason)``, read as ``code: reason``, answered as
``{"error": code, "reason": reason}`` with the codes of docs/protocol.md and docs/sim.md.

Many of these also keep the built-in base they always had (``ValueError`` for bad input,
``RuntimeError`` for a failing part), so existing ``except ValueError`` code still catches them.
"""

from __future__ import annotations


class StuartError(Exception):
    """An expected failure with a code and a sentence for people."""

    code: str = "error"

    def __init__(self, reason: str = "", code: str | None = None) -> None:
        super().__init__(reason)
        self.reason = reason
        if code is not None:
            self.code = code


class CodedError(StuartError):
    """An error of a line protocol: ``(code, reason)``, shown as ``code: reason``."""

    def __init__(self, code: str, reason: str) -> None:
        super().__init__(reason, code)

    def __str__(self) -> str:
        return f"{self.code}: {self.reason}"
