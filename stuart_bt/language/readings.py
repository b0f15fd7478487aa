"""Which of a recogniser's readings of one utterance to act on.

A recogniser's best reading is the likeliest *text*, not the likeliest *command*: beam search
keeps several readings of the same sound, and the best one is often a near miss of what the
robot can do ("head to it, go to the 3D printers", "could you go turn the kitchen") while the
next one, a hair less likely, is the command itself. So when the best reading is not a clear
command, a reading that is one, and whose average log probability trails the best by no more
than ``margin``, is taken instead. A clear command is addressed to the robot (the wake phrase),
gives intents, and every target it names resolves on the map or among the objects and gestures.
The margin keeps the sound in charge: a reading far less likely than the best is never chosen
because it would be convenient, and talk stays talk (a non-command's other readings are its
own words, rarely a clear command within the margin; the hearing benchmark counts any).
A reading within the margin that greets someone else by name ("hey Sarah, ..." beside "hey
Stuart, ...") is a rival too: the robot asks whether it was meant.

Readings the robot does not act on for a task may still make it safer, never move it: within
:data:`ADDRESSEE_MARGIN` of the best, one greeting someone else makes it ask, and one that only
stops it ("Stewart, stop." behind "do it, stop." in noise) stops it. A stop is never unsafe, and a
stop missed is the one mishearing that can hurt someone.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from .wake import GREETINGS

if TYPE_CHECKING:
    from .parse import Parser, ParseResult
    from .resolve import Resolver

READING_MARGIN = 0.15  # average log probability per token a command reading may trail the best by
# how far a reading greeting someone else by name may trail the chosen one and still make the robot
# ask: a recogniser primed with the robot's name ranks it first (measured, docs/hearing.md: "hey
# Sarah, ..." trailed "hey Stuart, ..." by 0.17 in whisper's own readings)
ADDRESSEE_MARGIN = 0.5
# how far a reading that only stops the robot may trail the best and still be acted on: as far as one
# that makes it ask (both only make the robot safer)
STOP_MARGIN = ADDRESSEE_MARGIN


def is_clear_command(text: str, parser: Parser, resolver: Resolver) -> bool:
    """Addressed to the robot, with intents, no doubt, every target resolved."""
    return _clear(parser.parse(text), resolver)


def _clear(result: ParseResult, resolver: Resolver) -> bool:
    """:func:`is_clear_command` of a text already parsed."""
    if not result.wake or not result.intents or result.doubt:
        return False
    return all(r is None or r.ok for r in resolver.resolve_all(result.intents))


def choose_reading(readings: Sequence[tuple[str, float]], parser: Parser, resolver: Resolver,
                   margin: float = READING_MARGIN) -> int:
    """Index into ``readings`` ((text, average log probability), best first) of the one to act
    on: the best, unless it is no clear command and a reading within ``margin`` of it is, or
    else one within :data:`STOP_MARGIN` that only stops the robot."""
    if len(readings) < 2 or is_clear_command(readings[0][0], parser, resolver):
        return 0
    best = readings[0][1]
    for index, (text, score) in enumerate(readings[1:], 1):
        if score < best - margin:
            break
        if is_clear_command(text, parser, resolver):
            return index
    return _only_a_stop(readings, best - STOP_MARGIN, parser, resolver)


def _only_a_stop(readings: Sequence[tuple[str, float]], least: float, parser: Parser, resolver: Resolver) -> int:
    """Index of the first reading scored at least ``least`` that is a clear command to stop and
    nothing else ("Stewart, stop."); 0 when none is."""
    for index, (text, score) in enumerate(readings[1:], 1):
        if score < least:
            continue
        result = parser.parse(text)
        if _clear(result, resolver) and all(i.action == "stop" for i in result.intents):
            return index
    return 0


def rival_reading(readings: Sequence[tuple[str, float]], chosen: int, parser: Parser, resolver: Resolver,
                  margin: float = READING_MARGIN) -> int | None:
    """Index of another reading, within ``margin`` of the chosen one, that is a clear command
    asking for something else ("go to the kitchen" / "go to the bathroom"), or within
    :data:`ADDRESSEE_MARGIN` one that greets someone else by name (then even a chosen reading the
    robot would only ask about, "hey Stuart, pick up the remote", was maybe not said to it): the
    robot heard two things and should ask which. None when the chosen reading has no such rival."""
    if len(readings) < 2:
        return None
    said = readings[chosen][0]
    clear = is_clear_command(said, parser, resolver)
    if not clear and not parser.parse(said).intents:
        return None
    mine = _asked(said, parser, resolver) if clear else []
    for index, (text, score) in enumerate(readings):
        behind = abs(score - readings[chosen][1])
        if index == chosen or behind > max(margin, ADDRESSEE_MARGIN):
            continue
        if clear and behind <= margin and is_clear_command(text, parser, resolver) and (
                _asked(text, parser, resolver) != mine):
            return index
        if _greets_someone_else(text, parser):  # "hey Stuart, ..." or "hey Sarah, ...": who was it said to?
            return index
    return None


def _greets_someone_else(text: str, parser: Parser) -> bool:
    """A greeting and then a name that is not the robot's, written as a name ("hey Sarah, pick up
    the book"): a recogniser primed with the robot's name hears it as the robot's too."""
    words = text.split(maxsplit=2)
    return (len(words) > 1 and words[0].strip(",.!").lower() in GREETINGS and words[1][:1].isupper()
            and not parser.parse(text).wake)


def _asked(text: str, parser: Parser, resolver: Resolver) -> list[tuple[str, str, float, float, float]]:
    """What a reading asks the robot to do, its targets as they resolve: "the Humanoids corner"
    and "the Humanoid corner", or "this crew driver" and "the screwdriver", ask for the same
    thing, so two readings that differ only so are no rivals."""
    intents = parser.parse(text).intents
    asked = []
    for intent, resolved in zip(intents, resolver.resolve_all(intents), strict=True):
        name = resolved.name if resolved is not None and resolved.ok else intent.target
        asked.append((intent.action, name or "", round(intent.x, 2), round(intent.y, 2), round(intent.yaw, 2)))
    return asked
