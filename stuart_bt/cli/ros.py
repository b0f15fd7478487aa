"""``stuart-bt ros``: the mission pipeline (or one tree) behind the original system's ROS 2 topics.

Starts one :class:`~stuart_bt.mission.executor.MissionExecutor` (daemons, and the MuJoCo world on
the sim backend) and one bridge node, then waits for SIGINT or SIGTERM; either shuts the tree,
the daemons and the node down, and the command exits 0. With a TREE file it runs that tree instead,
as ``stuart-bt run`` does, and what arrives on the input topics is said to the running tree
(:class:`~stuart_bt.mission.talking_tree.TalkingTree`): the command ends with the tree (exit 0 when
it succeeded or a signal stopped it, else 1). A start that fails (bad namespace or domain id, a tree
with errors, a daemon that does not come up) prints one line and exits 1. docs/ros.md has the topics.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
import threading
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..core.interrupts import Interrupts
from .hear import add_hearing_arguments, make_listener
from .main import _daemon_options
from .mission import add_llm_arguments, llm_options
from .speed import add_speed_argument, speed_for

if TYPE_CHECKING:
    from ..mission.executor import MissionOptions
    from ..mission.talking_tree import TalkingTree

EXIT_OK, EXIT_FAILED = 0, 1
MAX_DOMAIN_ID = 232  # the highest ROS 2 domain id whose DDS ports fit (ROS 2 docs, "domain ID")


def add_command(subparsers: Any) -> argparse.ArgumentParser:
    """Register ``stuart-bt ros`` on an argparse sub-parser set."""
    p = subparsers.add_parser(
        "ros", help="a ROS 2 bridge node: /audio_msg in, /llm/task_intent, /llm/response, /bt/status out",
        description="Run the mission pipeline (or one TREE) behind the original system's ROS 2 topics "
                    "(docs/ros.md). ROS_DOMAIN_ID is respected; Ctrl-C or SIGTERM stops node, tree and daemons.")
    p.add_argument("tree", nargs="?", metavar="TREE",
                   help="run this tree instead of missions: what arrives on the input topics is said to it (a "
                        "question is answered at the next pause in speech, 'stop' holds it, 'continue' goes on); "
                        "the bridge ends with the tree")
    p.add_argument("--backend", choices=("dry", "sim", "unitree"), default="dry", help="skill backend (default dry)")
    p.add_argument("--namespace", default="/", metavar="NS", help="namespace of the node and its topics (default /)")
    p.add_argument("--start", metavar="MARKER", help="where the robot starts (default entrance)")
    add_speed_argument(p, ("dry", "sim", "unitree"), interactive=True)
    p.add_argument("--status-rate", type=float, default=10.0, metavar="HZ",
                   help="most /bt/status messages per second (default 10)")
    p.add_argument("--confirm-picks", action="store_true",
                   help="hold every pick until 'confirm' arrives on /pick_target (the original safety step)")
    p.add_argument("--daemon-options", metavar="FILE",
                   help="JSON or YAML: {family: {option: value}} for the daemons (as for stuart-bt run)")
    p.add_argument("--log", type=Path, metavar="OUT.jsonl", help="also write every event, one JSON object per line")
    p.add_argument("--hear", metavar="SOURCE", help="also hear SOURCE (mic, mic:DEVICE, file:PATH, -, robot, "
                                                     "robot:asr) and publish what is heard on /audio_msg")
    add_hearing_arguments(p)
    add_llm_arguments(p)
    p.set_defaults(func=cmd_ros)
    return p


def cmd_ros(args: argparse.Namespace) -> int:
    problem = _check(args)
    if problem:
        print(f"stuart-bt: {problem}", file=sys.stderr)
        return EXIT_FAILED
    from ..mission.executor import MissionExecutor
    from ..ros.node import Bridge  # rclpy loads here, and only in this process

    daemon_options = _daemon_options(args.daemon_options, also=("ears",))  # a bad file: one line, nothing started
    ears_options = daemon_options.pop("ears", {})
    if args.confirm_picks:
        daemon_options.setdefault("pick", {})["confirm"] = True
    if args.tree:
        return _bridge_tree(args, daemon_options, ears_options)
    options = mission_options(args, daemon_options)
    stop = threading.Event()
    with _interrupts(stop):
        try:
            robot = MissionExecutor(options)
        except (ValueError, RuntimeError) as e:  # bad options, a missing model file
            print(f"stuart-bt: {e}", file=sys.stderr)
            return EXIT_FAILED
        with robot:
            bridge = Bridge(robot, namespace=_namespace(args.namespace), status_rate=args.status_rate)
            listener = None
            try:
                bridge.start()
                listener = make_listener(args.hear, robot, args, ears_options)
                if listener is not None:
                    listener.start()
                _announce(bridge, robot)
                while not stop.wait(0.2):
                    pass
                robot.close()  # the tree halts and the daemons stop while the node still reports it
            finally:
                if listener is not None:
                    listener.close()
                bridge.close()
    print("ros bridge: stopped; every daemon stopped", flush=True)
    return EXIT_OK


def _bridge_tree(args: argparse.Namespace, daemon_options: dict[str, Any], ears_options: dict[str, Any]) -> int:
    """``stuart-bt ros TREE``: the node is made before the session starts, so its snapshot and
    ``/bt/events`` see the tree being built; the tree runs on this thread and a signal stops it."""
    from ..ros.node import Bridge

    try:
        robot = talking_tree(args, daemon_options)
    except (ValueError, RuntimeError) as e:  # a missing model file
        print(f"stuart-bt: {e}", file=sys.stderr)
        return EXIT_FAILED
    stop = threading.Event()
    with _interrupts(stop, also=lambda: robot.request_stop("interrupted")):
        listener = None
        try:
            bridge = Bridge(robot, namespace=_namespace(args.namespace), status_rate=args.status_rate)
            try:
                robot.start()
                bridge.start()
                listener = make_listener(args.hear, robot, args, ears_options)
                if listener is not None:
                    listener.start()
                _announce(bridge, robot)
                if stop.is_set():  # a signal while the daemons came up: the run ends before its first tick
                    robot.request_stop("interrupted")
                outcome = robot.run()
                robot.close()  # every daemon stops while the node still reports it
            finally:
                if listener is not None:
                    listener.close()
                bridge.close()
        finally:
            robot.close()
    print(f"ros bridge: the tree ended {outcome.status}{f' ({outcome.reason})' if outcome.reason else ''}; "
          "every daemon stopped", flush=True)
    return EXIT_OK if outcome.status in ("SUCCESS", "STOPPED") else EXIT_FAILED


def talking_tree(args: argparse.Namespace, daemon_options: dict[str, Any]) -> TalkingTree:
    """The tree behind the bridge, from the command's options (a tree with errors: one line)."""
    from ..conversation import make_conversation
    from ..mission.talking_tree import TalkingTree
    from ..run.session import RunOptions
    from .main import _load

    spec = _load(args.tree, None)
    options = RunOptions(backend=args.backend, speed=speed_for(args.backend, args.speed, interactive=True),
                         start=args.start, log=args.log, daemon_options=daemon_options)
    conversation = make_conversation(args.llm, **llm_options(args)) if args.llm != "none" else None
    return TalkingTree(spec, options, conversation)


