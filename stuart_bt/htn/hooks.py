"""Python hooks: named functions a YAML domain calls when an expression would be too awkward.

Two kinds, both ``fn(state, **params)``:

- **conditions** return a bool (``pre: [{hook: known_gesture, args: {name: name}}]``); a false
  result rejects the method or primitive, and the explanation names the hook and its arguments;
- **functions** return a value for skill arguments or effects (``args: {hook: standoff_args,
  args: {obj: obj}}``): trigonometry, look-ups through two tables, anything that is not a
  one-line expression.

Hooks are registered on a :class:`HookRegistry` that the caller hands to the domain loader; a
domain file only names them, so loading a YAML file never imports or runs code it chose. Hooks
must not change the state they are given: the planner predicts effects only through a
primitive's declared ``effects``.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

HOOK_KINDS = ("condition", "function")


@dataclass(frozen=True)
class Hook:
    """One registered hook and what the loader needs to check calls to it."""

    name: str
    kind: str  # "condition" | "function"
    fn: Callable[..., Any]
    params: tuple[str, ...]  # keyword parameters after ``state``
    required: tuple[str, ...]  # those without a default
    accepts_any: bool  # has **kwargs
    doc: str = ""

    def __call__(self, state: Any, **params: Any) -> Any:
        return self.fn(state, **params)


@dataclass
class HookRegistry:
    """Named hooks; ``@registry.condition`` and ``@registry.function`` register a function
    under its own name (or ``name=``)."""

    hooks: dict[str, Hook] = field(default_factory=dict)

    def condition(self, fn: Callable[..., Any] | None = None, *, name: str | None = None) -> Any:
        return self._decorator("condition", fn, name)

    def function(self, fn: Callable[..., Any] | None = None, *, name: str | None = None) -> Any:
        return self._decorator("function", fn, name)

    def register(self, kind: str, fn: Callable[..., Any], name: str | None = None) -> Hook:
        if kind not in HOOK_KINDS:
            raise ValueError(f"hook kind must be one of {HOOK_KINDS}, not {kind!r}")
        hook = _describe(kind, fn, name or fn.__name__)
        if hook.name in self.hooks:
            raise ValueError(f"hook {hook.name!r} is registered twice")
        self.hooks[hook.name] = hook
        return hook

    def get(self, name: str) -> Hook | None:
        return self.hooks.get(name)

    def names(self, kind: str | None = None) -> list[str]:
        return [n for n, h in self.hooks.items() if kind is None or h.kind == kind]

    def merged(self, other: HookRegistry) -> HookRegistry:
        """A registry with both sets of hooks (``other`` may not redefine a name)."""
        out = HookRegistry(dict(self.hooks))
        for name, hook in other.hooks.items():
            if name in out.hooks:
                raise ValueError(f"hook {name!r} is registered twice")
            out.hooks[name] = hook
        return out

    def __contains__(self, name: object) -> bool:
        return name in self.hooks

    def _decorator(self, kind: str, fn: Callable[..., Any] | None, name: str | None) -> Any:
        if fn is not None:
            self.register(kind, fn, name)
            return fn

        def wrap(f: Callable[..., Any]) -> Callable[..., Any]:
            self.register(kind, f, name)
            return f

        return wrap


def _describe(kind: str, fn: Callable[..., Any], name: str) -> Hook:
    """Read the signature once, so the loader can check every call in the YAML against it."""
    try:
        sig = inspect.signature(fn)
    except (TypeError, ValueError):
        raise ValueError(f"hook {name!r}: cannot read its signature") from None
    params = list(sig.parameters.values())
    if not params or params[0].kind not in (inspect.Parameter.POSITIONAL_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD):
        raise ValueError(f"hook {name!r} must take the state as its first argument")
    keyword = (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)
    named = [p for p in params[1:] if p.kind in keyword]
    required = tuple(p.name for p in named if p.default is inspect.Parameter.empty)
    accepts_any = any(p.kind is inspect.Parameter.VAR_KEYWORD for p in params)
    doc = (inspect.getdoc(fn) or "").split("\n\n")[0]
    return Hook(name, kind, fn, tuple(p.name for p in named), required, accepts_any, doc)
