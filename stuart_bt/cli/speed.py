"""The ``--speed`` option: one wording and one default rule for every command that runs a robot.

What the number means differs by backend, so the help says it for each backend a command
offers. The default depends on who is watching: a command a person talks to (``chat``,
``listen``, ``ros``, ``serve``) runs the simulator at real time, so the robot has not already
crossed the room when they say "stop"; a batch command (``run``, ``mission``) lets the
simulator go as fast as the tree keeps up, because nobody waits on it.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence

REAL_TIME = 1.0

_MEANING = {
    "dry": "clock seconds per wall second (default 1)",
    "sim": "cap on simulated seconds per wall second",
    "unitree": "scales only the framework's clock (tree timeouts, waits); the robot moves and speaks in "
               "real time, so keep the default 1 on a real robot",
}
_SIM_DEFAULT = {
    True: "default 1: real time, so a person can say 'stop' in time; 0: as fast as the tree keeps up",
    False: "default 0: as fast as the tree keeps up",
}


def speed_help(backends: Sequence[str], interactive: bool, sim_note: str = "") -> str:
    """The ``--speed`` help for a command offering ``backends``; ``sim_note`` qualifies the sim
    default (``run``: 1 with ``--viewer``)."""
    parts = []
    for backend in backends:
        meaning = _MEANING[backend]
        if backend == "sim":
            meaning += f" ({_SIM_DEFAULT[interactive]}{sim_note})"
        parts.append(f"{backend}: {meaning}")
    return "; ".join(parts)


def add_speed_argument(p: argparse.ArgumentParser, backends: Sequence[str], *, interactive: bool,
                       sim_note: str = "") -> None:
    """Register ``--speed F`` with the help for ``backends``; read it back with :func:`speed_for`."""
    p.add_argument("--speed", type=float, default=None, metavar="F",
                   help=speed_help(backends, interactive, sim_note))


def speed_for(backend: str, speed: float | None, *, interactive: bool) -> float | None:
    """The speed a session gets: the one asked for, else real time for an interactive command on
    the simulator, else None (each backend's own default: dry 1, sim as fast as the tree keeps
    up, unitree 1). Raises ValueError for a negative speed (no clock runs backwards)."""
    if speed is not None:
        if speed < 0:
            raise ValueError(f"--speed must not be negative (got {speed:g}); 0 is as fast as possible")
        return speed
    return REAL_TIME if interactive and backend == "sim" else None
