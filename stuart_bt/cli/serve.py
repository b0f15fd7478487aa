"""``stuart-bt serve``: a tree (or the mission console, or a saved log) in the browser.

The socket is bound before anything starts, so a port in use or an address that is not this
machine's fails in one line and no daemon is left behind; then the robot side starts (daemons,
the simulator), then the page is served until Ctrl-C, and everything is stopped in order.
"""

from __future__ import annotations

import argparse
import contextlib
import socket
import sys
from pathlib import Path
from typing import Any

from .speed import add_speed_argument, speed_for

EXIT_OK, EXIT_FAILED = 0, 1


def add_command(subparsers: Any) -> argparse.ArgumentParser:
    """Register ``stuart-bt serve`` on an argparse sub-parser set."""
    p = subparsers.add_parser(
        "serve", help="the live web view: tree, mission console, map, gesture recorder",
        description="Run a tree (or the mission console) and watch it in a browser. Binds 127.0.0.1; any "
                    "other address needs the token printed at start.")
    p.add_argument("file", nargs="?", metavar="TREE", help="the tree to run (or use --mission / --replay)")
    p.add_argument("--mission", action="store_true", help="a mission console instead of one tree")
    p.add_argument("--replay", metavar="RUN.jsonl", help="show a saved event log (from --log) instead of running")
    p.add_argument("--backend", choices=("dry", "sim", "unitree"), default="dry", help="skill backend (default dry)")
    p.add_argument("--host", default="127.0.0.1", help="address to bind (default 127.0.0.1)")
    p.add_argument("--port", type=int, default=8081, help="port (default 8081; 0 picks a free one)")
    p.add_argument("--allow-host", action="append", default=[], metavar="NAME",
                   help="another name browsers use for this server (e.g. robot.local); requests naming any "
                        "other host are refused (DNS rebinding)")
    add_speed_argument(p, ("dry", "sim", "unitree"), interactive=True)
    p.add_argument("--rate", type=float, default=20.0, metavar="HZ", help="tick rate (default 20)")
    p.add_argument("--markers", metavar="FILE", help="marker file the map edits (default: the tree's)")
    p.add_argument("--gestures", metavar="DIR", default="gestures",
                   help="folder of recorded gestures (default ./gestures)")
    p.add_argument("--start", metavar="MARKER", help="marker the robot starts at (default entrance)")
    p.add_argument("--log", metavar="OUT.jsonl", help="write every event as JSON lines (replay it with --replay)")
    p.add_argument("--paused", action="store_true", help="wait for the Run button instead of starting the tree")
    p.add_argument("--no-wake", action="store_true", help="no 'Hey Stuart' needed in the console")
    p.set_defaults(func=cmd_serve)
    return p


def cmd_serve(args: argparse.Namespace) -> int:
    from .main import UserError

    modes = sum(bool(m) for m in (args.file, args.mission, args.replay))
    if modes != 1:
        raise UserError("give one of: a TREE file, --mission, or --replay RUN.jsonl")
    if args.rate <= 0 or (args.speed is not None and args.speed < 0):
        raise UserError("--rate must be positive and --speed not negative")
    if not 0 <= args.port <= 65535:
        raise UserError(f"--port {args.port} is not a port number (0..65535)")
    listener = _bind(args.host, args.port)
    try:
        return _serve(args, listener)
    finally:
        listener.close()


