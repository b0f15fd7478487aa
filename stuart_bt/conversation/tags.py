"""Gesture tags in a model's reply: ``"Hello! [wave]"`` -> ("Hello!", ["high wave"]).

A reply may carry tags naming gestures of :mod:`stuart_bt.core.gestures` (any accepted spelling or
alias: ``[wave]``, ``[high_five]``, ``[Shake Hands]``). The spoken text never contains tags;
unknown tags are dropped. The gestures are *kept only when the exchange is social*: a robot that
waves while explaining where the bathroom is looks odd, and small models add tags everywhere.

The social classifier (:func:`is_social`) is deterministic keyword rules, no model:

- the **user text** is social when it greets ("hi", "hello", "good morning"), thanks, says
  goodbye, pays a compliment ("you're great", "nice job", "I like you") or makes small talk
  ("how are you", "what's your name", "nice to meet you", "who are you");
- or the **reply** *opens* with a greeting, thanks or goodbye ("Hello!", "Thank you", "Goodbye",
  "You're welcome", "Nice to meet you").

Anything else (a question about the lab, what the robot sees, ...) is not social and its tags
are stripped.
"""

from __future__ import annotations

import re

from ..core.gestures import lookup

_TAG = re.compile(r"\[\s*([^\[\]\n]{1,40}?)\s*\]")
_SPACE = re.compile(r"[ \t]+")
_BEFORE_PUNCT = re.compile(r"\s+([.,!?;:])")

_GREETING = r"hi|hiya|hello|hey|howdy|greetings|good (?:morning|afternoon|evening)|welcome"
_THANKS = r"thanks?(?: you)?|thank you|cheers|much appreciated|you'?re welcome|my pleasure"
_GOODBYE = r"bye|goodbye|good ?bye|see you|see ya|farewell|good night|take care|have a (?:nice|good|great) day"
_COMPLIMENT = (r"you(?:'re| are) (?:so |very |really )?(?:great|awesome|amazing|cool|cute|nice|smart|clever|"
               r"the best|funny|wonderful|impressive)|(?:nice|good|great) (?:job|work)|well done|"
               r"i (?:like|love) you|love you|you rock|cool robot")
_SMALL_TALK = (r"how are you|how(?:'s| is) it going|how do you do|what(?:'s| is) your name|who are you|"
               r"nice to meet you|pleased to meet you|how(?:'s| is) your day|are you (?:happy|ok|okay|alright)|"
               r"do you like|what do you like|tell me (?:a joke|about yourself)|what'?s up|sup")
_USER_SOCIAL = re.compile(rf"\b(?:{_GREETING}|{_THANKS}|{_GOODBYE}|{_COMPLIMENT}|{_SMALL_TALK})\b", re.IGNORECASE)
_REPLY_OPENS_SOCIAL = re.compile(
    rf"^\W*(?:{_GREETING}|{_THANKS}|{_GOODBYE}|nice to meet you|pleased to meet you|glad to meet you)\b",
    re.IGNORECASE)


def is_social(user_text: str, reply_text: str = "") -> bool:
    """Whether the exchange is social (greeting, thanks, goodbye, compliment, small talk)."""
    return bool(_USER_SOCIAL.search(user_text) or _REPLY_OPENS_SOCIAL.match(reply_text))


def parse_tags(reply: str) -> tuple[str, list[str]]:
    """The reply without any ``[...]`` tag, and the canonical names of the known gestures tagged
    (in order, without repeats). Unknown tags are removed from the text all the same."""
    gestures: list[str] = []
    for match in _TAG.finditer(reply):
        gesture = lookup(match.group(1))
        if gesture is not None and gesture.name not in gestures:
            gestures.append(gesture.name)
    text = _TAG.sub(" ", reply).replace("[", " ").replace("]", " ")
    text = _BEFORE_PUNCT.sub(r"\1", _SPACE.sub(" ", text))
    return "\n".join(line.strip() for line in text.strip().splitlines() if line.strip()), gestures


_ABBREVIATION = re.compile(r"\b(Dr|Mr|Mrs|Ms|Prof|St|Jr|Sr|vs|etc|e\.g|i\.e)\.", re.IGNORECASE)
_HIDDEN_DOT = "\u2024"  # stands in for an abbreviation's dot while sentences are split
_SENTENCE = re.compile(r"[^.!?]*[.!?]+(?:[\"')\]]*)|[^.!?]+$")


def speakable(text: str, max_sentences: int = 2) -> str:
    """At most ``max_sentences`` sentences on one line, and no unfinished last sentence when a
    finished one exists: small models ramble and stop mid-word at ``max_tokens``, and a robot
    should neither lecture nor trail off."""
    flat = _ABBREVIATION.sub(lambda m: m.group(1) + _HIDDEN_DOT, " ".join(text.split()))
    sentences = [m.group(0).strip().replace(_HIDDEN_DOT, ".") for m in _SENTENCE.finditer(flat) if m.group(0).strip()]
    finished = [s for s in sentences if s[-1] in ".!?\"')]"]
    kept = (finished or sentences)[:max_sentences] if max_sentences > 0 else sentences
    return " ".join(kept)


def postprocess(user_text: str, reply: str, max_sentences: int = 2) -> tuple[str, list[str]]:
    """(spoken text, gestures): tags always leave the text, which is cut to ``max_sentences``
    sentences (0: no cut); gestures stay only when the exchange is social."""
    text, gestures = parse_tags(reply)
    text = speakable(text, max_sentences)
    return text, (gestures if is_social(user_text, text) else [])
