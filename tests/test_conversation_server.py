"""The OpenAI-compatible backend against llama-cpp-python's own server on loopback
(``python -m llama_cpp.server``, the ``server`` extra), serving the tiny SmolLM2 GGUF."""

from __future__ import annotations

import importlib.util
import json
import socket
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator

import pytest

from stuart_bt.conversation import make_conversation
from stuart_bt.conversation.openai_http import UNAVAILABLE, OpenAIConversation, normalise_base_url

SERVER_PACKAGES = ("llama_cpp", "fastapi", "uvicorn", "sse_starlette", "starlette_context", "pydantic_settings")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _ready(url: str) -> bool:
    try:
        with urllib.request.urlopen(f"{url}/models", timeout=1) as response:
            return bool(json.load(response).get("data"))
    except OSError:
        return False


@pytest.fixture(scope="module")
def server_url() -> Iterator[str]:
    absent = [p for p in SERVER_PACKAGES if importlib.util.find_spec(p) is None]
    if absent:
        reason = f"llama_cpp.server cannot start: missing {', '.join(absent)} (pip install 'stuart-bt[llm]')"
        print(reason)
        pytest.skip(reason)
    from stuart_bt.conversation.llama import default_model_path

    port = _free_port()
    process = subprocess.Popen(
        [sys.executable, "-m", "llama_cpp.server", "--model", str(default_model_path()), "--host", "127.0.0.1",
         "--port", str(port), "--n_ctx", "2048", "--verbose", "False"],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    url = f"http://127.0.0.1:{port}/v1"
    try:
        deadline = time.monotonic() + 30
        while not _ready(url):
            if process.poll() is not None:
                raise RuntimeError(f"llama_cpp.server exited: {process.stderr.read().decode()[-500:]}")
            if time.monotonic() > deadline:
                raise TimeoutError("llama_cpp.server not ready in 30 s")
            time.sleep(0.2)
        yield url
    finally:
        process.terminate()
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


def test_reply_from_the_server(server_url: str) -> None:
    conversation = make_conversation("openai", base_url=server_url, model="smollm2", timeout=30, max_tokens=40)
    reply = conversation.reply("Hello! What is this place?", {"at": "entrance"})
    assert reply.text and reply.text != UNAVAILABLE and "[" not in reply.text, conversation.last_error
    assert 0 < conversation.last_timing["first_token_s"] <= conversation.last_timing["total_s"]
    assert len(conversation.history) == 2


def test_streamed_and_whole_replies_agree(server_url: str) -> None:
    kwargs = {"max_tokens": 24, "temperature": 0.0, "seed": 3}
    streamed = OpenAIConversation(server_url, "smollm2", stream=True, **kwargs)
    whole = OpenAIConversation(server_url, "smollm2", stream=False, **kwargs)
    assert streamed.reply("Where is the kitchen?", {}) == whole.reply("Where is the kitchen?", {})
    assert streamed.last_raw == whole.last_raw and streamed.last_raw


def test_server_side_tags_are_post_processed(server_url: str) -> None:
    conversation = OpenAIConversation(server_url, "smollm2", max_tokens=16, temperature=0.0)
    conversation.history._messages = [{"role": "user", "content": "Hi there!"},
                                      {"role": "assistant", "content": "Hello there! [wave]"}]
    reply = conversation.reply("Good morning!", {})
    assert "[" not in reply.text
    if "[" in conversation.last_raw:  # the tiny model copied the tag: a greeting keeps it
        assert reply.gestures


def test_unreachable_server_gives_an_apology_not_an_exception() -> None:
    conversation = OpenAIConversation(f"http://127.0.0.1:{_free_port()}", timeout=2)
    assert conversation.reply("hello", {}).text == UNAVAILABLE
    assert conversation.last_error and "cannot reach LLM server" in conversation.last_error
    assert len(conversation.history) == 0


def test_base_url_normalisation() -> None:
    assert normalise_base_url("http://127.0.0.1:8080") == "http://127.0.0.1:8080/v1"
    assert normalise_base_url("http://localhost:11434/v1/") == "http://localhost:11434/v1"
    assert normalise_base_url("https://example.org/api/v1") == "https://example.org/api/v1"


def test_unknown_backend_is_refused() -> None:
    with pytest.raises(ValueError, match="unknown conversation backend"):
        make_conversation("gpt9")
    assert make_conversation("none").reply("hi", {}).text


def test_a_task_proposal_from_the_server_has_the_schema_s_shape(server_url: str) -> None:
    from stuart_bt.mission import proposals

    conversation = OpenAIConversation(server_url, "smollm2", timeout=60)
    raw = conversation.propose(proposals.messages("wave at me please", ["kitchen"], ["cup"], ["wave", "clap"]),
                               proposals.schema(("gesture", "navigate_to_marker")))
    intents = proposals.parse(raw, ("gesture", "navigate_to_marker"))
    assert intents is not None and {i.action for i in intents} <= {"gesture", "navigate_to_marker"}, raw
