"""What every leaf accepts: names, typed parameters, alternatives and default timeouts.

This table is the single source for load-time validation, the generated JSON Schema, the docs
and the leaves themselves. A skill leaf sends one command to the daemon of its ``family``;
built-in leaves (``condition``, ``set``, ``log``, ``wait``, ``stop``) run inside the executor.

Parameter types:

``string`` ``number`` ``integer`` ``boolean``  plain YAML scalars (integers are numbers too)
``seconds``  a number >= 0
``angle``    radians, counter-clockwise positive (REP-103)
``marker``   a name from the marker file, when one is configured
``gesture``  a name from :mod:`stuart_bt.core.gestures`
``gestures`` a list of such names
``path``     a file path, relative to the tree file
``choice``   one of ``Param.choices``
``expression`` a blackboard expression (:mod:`stuart_bt.core.expr`)
``any``      any YAML value

Any parameter may instead hold a blackboard reference ``$key`` resolved when the leaf starts.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

PARAM_TYPES = (
    "string", "number", "integer", "boolean", "seconds", "angle", "marker", "gesture",
    "gestures", "path", "choice", "expression", "any",
)

COMMON_PARAMS = ("name", "timeout")  # accepted by every leaf, composite and decorator where sensible


@dataclass(frozen=True)
class Param:
    name: str
    type: str
    doc: str
    required: bool = False
    default: Any = None
    choices: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        assert self.type in PARAM_TYPES, self.type


@dataclass(frozen=True)
class LeafSpec:
    """One leaf kind.

    ``one_of`` lists alternative parameter groups: exactly one group must be used, and inside
    it the params marked ``required`` must all be given. Params in no group are always allowed.
    ``shorthand`` names the param a bare scalar fills (``speak: "Hello"``).
    """

    name: str
    doc: str
    params: tuple[Param, ...] = ()
    family: str | None = None  # daemon family; None = runs inside the executor
    command: str | None = None  # daemon command name (defaults to the leaf name)
    shorthand: str | None = None
    one_of: tuple[tuple[str, ...], ...] = ()
    default_timeout: float = 60.0

    def param(self, name: str) -> Param | None:
        return next((p for p in self.params if p.name == name), None)

    @property
    def param_names(self) -> list[str]:
        return [p.name for p in self.params]


ARMS = ("auto", "left", "right")

LEAVES: dict[str, LeafSpec] = {
    s.name: s
    for s in (
        LeafSpec(
            "navigate",
            "Walk to a named marker, a map pose (x, y, yaw) or a body-relative offset (dx, dy, dyaw).",
            (
                Param("marker", "marker", "Marker name or display name from the marker file.", required=True),
                Param("x", "number", "Map x in metres.", required=True),
                Param("y", "number", "Map y in metres.", required=True),
                Param("yaw", "angle", "Map heading in radians; default keeps the arrival heading.", default=None),
                Param("dx", "number", "Metres forward (negative: back).", default=0.0),
                Param("dy", "number", "Metres to the left (negative: right).", default=0.0),
                Param("dyaw", "angle", "Radians to turn, counter-clockwise positive.", default=0.0),
                Param("tolerance", "number", "Arrival tolerance in metres.", default=0.10),
                Param("yaw_tolerance", "angle", "Arrival heading tolerance in radians.", default=0.0873),
            ),
            family="loco",
            shorthand="marker",
            one_of=(("marker",), ("x", "y", "yaw"), ("dx", "dy", "dyaw")),
            default_timeout=180.0,
        ),
        LeafSpec(
            "approach",
            "Walk up to a remembered object (or a map point) and stop with it within reach, facing "
            "it; the backend picks a free spot on its map.",
            (
                Param("object", "string", "Object label; its position is read from the world state when "
                      "the leaf starts.", required=True),
                Param("x", "number", "Map x of the point to face, metres.", required=True),
                Param("y", "number", "Map y of the point to face, metres.", required=True),
                Param("standoff", "number", "Metres the point ends up ahead of the robot's base (the G1's "
                      "arm reaches ~0.42 m from the shoulder).", default=0.29),
                Param("lateral", "number", "Metres the point ends up left of the robot's centre line "
                      "(negative: right); 0.1 puts it in front of a shoulder. The daemon may mirror it when "
                      "that side is blocked.", default=0.0),
                Param("tolerance", "number", "Arrival tolerance in metres.", default=0.10),
                Param("yaw_tolerance", "angle", "Arrival heading tolerance in radians.", default=0.0873),
            ),
            family="loco",
            command="navigate",
            shorthand="object",
            one_of=(("object",), ("x", "y")),
            default_timeout=180.0,
        ),
        LeafSpec(
            "view",
            "Walk to where the head camera sees a remembered object (or a map point): in its picture "
            "and range, with nothing on the map in between. It stays, or only turns, when it sees "
            "it from where it stands; an object in the middle of a table is looked at from its edge, "
            "with no arm's reach needed.",
            (
                Param("object", "string", "Object label; its position is read from the world state when "
                      "the leaf starts.", required=True),
                Param("x", "number", "Map x of the point to look at, metres.", required=True),
                Param("y", "number", "Map y of the point to look at, metres.", required=True),
                Param("z", "number", "Height of the point above the floor, metres.", default=0.0),
                Param("tolerance", "number", "Arrival tolerance in metres.", default=0.10),
                Param("yaw_tolerance", "angle", "Arrival heading tolerance in radians.", default=0.0873),
            ),
            family="loco",
            command="navigate",
            shorthand="object",
            one_of=(("object",), ("x", "y", "z")),
            default_timeout=180.0,
        ),
        LeafSpec(
            "turn",
            "Turn in place by an angle (radians, counter-clockwise positive) or by degrees.",
            (
                Param("angle", "angle", "Radians, counter-clockwise positive.", required=True),
                Param("degrees", "number", "Degrees, counter-clockwise positive.", required=True),
            ),
            family="loco",
            shorthand="angle",
            one_of=(("angle",), ("degrees",)),
            default_timeout=30.0,
        ),
        LeafSpec(
            "pick",
            "Pick up an object by its detector label.",
            (
                Param("object", "string", "Object label, e.g. 'bottle'.", required=True),
                Param("arm", "choice", "Which arm; 'auto' picks the closer one.", default="auto", choices=ARMS),
            ),
            family="pick",
            shorthand="object",
            default_timeout=90.0,
        ),
        LeafSpec(
            "release",
            "Put down what the robot holds.",
            (Param("arm", "choice", "Which arm; 'auto' releases whatever is held.", default="auto", choices=ARMS),),
            family="pick",
            shorthand="arm",
            default_timeout=60.0,
        ),
        LeafSpec(
            "gesture",
            "Play a gesture from the library, a list of them in order, or a recorded gesture file.",
            (
                Param("play", "gesture", "Gesture name or vendor id, e.g. 'high wave' or '26'.", required=True),
                Param("sequence", "gestures", "Gesture names played one after another.", required=True),
                Param("file", "path", "Recorded gesture JSON (keyframes).", required=True),
                Param("wait", "boolean", "false: succeed at once and let the gesture play on.", default=True),
            ),
            family="gesture",
            shorthand="play",
            one_of=(("play",), ("sequence",), ("file",)),
            default_timeout=60.0,
        ),
        LeafSpec(
            "speak",
            "Say a text.",
            (
                Param("text", "string", "What to say; ${key} inserts a blackboard value.", required=True),
                Param("wait", "boolean", "false: succeed at once and let speech overlap what follows.", default=True),
            ),
            family="tts",
            shorthand="text",
            default_timeout=120.0,
        ),
        LeafSpec(
            "find",
            "Look for an object by label with the head camera; its position goes to the world state.",
            (Param("object", "string", "Object label, e.g. 'cup'.", required=True),),
            family="vision",
            shorthand="object",
            default_timeout=60.0,
        ),
        LeafSpec(
            "observe",
            "Look once with the head camera; everything in view goes to the world state.",
            (),
            family="vision",
            default_timeout=10.0,
        ),
        LeafSpec(
            "wait",
            "Do nothing for some seconds (clock time).",
            (Param("seconds", "seconds", "How long.", required=True),),
            shorthand="seconds",
            default_timeout=float("inf"),
        ),
        LeafSpec(
            "stop",
            "Stop all motion: every daemon receives stop. Succeeds once they acknowledge.",
            (),
            default_timeout=5.0,
        ),
        LeafSpec(
            "condition",
            "Succeed when a blackboard expression is true, fail otherwise (or wait for it).",
            (
                Param("expr", "expression", "E.g. \"battery > 20 and held == 'bottle'\".", required=True),
                Param("wait", "boolean", "true: stay RUNNING until the expression holds.", default=False),
            ),
            shorthand="expr",
            default_timeout=float("inf"),
        ),
        LeafSpec(
            "set",
            "Write a blackboard key: a literal value or the result of an expression.",
            (
                Param("key", "string", "Blackboard key (dots for nested: 'visits.kitchen').", required=True),
                Param("value", "any", "Literal value (or $key reference).", required=True),
                Param("expr", "expression", "Expression evaluated on the blackboard.", required=True),
            ),
            one_of=(("value",), ("expr",)),
            default_timeout=float("inf"),
        ),
        LeafSpec(
            "log",
            "Write a message to the event log; ${key} inserts a blackboard value.",
            (
                Param("message", "string", "The message.", required=True),
                Param("level", "choice", "Severity.", default="info", choices=("debug", "info", "warning", "error")),
            ),
            shorthand="message",
            default_timeout=float("inf"),
        ),
    )
}

SKILLS = tuple(n for n, s in LEAVES.items() if s.family is not None or n in ("wait", "stop"))
FAMILIES = ("loco", "tts", "gesture", "pick", "vision")


@dataclass(frozen=True)
class NodeKind:
    """A composite or decorator kind and the options it takes (besides ``name``)."""

    name: str
    category: str  # "composite" | "decorator"
    doc: str
    params: tuple[Param, ...] = field(default_factory=tuple)


COMPOSITES: dict[str, NodeKind] = {
    k.name: k
    for k in (
        NodeKind(
            "sequence",
            "composite",
            "Run children in order until one fails. memory (default true): resume at the running child "
            "instead of re-checking earlier ones every tick.",
            (Param("memory", "boolean", "Resume at the running child (default true).", default=True),),
        ),
        NodeKind(
            "selector",
            "composite",
            "Fallback: try children in order until one succeeds. memory (default false): re-check "
            "higher-priority children every tick, so a recovered condition preempts a lower one.",
            (Param("memory", "boolean", "Resume at the running child (default false).", default=False),),
        ),
        NodeKind(
            "parallel",
            "composite",
            "Tick all children every tick. policy all: success when all succeed; one: when one does; "
            "selected: when the children named in 'selected' do. Any failure fails the parallel.",
            (
                Param("policy", "choice", "all | one | selected", default="all", choices=("all", "one", "selected")),
                Param("synchronise", "boolean", "Do not re-tick children that already succeeded.", default=True),
                Param("selected", "any", "Names of the children that must succeed (policy selected)."),
            ),
        ),
    )
}

DECORATORS: dict[str, NodeKind] = {
    k.name: k
    for k in (
        NodeKind("retry", "decorator", "Re-run the child after a failure, up to 'times' failures.",
                 (Param("times", "integer", "Failures allowed before giving up.", required=True),)),
        NodeKind("repeat", "decorator", "Run the child to success 'times' times (-1: forever); a failure fails.",
                 (Param("times", "integer", "Successes needed; -1 repeats forever.", required=True),)),
        NodeKind("timeout", "decorator", "Fail the child (and stop it) if it runs longer than 'seconds' (clock time).",
                 (Param("seconds", "seconds", "Time limit.", required=True),)),
        NodeKind("inverter", "decorator", "Swap success and failure."),
        NodeKind("force_success", "decorator", "Turn failure into success."),
        NodeKind("force_failure", "decorator", "Turn success into failure."),
        NodeKind("oneshot", "decorator", "Run the child to completion once; afterwards return that result.",
                 (Param("on", "choice", "Latch on 'success' only or on any 'completion'.", default="completion",
                        choices=("success", "completion")),)),
        NodeKind("guard", "decorator", "Run the child only while a blackboard expression holds; when it stops "
                 "holding, the child is stopped and the guard fails.",
                 (Param("condition", "expression", "Blackboard expression.", required=True),)),
        NodeKind("delay", "decorator", "Wait 'seconds' (clock time), then run the child.",
                 (Param("seconds", "seconds", "How long to wait first.", required=True),)),
    )
}
