"""``python -m stuart_bt.sim.world``: the world server as a process. Its options, its READY line
on stdout (a daemon READY with the world's details), and an orderly end whatever stops it:
recordings finished, the map drawn, socket and clock file removed (docs/sim.md).
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
from pathlib import Path

from stuart_bt.core.jsonfile import to_json
from stuart_bt.daemon import protocol

from .clock import ClockFile
from .errors import WorldError
from .scene import build_scene
from .server import Server
from .world import World


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="python -m stuart_bt.sim.world",
                                     description="The MuJoCo world server (docs/sim.md).")
    parser.add_argument("--socket", required=True, help="Unix socket path to listen on")
    parser.add_argument("--clock", required=True, help="clock file to create (e.g. /dev/shm/stuart-world.clock)")
    parser.add_argument("--scene", default="lab", help="scene name (sim/scenes/NAME.xml) or an .xml path")
    parser.add_argument("--robot", default=None, help="robot MJCF (default sim/models/g1.xml)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the one random generator (noise)")
    parser.add_argument("--hold", action="store_true",
                        help="take no physics step until a clock driver attaches (runs start at t = 0)")
    parser.add_argument("--speed", type=float, default=None,
                        help="cap sim time at SPEED x wall time (0: no cap; default 0, or 1 with --viewer)")
    parser.add_argument("--record", default=None, help="record the chase camera for the whole run (.mp4 or .gif)")
    parser.add_argument("--record-fps", type=float, default=10.0, help="frames per sim second of --record")
    parser.add_argument("--viewer", action="store_true", help="open the interactive MuJoCo viewer")
    parser.add_argument("--map-out", default=None, help="at exit, draw the map with the driven path to this PNG")
    parser.add_argument("--loc-noise", action="store_true", help="add localisation noise to the reported base pose")
    parser.add_argument("--start", default=None, help="start pose X,Y[,YAW] (default 0,0,0: the entrance)")
    parser.add_argument("--remove-dir", action="store_true",
                        help="at exit, remove the socket's folder (a temporary folder made for this world: its "
                             "owner may have been killed and cannot remove it)")
    parser.add_argument("--ignore-stdin", action="store_true",
                        help="do not exit when stdin closes (for running detached, e.g. with </dev/null)")
    return parser.parse_args(argv)


def _claim_stdout() -> int:
    """Keep the real stdout for the READY line; anything else written to fd 1 (MuJoCo warnings)
    goes to stderr."""
    sys.stdout.flush()
    out_fd = os.dup(1)
    os.dup2(2, 1)
    return out_fd


def _start_pose(text: str | None) -> tuple[float, float, float]:
    if not text:
        return 0.0, 0.0, 0.0
    parts = [float(v) for v in text.split(",")]
    if len(parts) not in (2, 3):
        raise ValueError(f"--start wants X,Y or X,Y,YAW, got {text!r}")
    return parts[0], parts[1], parts[2] if len(parts) == 3 else 0.0


def main(argv: list[str] | None = None) -> int:
    out_fd = _claim_stdout()
    options = parse_args(argv)
    speed = options.speed if options.speed is not None else (1.0 if options.viewer else 0.0)
    if options.viewer and not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        print("world: --viewer needs a display (neither DISPLAY nor WAYLAND_DISPLAY is set); "
              "run without --viewer, or --record a video instead", file=sys.stderr)
        return 2
    try:
        scene = build_scene(options.scene, options.robot)
        start = _start_pose(options.start)
    except (FileNotFoundError, ValueError) as e:
        print(f"world: {e}", file=sys.stderr)
        return 2
    run_dir = Path(options.socket).resolve().parent
    world = World(scene, options.seed, options.loc_noise, run_dir, Path(options.scene).stem)
    if start != (0.0, 0.0, 0.0):
        world.cmd_set_base({"x": start[0], "y": start[1], "yaw": start[2]})
        world.path_log = [(start[0], start[1])]
    viewer = None
    if options.viewer:
        try:
            import mujoco.viewer

            viewer = mujoco.viewer.launch_passive(world.model, world.data)
        except Exception as e:  # noqa: BLE001 - no GL, no window system: say so in one line
            print(f"world: cannot open the viewer: {e}", file=sys.stderr)
            return 2
    clock = ClockFile(options.clock, world.dt)
    server = None
    reason = "start-up failed"
    try:
        server = Server(world, options.socket, clock, speed, watch_stdin=not options.ignore_stdin, viewer=viewer,
                        out_fd=out_fd, hold=options.hold)
        if options.record:
            world.start_recording(options.record, options.record_fps)
        ready = {**protocol.ready("world", "mujoco", os.getpid(), sorted(world.commands)),
                 "socket": options.socket, "clock": options.clock, "timestep": world.dt,
                 "scene": world.scene_name, "robot": str(scene.robot_path), "objects": sorted(scene.objects),
                 "speed": speed}
        os.write(out_fd, (to_json(ready) + "\n").encode())
        print(f"world: ready on {options.socket} (clock {options.clock}, dt {world.dt:g} s, pid {os.getpid()})",
              file=sys.stderr)
        reason = server.run()
    except (WorldError, OSError) as e:
        print(f"world: {getattr(e, 'reason', e)}", file=sys.stderr)
        return 2
    finally:
        for done in world.close():
            print(f"world: wrote {done['path']} ({done['frames']} frames)", file=sys.stderr)
        if options.map_out:
            try:
                print(f"world: wrote {world.draw_map(options.map_out)}", file=sys.stderr)
            except Exception as e:  # noqa: BLE001 - the map is a by-product: the world runs on without it
                print(f"world: could not draw the map: {e}", file=sys.stderr)
        if server is not None:
            server.close()
        clock.close(remove=True)
        if options.remove_dir:
            shutil.rmtree(run_dir, ignore_errors=True)
        if viewer is not None:
            viewer.close()
        print(f"world: stopped at t={world.t:.3f} s ({reason})", file=sys.stderr)
    return 0
