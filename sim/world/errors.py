"""The world server's error, on both sides of its socket. The world speaks the daemons' line
protocol (docs/protocol.md), so its codes come from the same table: a request the world refuses
is answered ``{"id": ..., "type": "error", "code": ..., "reason": ...}`` with one of
:data:`~stuart_bt.daemon.protocol.WORLD_CODES`, and raised in the client as the same
:class:`WorldError`."""

from __future__ import annotations

from stuart_bt.core.errors import CodedError
from stuart_bt.daemon.protocol import CLIENT_CODES, WORLD_CODES

__all__ = ["CLIENT_CODES", "WORLD_CODES", "WorldError"]


class WorldError(CodedError):
    """The world refused a request (``code`` one of ``WORLD_CODES``), or could not be reached
    (``CLIENT_CODES``: ``disconnected``, ``timeout``, ``start_failed``); nothing was done."""
