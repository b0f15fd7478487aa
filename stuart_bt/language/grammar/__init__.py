"""The command grammar, one module per job (bottom first): :mod:`.lexicon` (the words, as data),
:mod:`.tokens` (text to tokens), :mod:`.state` (one parse's state), :mod:`.nouns` and
:mod:`.amounts` (noun phrases, distances and angles), one reader module per verb family
(:mod:`.gestures`, :mod:`.finding`, :mod:`.stopping`, :mod:`.motion`, :mod:`.picking`,
:mod:`.light_verbs`), :mod:`.clauses` (openers, verbless clauses, connectors) and :mod:`.driver` (the
:class:`Grammar` that reads a whole command). See :mod:`.driver` for what the grammar accepts
and why it is rule-based."""

from .driver import Grammar, parse_command
from .state import Defaults
from .tokens import Tokens, tokenize

__all__ = ["Defaults", "Grammar", "Tokens", "parse_command", "tokenize"]
