"""The utterance parser on anything a recogniser, a typist or a fuzzer can produce: it never
raises, its result is strict JSON, and without a wake phrase nothing becomes an intent."""

from __future__ import annotations

import json

from hypothesis import given, settings
from hypothesis import strategies as st

from stuart_bt.language.parse import Parser

PARSER = Parser()
WORDS = ["go", "to", "the", "kitchen", "turn", "left", "right", "stop", "continue", "pick", "up", "bottle",
         "and", "then", "metres", "degrees", "minus", "1e999", "nan", "inf", "-5", "0.5", "?", ",", "!", "don't",
         "if", "wave", "find", "please", "Stuart", "Stewart", "hey", "hi", "\u00e9", "\u202e", "\x00", "\ud800"]
SPOKEN = st.lists(st.sampled_from(WORDS), max_size=40).map(" ".join)


@settings(max_examples=400, deadline=None)
@given(st.text(max_size=300) | SPOKEN)
def test_any_text_parses_to_strict_json_without_raising(text: str):
    result = PARSER.parse(text)
    json.loads(result.to_json(), parse_constant=lambda name: (_ for _ in ()).throw(AssertionError(name)))


@settings(max_examples=400, deadline=None)
@given(SPOKEN.filter(lambda t: not PARSER.parse(t).wake))
def test_nothing_said_without_the_wake_phrase_becomes_an_intent(text: str):
    assert PARSER.parse(text).intents == []
