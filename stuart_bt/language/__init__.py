"""Voice commands: what people say to Stuart -> TaskIntents for the planner.

Pipeline (docs/voice.md)::

    utterance --WakeFilter--> command text --Grammar--> [TaskIntent, ...] --Resolver--> markers / objects

- :mod:`.wake`: "Hey Stuart" and what speech recognisers make of it (phonetic matching);
- :mod:`.numbers`: spoken numbers and quantities ("one and a half metres", "a quarter turn");
- :mod:`.grammar`: deterministic command grammar for the eight intents, compounds, politeness,
  and telling commands from conversation;
- :mod:`.intents`: TaskIntent, its JSON, and the spoken confirmation;
- :mod:`.parse`: the whole utterance -> ParseResult (the CLI's JSON contract);
- :mod:`.resolve`: spoken targets -> marker names / object labels, or why not;
- :mod:`.cli`: ``stuart-bt parse``.
"""

from .compiled import use_source_when_stale

use_source_when_stale()  # before the first grammar module is imported

from .grammar import Defaults, Grammar, parse_command  # noqa: E402
from .intents import ACTIONS, TaskIntent, confirmation  # noqa: E402
from .parse import Parser, ParseResult, parse  # noqa: E402
from .resolve import Resolution, Resolver  # noqa: E402
from .wake import WakeFilter, WakeMatch  # noqa: E402

__all__ = [
    "ACTIONS", "Defaults", "Grammar", "ParseResult", "Parser", "Resolution", "Resolver", "TaskIntent",
    "WakeFilter", "WakeMatch", "confirmation", "parse", "parse_command",
]
