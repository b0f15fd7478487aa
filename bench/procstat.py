"""What a process tree holds right now: resident memory and open file descriptors per process,
read from /proc (Linux), for the soak benchmark.

A long session that leaks shows it here first: RSS that climbs with every command, or a file
descriptor per command that is never closed. Reading /proc costs a few hundred microseconds and
needs nothing installed, so it can be sampled between commands without disturbing them.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Usage:
    """One process's footprint at one moment."""

    pid: int
    name: str
    rss_kb: int
    fds: int


def _ppid_and_name(pid: int) -> tuple[int, str] | None:
    try:
        raw = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    # the name is in parentheses and may itself hold spaces or parentheses: split at the last ")"
    head, _, tail = raw.rpartition(")")
    fields = tail.split()
    if len(fields) < 2:
        return None
    return int(fields[1]), head.partition("(")[2]


def descendants(root: int) -> list[int]:
    """Every live process below ``root`` (children, their children, ...)."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            found = _ppid_and_name(int(entry.name))
            if found is not None:
                children.setdefault(found[0], []).append(int(entry.name))
    out: list[int] = []
    stack = list(children.get(root, []))
    while stack:
        pid = stack.pop()
        out.append(pid)
        stack += children.get(pid, [])
    return sorted(out)


def usage(pid: int) -> Usage | None:
    """RSS (kB, from /proc/PID/status) and open descriptors of ``pid``; None if it is gone."""
    found = _ppid_and_name(pid)
    if found is None:
        return None
    try:
        status = Path(f"/proc/{pid}/status").read_text()
        fds = len(os.listdir(f"/proc/{pid}/fd"))
    except OSError:
        return None
    rss = 0
    for line in status.splitlines():
        if line.startswith("VmRSS:"):
            rss = int(line.split()[1])
            break
    return Usage(pid, found[1], rss, fds)


def tree_usage(root: int) -> dict[int, Usage]:
    """Usage of ``root`` and every process below it, by pid."""
    out: dict[int, Usage] = {}
    for pid in [root, *descendants(root)]:
        found = usage(pid)
        if found is not None:
            out[pid] = found
    return out
