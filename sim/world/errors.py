"""The world server's error, on both sides of its socket: one class and its table of codes
(docs/sim.md). A request the world refuses is answered ``{"ok": false, "error": code, "reason": ...}``
and raised in the client as the same :class:`WorldError`."""

from __future__ import annotations

from stuart_bt.core.errors import CodedError

ERROR_CODES = ("bad_request", "unknown_command", "not_found", "out_of_range", "busy", "internal")


class WorldError(CodedError):
    """The world refused a request (``code`` one of :data:`ERROR_CODES`), or could not be reached
    (``disconnected`` / ``timeout``, client side); nothing was done."""
