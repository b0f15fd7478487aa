"""``make_conversation(kind, **options)``: one place that maps a backend name to an object, so
the CLI and the mission executor need only a string and a few options."""

from __future__ import annotations

from typing import Any

from .reply import CannedConversation, Conversation

KINDS = ("none", "llama", "openai")


def make_conversation(kind: str = "none", **options: Any) -> Conversation:
    """``none`` -> :class:`CannedConversation` (options ignored); ``llama`` ->
    :class:`~.llama.LlamaConversation` (``model_path``, ``n_ctx``, ``max_tokens``, ``temperature``,
    ``seed``, ...); ``openai`` -> :class:`~.openai_http.OpenAIConversation` (``base_url``, ``model``,
    ``api_key``, ``timeout``, ...). Options that are ``None`` are left at the backend's default.
    Backends import lazily: ``none`` needs no LLM package."""
    options = {k: v for k, v in options.items() if v is not None}
    if kind == "none":
        return CannedConversation()
    if kind == "llama":
        from .llama import LlamaConversation
        return LlamaConversation(**options)
    if kind == "openai":
        from .openai_http import OpenAIConversation
        return OpenAIConversation(**options)
    raise ValueError(f"unknown conversation backend {kind!r} (choose from {', '.join(KINDS)})")