def _serve(args: argparse.Namespace, listener: socket.socket) -> int:
    import uvicorn

    from ..maps.markers import load_markers
    from ..web.app import WebParts, create_app
    from ..web.gestures import GestureFolder
    from ..web.mapfile import MapFile, default_map
    from ..web.markers import MarkerStore
    from ..web.security import Guard

    guard = Guard.for_host(args.host, listener.getsockname()[1], tuple(args.allow_host))
    control, hub, markers_file, what = _robot(args)
    map_file = MapFile.load(default_map())
    parts = WebParts(hub=hub, guard=guard, control=control, map=map_file,
                     markers=MarkerStore(markers_file, map_file.bounds()) if markers_file else None,
                     gestures=GestureFolder(args.gestures))
    port = listener.getsockname()[1]
    host = f"[{args.host}]" if ":" in args.host else args.host
    address = f"http://{host}:{port}/" + (f"?token={guard.token}" if guard.token else "")
    try:
        if control is not None:
            print(f"starting {what} ...", file=sys.stderr, flush=True)
            control.start()
            if parts.markers is not None:  # the markers the map shows are the ones "go to" knows
                control.set_markers(load_markers(parts.markers.path))
        print(f"serving {what} at {address}  (Ctrl-C stops)", flush=True)
        if guard.token:
            print(f"token: {guard.token}  (needed on every request: this address is not loopback-only)", flush=True)
        server = uvicorn.Server(uvicorn.Config(create_app(parts), log_level="warning", lifespan="on",
                                               ws="websockets-sansio", timeout_graceful_shutdown=2))
        with contextlib.suppress(KeyboardInterrupt):  # uvicorn re-raises the Ctrl-C it handled: a normal end
            server.run(sockets=[listener])
    finally:
        if control is not None:
            control.close()
        hub.close()
    print("stopped; every daemon is down", file=sys.stderr)
    return EXIT_OK


def _robot(args: argparse.Namespace) -> tuple[Any, Any, Path | None, str]:
    """(control, hub, marker file, description) for the chosen mode."""
    from ..web.control import MissionControl, TreeControl
    from ..web.hub import EventHub
    from .main import UserError, _load

    speed = speed_for(args.backend, args.speed, interactive=True)
    if args.replay:
        from ..core.events import read_jsonl

        try:
            events = read_jsonl(args.replay)
        except (OSError, ValueError, KeyError) as e:
            raise UserError(f"{args.replay}: not an event log: {e}") from None
        if not events:
            raise UserError(f"{args.replay}: the log is empty")
        markers = Path(args.markers) if args.markers else _package_markers()
        return None, EventHub(replay=events, info={"mode": "replay", "file": args.replay}), markers, \
            f"the replay of {args.replay} ({len(events)} events)"
    if args.mission:
        from ..mission.executor import MissionOptions

        if args.backend == "unitree":
            raise UserError("the mission console runs on --backend dry or sim")
        mission = MissionOptions(backend=args.backend, rate=args.rate, speed=speed, start=args.start,
                                 require_wake=not args.no_wake, log=Path(args.log) if args.log else None)
        control: Any = MissionControl(mission)
        info = {"mode": "mission", "backend": args.backend}
        return control, EventHub(control.events, info=info), Path(args.markers) if args.markers else \
            control.markers_file, f"the mission console ({args.backend})"
    from ..run.session import RunOptions

    spec = _load(args.file, args.markers)
    options = RunOptions(backend=args.backend, rate=args.rate, speed=speed, start=args.start,
                         log=Path(args.log) if args.log else None)
    control = TreeControl(spec, options, autostart=not args.paused, require_wake=not args.no_wake)
    info = {"mode": "tree", "backend": args.backend, "file": args.file}
    markers = Path(spec.markers_file) if spec.markers_file else _package_markers()
    return control, EventHub(control.events, info=info), markers, f"{args.file} ({args.backend})"


def _package_markers() -> Path:
    from importlib.resources import files

    return Path(str(files("stuart_bt.sim").joinpath("maps/lab_markers.json")))


def _bind(host: str, port: int) -> socket.socket:
    """The listening socket, or one clear message (port in use, not an address of this machine)."""
    from .main import UserError

    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind((host, port))
    except OSError as e:
        sock.close()
        raise UserError(f"cannot listen on {host}:{port}: {e.strerror or e}") from None
    sock.listen(64)
    sock.set_inheritable(True)
    return sock