def mission_options(args: argparse.Namespace, daemon_options: dict[str, Any]) -> MissionOptions:
    """The robot behind the bridge, from the command's options: people talk to it over the topics,
    so the simulator runs at real time unless ``--speed`` says otherwise."""
    from ..mission.executor import MissionOptions

    return MissionOptions(backend=args.backend, speed=speed_for(args.backend, args.speed, interactive=True),
                          start=args.start, log=args.log, conversation=args.llm,
                          conversation_options=llm_options(args), daemon_options=daemon_options)


def _check(args: argparse.Namespace) -> str | None:
    """One sentence for the first bad option, else None (nothing has started yet)."""
    if args.status_rate <= 0:
        return "--status-rate must be positive"
    if args.speed is not None and args.speed < 0:
        return "--speed must not be negative"
    domain = os.environ.get("ROS_DOMAIN_ID", "").strip()
    if domain and not (domain.isdigit() and int(domain) <= MAX_DOMAIN_ID):
        return f"ROS_DOMAIN_ID must be a whole number from 0 to {MAX_DOMAIN_ID}, not {domain!r}"
    from ..ros.guard import forbid_vendor_sdk

    forbid_vendor_sdk()  # before rclpy loads
    from rclpy.exceptions import InvalidNamespaceException
    from rclpy.validate_namespace import validate_namespace

    try:
        validate_namespace(_namespace(args.namespace))
    except InvalidNamespaceException as e:
        why = str(e).splitlines()[0].removeprefix("Invalid namespace: ").rstrip(": ")
        return f"bad --namespace {args.namespace!r}: {why} (try {_closest_namespace(args.namespace)!r})"
    return None


def _closest_namespace(ns: str) -> str:
    """A valid namespace like ``ns``: other characters become '_', no empty or digit-led parts."""
    parts = [re.sub(r"\W", "_", p, flags=re.ASCII) for p in ns.split("/") if p]
    return "/" + "/".join(p if not p[0].isdigit() else "_" + p for p in parts)


def _namespace(ns: str) -> str:
    return ns if ns.startswith("/") else "/" + ns


def _announce(bridge: Any, robot: Any) -> None:
    """One line that says the bridge is up and where (tests and scripts wait for it)."""
    from ..ros import topics as t

    supervisor = robot.session.supervisor
    daemons = ", ".join(f"{f} {supervisor.pid(f)}" for f in supervisor.families) if supervisor else "none"
    ins = " ".join(bridge.resolve(k) for k in (t.AUDIO_IN, t.LLM_INPUT, t.MISSION_IN, t.PICK_TARGET))
    print(f"ros bridge: node {bridge.full_name} domain {bridge.context.get_domain_id()} backend "
          f"{robot.session.options.backend}; daemons {daemons}; listening on {ins}", flush=True)


def _interrupts(stop: threading.Event, also: Callable[[], None] | None = None) -> Interrupts:
    """SIGINT and SIGTERM only set ``stop`` (and call ``also``, such as asking a running tree to
    stop), on the interrupts' own thread, never inside the handler (:mod:`stuart_bt.core.interrupts`:
    setting an event the main thread waits on from the handler can hang it): the main thread then
    shuts down in order. SIGINT is set explicitly because a bridge started in the background
    inherits it ignored."""
    def on_signal(signum: int) -> None:
        stop.set()
        if also is not None:
            also()

    return Interrupts(on_signal)
