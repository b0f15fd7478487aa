"""Who may use the web view: loopback without a token, any other address only with one.

Rule: a server bound to 127.0.0.1, ``localhost`` or ``::1`` is reachable only from this machine and
needs no token. Bound anywhere else (0.0.0.0, a LAN address, even 127.0.0.2) every request and
every socket must carry the token printed at start: as ``?token=`` (the printed address has it;
the page then keeps it in a same-site cookie so its own scripts and socket carry it) or as an
``Authorization: Bearer`` header. Independently of the token, a request that changes something
(POST, PUT, DELETE) and every WebSocket must come from the page itself: an ``Origin`` header,
when a browser sends one, must name this server, so another site open in the same browser can
neither drive the robot nor read the stream.
"""

from __future__ import annotations

import hmac
import secrets
from dataclasses import dataclass
from typing import Mapping
from urllib.parse import urlsplit

LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "::1")
COOKIE = "stuart_bt_token"
CHANGING = ("POST", "PUT", "PATCH", "DELETE")


def needs_token(host: str) -> bool:
    return host not in LOOPBACK_HOSTS


@dataclass
class Guard:
    """The checks for one server; ``token`` is None on loopback."""

    token: str | None

    @classmethod
    def for_host(cls, host: str) -> "Guard":
        return cls(secrets.token_urlsafe(24) if needs_token(host) else None)

    def token_ok(self, query: Mapping[str, str], headers: Mapping[str, str], cookies: Mapping[str, str]) -> bool:
        if self.token is None:
            return True
        auth = headers.get("authorization", "")
        offered = [query.get("token", ""), cookies.get(COOKIE, ""),
                   auth[7:] if auth.lower().startswith("bearer ") else ""]
        return any(o and hmac.compare_digest(o.encode(), self.token.encode()) for o in offered)

    @staticmethod
    def origin_ok(headers: Mapping[str, str], scheme: str = "http") -> bool:
        """No Origin (not a browser, or a same-origin GET) passes; otherwise it must be this host."""
        origin = headers.get("origin")
        if origin is None:
            return True
        host = headers.get("host", "")
        parts = urlsplit(origin)
        return parts.scheme in (scheme, scheme.replace("ws", "http")) and parts.netloc == host
