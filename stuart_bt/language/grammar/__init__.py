"""The command grammar, one module per job (bottom first): :mod:`.lexicon` (the words, as data),
:mod:`.tokens` (text to tokens), :mod:`.state` (one parse's state), :mod:`.nouns` and
:mod:`.amounts` (noun phrases, distances and angles), one reader module per verb family
(:mod:`.gestures`, :mod:`.finding`, :mod:`.stopping`, :mod:`.motion`, :mod:`.picking`,
:mod:`.light_verbs`), :mod:`.clauses` (openers, verbless clauses, connectors), :mod:`.forms` (question
tags, retractions), :mod:`.driver` (the :class:`Grammar` that reads a whole command) and
:mod:`.coverage` (which words it used). See :mod:`.driver` for what the grammar accepts and why
it is rule-based."""

from .coverage import Coverage, coverage
from .driver import Grammar, Reading, parse_command
from .state import Defaults
from .tokens import Tokens, tokenize

__all__ = ["Coverage", "Defaults", "Grammar", "Reading", "Tokens", "coverage", "parse_command",
           "tokenize"]
