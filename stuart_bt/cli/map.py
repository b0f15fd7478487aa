"""``stuart-bt map``: the robot's SLAM maps from the command line (start mapping, save, relocalise, close).

The vendor SDK stays out of this process: the command starts the loco daemon with the unitree
backend and sends it one mapping command, exactly as a tree would, then shuts it down. Network
settings come from ``--interface`` / ``--domain`` or the ``STUART_UNITREE_*`` environment
variables (docs/robot.md).

    stuart-bt map start                                   # walk the robot around the space
    stuart-bt map save /home/unitree/lab.pcd              # end mapping and save the point cloud
    stuart-bt map relocalise /home/unitree/lab.pcd --pose 0,0,0
    stuart-bt map pose                                    # {"pose": {"x", "y", "yaw"}, ...}: for markers
    stuart-bt map close                                   # stop the SLAM service
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ..core.jsonfile import to_json

ACTIONS = {  # action -> (loco daemon command, help)
    "start": ("map_start", "start mapping (then walk the robot around the space)"),
    "save": ("map_save", "end mapping and save the map to PATH (a .pcd on the robot)"),
    "relocalise": ("relocalise", "localise on the map at PATH from an initial pose"),
    "close": ("slam_close", "stop the SLAM service"),
    "pose": ("state", "print where the robot is localised now (to write marker files)"),
}


def add_command(sub: Any) -> None:
    p = sub.add_parser("map", help="robot SLAM maps (unitree): start mapping, save, relocalise, pose, close",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("action", choices=tuple(ACTIONS), help="; ".join(f"{k}: {v[1]}" for k, v in ACTIONS.items()))
    p.add_argument("path", nargs="?", metavar="PATH", help="map file on the robot (save, relocalise)")
    p.add_argument("--pose", metavar="X,Y,YAW", default="0,0,0",
                   help="relocalise: initial map pose, metres and radians (default 0,0,0)")
    p.add_argument("--interface", metavar="NIC", help="network interface to the robot (else STUART_UNITREE_INTERFACE)")
    p.add_argument("--domain", type=int, metavar="ID", help="DDS domain (else STUART_UNITREE_DOMAIN, default 0)")
    p.add_argument("--timeout", type=float, default=10.0, metavar="S", help="seconds to wait for the answer")
    p.set_defaults(func=cmd_map)


def map_request(action: str, path: str | None, pose: str) -> dict[str, Any]:
    """The loco daemon's arguments for ``action``; a bad path or pose is a UserError."""
    from .main import UserError

    if action in ("save", "relocalise"):
        if not path:
            raise UserError(f"map {action} needs PATH, the map file on the robot (e.g. /home/unitree/lab.pcd)")
        if not (path.startswith("/") and path.endswith(".pcd")):
            raise UserError(f"map {action}: PATH must be an absolute .pcd path on the robot, got {path!r}")
    elif path:
        raise UserError(f"map {action} takes no PATH (got {path!r})")
    args: dict[str, Any] = {"path": path} if path else {}
    if action == "relocalise":
        try:
            x, y, yaw = (float(v) for v in pose.split(","))
        except ValueError:
            raise UserError(f"--pose must be X,Y,YAW in metres and radians, got {pose!r}") from None
        args["pose"] = {"x": x, "y": y, "yaw": yaw}
    return args


def cmd_map(args: argparse.Namespace) -> int:
    import tempfile

    from ..core.clock import ScaledClock
    from ..core.events import EventStream
    from ..daemon.supervisor import Supervisor
    from .main import EXIT_FAILED, EXIT_OK

    request_args = map_request(args.action, args.path, args.pose)
    options: dict[str, Any] = {}
    if args.interface:
        options["interface"] = args.interface
    if args.domain is not None:
        options["domain"] = args.domain
    clock = ScaledClock(1.0)
    # the daemon's log folder goes with the command: a one-shot request leaves nothing in /tmp
    with tempfile.TemporaryDirectory(prefix="stuart_bt-daemons-") as run_dir, \
            Supervisor("unitree", clock, EventStream(clock), families=("loco",), options={"loco": options},
                       handshake_timeout=30.0, run_dir=run_dir) as supervisor:
        command = ACTIONS[args.action][0]
        request = supervisor.wait(supervisor.client("loco").request(command, request_args), timeout=args.timeout)
    if request.ok:
        print(to_json(request.result))
        return EXIT_OK
    code = f" (vendor code {request.vendor_code})" if request.vendor_code is not None else ""
    print(f"stuart-bt: map {args.action} failed{code}: {request.reason or request.status}", file=sys.stderr)
    return EXIT_FAILED
