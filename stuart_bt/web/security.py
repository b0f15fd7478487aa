"""Who may use the web view: loopback without a token, any other address only with one.

Rule: a server bound to 127.0.0.1, ``localhost`` or ``::1`` is reachable only from this machine and
needs no token. Bound anywhere else (0.0.0.0, a LAN address, even 127.0.0.2) every request and
every socket must carry the token printed at start: as ``?token=`` (the printed address has it;
the page then keeps it in a same-site cookie so its own scripts and socket carry it) or as an
``Authorization: Bearer`` header. Independently of the token, a request that changes something
(POST, PUT, DELETE) and every WebSocket must come from the page itself: an ``Origin`` header,
when a browser sends one, must name this server, so another site open in the same browser can
neither drive the robot nor read the stream.

Every request and socket must also name this server in its ``Host`` header: the bound address
and port (for a loopback bind also ``localhost`` and ``[::1]``), or a name given with
``--allow-host``. Without that, a page on any site could rebind its own name to 127.0.0.1 (DNS
rebinding) and become "this server" to the browser: its requests would carry its own name as
Host and as Origin, which agree with each other, but not with the names allowed here.
"""

from __future__ import annotations

import hmac
import secrets
from collections.abc import Mapping
from dataclasses import dataclass
from urllib.parse import urlsplit

LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "::1")
COOKIE = "stuart_bt_token"
CHANGING = ("POST", "PUT", "PATCH", "DELETE")


def needs_token(host: str) -> bool:
    return host not in LOOPBACK_HOSTS


def allowed_hosts(host: str, port: int, extra: tuple[str, ...] = ()) -> frozenset[str]:
    """The ``Host`` header values that name a server bound to ``host``:``port`` (lower case)."""
    names = {host, *extra}
    if host in LOOPBACK_HOSTS:
        names |= set(LOOPBACK_HOSTS)
    return frozenset(f"[{n}]:{port}" if ":" in n else f"{n}:{port}" for n in (name.lower() for name in names))


@dataclass
class Guard:
    """The checks for one server; ``token`` is None on loopback; ``hosts`` the Host values that
    name it (None: not checked, for an app embedded behind a proxy that checks them)."""

    token: str | None
    hosts: frozenset[str] | None = None

    @classmethod
    def for_host(cls, host: str, port: int | None = None, extra: tuple[str, ...] = ()) -> Guard:
        hosts = allowed_hosts(host, port, extra) if port is not None else None
        return cls(secrets.token_urlsafe(24) if needs_token(host) else None, hosts)

    def host_ok(self, headers: Mapping[str, str]) -> bool:
        """The request names this server (DNS rebinding closed), or no list of names is kept."""
        return self.hosts is None or headers.get("host", "").lower() in self.hosts

    def token_ok(self, query: Mapping[str, str], headers: Mapping[str, str], cookies: Mapping[str, str]) -> bool:
        if self.token is None:
            return True
        auth = headers.get("authorization", "")
        offered = [query.get("token", ""), cookies.get(COOKIE, ""),
                   auth[7:] if auth.lower().startswith("bearer ") else ""]
        return any(o and hmac.compare_digest(o.encode(), self.token.encode()) for o in offered)

    def origin_ok(self, headers: Mapping[str, str], scheme: str = "http") -> bool:
        """No Origin (not a browser, or a same-origin GET) passes; otherwise it must name this
        server: one of its allowed names, never merely whatever Host the client sent."""
        origin = headers.get("origin")
        if origin is None:
            return True
        parts = urlsplit(origin)
        if parts.scheme not in (scheme, scheme.replace("ws", "http")):
            return False
        if self.hosts is None:
            return parts.netloc.lower() == headers.get("host", "").lower()
        return parts.netloc.lower() in self.hosts
