"""Gesture tags: parsed against the gesture library, unknown ones dropped, never spoken, and
kept only when the exchange is social."""

from __future__ import annotations

import pytest

from stuart_bt.conversation.tags import is_social, parse_tags, postprocess, speakable

SOCIAL = ["Hello!", "hi there", "Good morning Stuart", "thanks a lot", "Thank you so much", "bye for now",
          "see you later", "you're awesome", "nice job on the tour", "how are you?", "what's your name",
          "nice to meet you", "I love you robot"]
NOT_SOCIAL = ["Where is the kitchen?", "What do you see?", "Who is the lab director?",
              "How tall are you?", "Tell me about the drone cage", "what is this thing"]


@pytest.mark.parametrize("raw, text, gestures", [
    ("Hello! [wave]", "Hello!", ["high wave"]),
    ("[high_five] Nice one!", "Nice one!", ["high five"]),
    ("Hi [Shake Hands] and [clap]!", "Hi and!", ["shake hand", "clap"]),
    ("Hello [dance] there [wave] [wave]", "Hello there", ["high wave"]),  # unknown dropped, repeats once
    ("No tags at all.", "No tags at all.", []),
    ("Broken [wave tag", "Broken wave tag", []),  # a stray bracket is not spoken either
    ("[26] Hi", "Hi", ["high wave"]),  # vendor ids are gesture names too
])
def test_parse_tags(raw: str, text: str, gestures: list[str]) -> None:
    assert parse_tags(raw) == (text, gestures)


@pytest.mark.parametrize("user", SOCIAL)
def test_social_keeps_gestures(user: str) -> None:
    assert is_social(user)
    text, gestures = postprocess(user, "Hello, nice to see you! [wave]")
    assert gestures == ["high wave"] and "[" not in text and "wave" not in text


@pytest.mark.parametrize("user", NOT_SOCIAL)
def test_not_social_strips_gestures(user: str) -> None:
    assert not is_social(user, "The kitchen is past the robot arms.")
    text, gestures = postprocess(user, "The kitchen is past the robot arms. [wave]")
    assert (text, gestures) == ("The kitchen is past the robot arms.", [])


def test_a_reply_that_opens_socially_is_social() -> None:
    assert is_social("I am going now", "Goodbye, come back soon!")
    assert postprocess("ok that's all", "Thank you for visiting! [face wave]")[1] == ["face wave"]
    assert not is_social("ok that's all", "The tour is over.")


def test_speakable_keeps_two_finished_sentences() -> None:
    assert speakable("One. Two! Three? Four") == "One. Two!"
    assert speakable("The kitchen is there.\n\nThe kit") == "The kitchen is there."
    assert speakable("no full stop") == "no full stop"
    assert speakable("Dr. Lopez runs the lab. She walks. Robots too.") == "Dr. Lopez runs the lab. She walks."
    assert speakable("A. B. C.", max_sentences=0) == "A. B. C."
