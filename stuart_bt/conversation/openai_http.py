"""The remote backend: any server speaking the OpenAI chat-completions HTTP API (llama.cpp's
``llama-server`` or ``python -m llama_cpp.server``, Ollama, vLLM), with the standard library only.

``base_url`` is the API root, e.g. ``http://127.0.0.1:8080/v1`` (a URL with no path gets ``/v1``).
Replies are streamed (server-sent events) by default so the time to first token is known; set
``stream=False`` for servers that do not stream. A server that cannot be reached or answers with
an error does not raise out of :meth:`OpenAIConversation.reply`: the robot says it cannot think
right now (``last_error`` keeps why), because the executor has no one to hand the exception to.
"""

from __future__ import annotations

import json
import threading
import time
import urllib.error
import urllib.parse
import urllib.request
from collections.abc import Iterator, Mapping
from typing import Any

from ..core.errors import StuartError
from .prompt import HISTORY_LIMIT, History, build_messages
from .reply import Reply
from .streaming import collect_timed
from .tags import postprocess

UNAVAILABLE = "Sorry, I can't think of an answer right now."


class ServerError(StuartError, RuntimeError):
    """The server could not be reached or answered with an error."""


def normalise_base_url(base_url: str) -> str:
    """``http://host:port`` -> ``http://host:port/v1``; a URL with a path is kept (minus a final /)."""
    url = base_url.rstrip("/")
    return url + "/v1" if urllib.parse.urlparse(url).path in ("", "/") else url


class OpenAIConversation:
    """A :class:`~stuart_bt.mission.commands.Conversation` over the OpenAI chat-completions API."""

    name = "openai"

    def __init__(self, base_url: str = "http://127.0.0.1:8080/v1", model: str = "default", *,
                 api_key: str | None = None, timeout: float = 30.0, max_tokens: int = 64,
                 temperature: float = 0.7, seed: int | None = 0, stream: bool = True,
                 knowledge: Mapping[str, Any] | None = None, extra_system: str = "",
                 history_limit: int = HISTORY_LIMIT, max_sentences: int = 2) -> None:
        self.base_url, self.model, self.api_key, self.timeout = normalise_base_url(base_url), model, api_key, timeout
        self.max_tokens, self.temperature, self.seed, self.streaming = max_tokens, temperature, seed, stream
        self.knowledge, self.extra_system = knowledge, extra_system
        self.history = History(history_limit)
        self.max_sentences = max_sentences
        self.last_timing: dict[str, float] = {}
        self.last_raw = ""
        self.last_error: str | None = None
        self._lock = threading.Lock()

    # -- HTTP -----------------------------------------------------------------------------------------
    def _request(self, messages: list[dict[str, str]], stream: bool, **extra: Any) -> Any:
        body: dict[str, Any] = {"model": self.model, "messages": messages, "max_tokens": self.max_tokens,
                                "temperature": self.temperature, "stream": stream, **extra}
        if self.seed is not None:
            body["seed"] = self.seed
        headers = {"Content-Type": "application/json", "Accept": "text/event-stream" if stream else "application/json"}
        if self.api_key:
            headers["Authorization"] = f"Bearer {self.api_key}"
        request = urllib.request.Request(f"{self.base_url}/chat/completions", data=json.dumps(body).encode(),
                                         headers=headers, method="POST")
        try:
            return urllib.request.urlopen(request, timeout=self.timeout)
        except urllib.error.HTTPError as exc:
            detail = exc.read(300).decode("utf-8", "replace").strip()
            raise ServerError(f"LLM server {self.base_url} answered HTTP {exc.code}: {detail}") from exc
        except (urllib.error.URLError, OSError) as exc:
            raise ServerError(f"cannot reach LLM server at {self.base_url}: {getattr(exc, 'reason', exc)}") from exc

    def stream(self, messages: list[dict[str, str]]) -> Iterator[str]:
        """Text chunks as the server sends them (``data: {...}`` lines up to ``data: [DONE]``)."""
        try:
            with self._request(messages, stream=True) as response:
                for line in response:
                    line = line.strip()
                    if not line.startswith(b"data:"):
                        continue
                    data = line[5:].strip()
                    if data == b"[DONE]":
                        return
                    choices = json.loads(data).get("choices") or [{}]
                    piece = (choices[0].get("delta") or {}).get("content")
                    if piece:
                        yield piece
        except (OSError, TimeoutError) as exc:  # a connection that dies mid-stream
            raise ServerError(f"LLM server {self.base_url} stream broke: {exc}") from exc

    def propose(self, messages: list[dict[str, str]], schema: dict[str, Any]) -> str:
        """JSON held to ``schema`` by the server (``response_format`` with a schema: llama.cpp's
        server, vLLM and Ollama honour it), greedy; raises :class:`ServerError`."""
        with self._lock:
            return self._whole(messages, response_format={"type": "json_object", "schema": schema},
                               temperature=0.0, max_tokens=160)

    def _whole(self, messages: list[dict[str, str]], **extra: Any) -> str:
        with self._request(messages, stream=False, **extra) as response:
            data = json.load(response)
        return (data["choices"][0]["message"].get("content") or "").strip()

    def complete(self, messages: list[dict[str, str]]) -> str:
        """The raw reply to ``messages``, timed into ``last_timing``; raises :class:`ServerError`."""
        with self._lock:
            return self._complete(messages)

    def _complete(self, messages: list[dict[str, str]]) -> str:
        start = time.perf_counter()
        if not self.streaming:
            text = self._whole(messages)
            total = time.perf_counter() - start
            self.last_timing = {"first_token_s": total, "total_s": total}
            return text
        text, self.last_timing = collect_timed(self.stream(messages))
        return text

    # -- Conversation ---------------------------------------------------------------------------------
    def reply(self, text: str, context: dict[str, Any]) -> Reply:
        """One turn; a server failure gives a spoken apology (and ``last_error``), never an exception."""
        with self._lock:
            messages = build_messages(text, context, self.history.messages, knowledge=self.knowledge,
                                      extra_system=self.extra_system, history_limit=self.history.limit)
            try:
                raw = self.last_raw = self._complete(messages)
            except (ServerError, ValueError, KeyError) as exc:
                self.last_error = str(exc)
                return Reply(UNAVAILABLE)
            self.last_error = None
            spoken, gestures = postprocess(text, raw, self.max_sentences)
            spoken = spoken or "Sorry, I have nothing to say to that."
            self.history.add(text, spoken)
            return Reply(spoken, gestures)
