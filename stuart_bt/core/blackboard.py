"""The blackboard: named values the tree reads and writes, with the world state under ``world``.

One :class:`Blackboard` per executor (not py_trees' process-global one), so several trees can run
in one process (tests, the web view) without sharing keys by accident. Writes are published on
the event stream as ``blackboard`` events. Keys may be dotted (``visits.kitchen``) to reach into
nested dicts or the world state's attributes.

Parameter values in trees may refer to the blackboard: a whole value ``"$key"`` is replaced by
the key's value; inside text, ``${key}`` is replaced by its string form; ``$$`` is a literal ``$``.
"""

from __future__ import annotations

import re
import threading
from typing import Any

from .events import EventStream
from .expr import resolve_dotted
from .world import WorldState

REF = re.compile(r"^\$([A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z0-9_]+)*)$")
TEMPLATE = re.compile(r"\$\{([A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z0-9_]+)*)\}")
_MISSING = object()


class Blackboard:
    """``initial``: the tree's starting values. They are set quietly: when a blackboard is made,
    the log, the views and the bridge are not listening yet, so :meth:`publish_initial` tells them
    once they are (the session does it when it starts)."""

    def __init__(self, events: EventStream | None = None, initial: dict[str, Any] | None = None) -> None:
        self._data: dict[str, Any] = {"world": WorldState()}
        self._events = events
        self._lock = threading.RLock()
        self._initial = list(initial or {})
        for k, v in (initial or {}).items():
            self._write(k, v)

    @property
    def world(self) -> WorldState:
        return self._data["world"]

    def get(self, key: str, default: Any = _MISSING) -> Any:
        """Value of a (dotted) key; raises KeyError when absent and no default is given."""
        try:
            return resolve_dotted(self._data, key)
        except KeyError:
            if default is _MISSING:
                raise
            return default

    def __contains__(self, key: str) -> bool:
        try:
            resolve_dotted(self._data, key)
        except KeyError:
            return False
        return True

    def set(self, key: str, value: Any) -> None:
        self._write(key, value)
        if self._events is not None:
            self._events.publish("blackboard", key=key, value=value)

    def publish_initial(self) -> None:
        """Publish each initial key with its value now, as a write, for whoever listens now."""
        if self._events is None:
            return
        for key in self._initial:
            value = self.get(key, _MISSING)
            if value is not _MISSING:
                self._events.publish("blackboard", key=key, value=value)

    def _write(self, key: str, value: Any) -> None:
        with self._lock:
            head, *rest = key.split(".")
            if not rest:
                self._data[head] = value
            else:
                target = self._data.setdefault(head, {})
                for part in rest[:-1]:
                    target = target.setdefault(part, {}) if isinstance(target, dict) else getattr(target, part)
                if isinstance(target, dict):
                    target[rest[-1]] = value
                else:
                    setattr(target, rest[-1], value)

    def keys(self) -> list[str]:
        return list(self._data)

    def snapshot(self) -> dict[str, Any]:
        """A JSON-friendly copy of everything on the blackboard."""
        out: dict[str, Any] = {}
        for k, v in self._data.items():
            out[k] = v.to_dict() if hasattr(v, "to_dict") else v
        return out

    def resolve(self, value: Any) -> Any:
        """Replace ``$key`` references and ``${key}`` templates in a parameter value."""
        if isinstance(value, str):
            m = REF.match(value)
            if m:
                return self.get(m.group(1))
            if "$" in value:
                return render_template(value, self.get)
            return value
        if isinstance(value, list):
            return [self.resolve(v) for v in value]
        if isinstance(value, dict):
            return {k: self.resolve(v) for k, v in value.items()}
        return value


def render_template(text: str, lookup: Any) -> str:
    """Fill ``${key}`` from ``lookup(key)``; ``$$`` stays a single ``$``."""
    parts = text.split("$$")
    return "$".join(TEMPLATE.sub(lambda m: _text(lookup(m.group(1))), p) for p in parts)


def _text(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def is_reference(value: Any) -> bool:
    return isinstance(value, str) and bool(REF.match(value))


def template_names(value: Any) -> list[str]:
    return TEMPLATE.findall(value.replace("$$", "")) if isinstance(value, str) else []
