"""Conversation backends for the mission executor: a persona + lab-knowledge prompt, gesture
tags kept only for social replies, and three backends behind one factory (docs/conversation.md).

Only light modules are imported here; the llama backend loads llama-cpp-python when made.
"""

from __future__ import annotations

from .factory import KINDS, make_conversation
from .prompt import HISTORY_LIMIT, History, build_messages, is_vision_question
from .tags import is_social, parse_tags, postprocess

__all__ = ["HISTORY_LIMIT", "KINDS", "History", "build_messages", "is_social", "is_vision_question",
           "make_conversation", "parse_tags", "postprocess"]
