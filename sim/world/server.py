"""The world server: one process that owns the MuJoCo world and answers JSON lines on a socket.

Physics and the requests share one thread. Between two physics steps the server accepts
connections and answers whatever requests have arrived (``selectors``, non-blocking sockets),
so no client can stall the world and every reply sees a consistent state. The world's sim time
goes out through the shared clock file after every step (:mod:`.clock`); when a driver is
attached the world steps only up to the driver's permit (lockstep with the tree's ticks),
otherwise it runs free, optionally capped at ``--speed`` times wall time.

The robot is kinematic: every step its base pose comes from :class:`.base.BaseController` and
its joints from :class:`.arms.JointPlayer`; only the free objects are simulated.

Protocol (docs/sim.md): request ``{"id", "cmd", "args"}``, reply ``{"id", "ok": true,
"result"}`` or ``{"id", "ok": false, "error": code, "reason"}``.
"""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import selectors
import shutil
import signal
import socket
import stat
import sys
import time
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

from stuart_bt.core.errors import CodedError
from stuart_bt.core.jsonfile import is_finite_number, to_json
from stuart_bt.daemon import args as a
from stuart_bt.daemon.protocol import MAX_LINE, LineBuffer, Oversize, ProtocolError, decode, encode
from stuart_bt.maps.markers import load_markers
from stuart_bt.maps.picture import draw_map_png

from .arms import SIDES, Hands, JointPlayer
from .base import BaseController, BaseLimits, PersonCheck, wrap
from .clock import ClockFile
from .errors import WorldError
from .occupancy import footprint_hits, grid_from_model, static_footprints
from .render import Cameras, Recorder, save_png
from .scene import MAPS_DIR, Scene, build_scene

READ_CHUNK = 1 << 16
FOOTPRINT_RADIUS = 0.2  # the base's own footprint (legs and feet) for the collision flag (m)
RAISED = (0.45, 0.12)  # above knee height (m), e.g. a table top, only the hips and torso (radius m) can touch
PERSON_HEIGHT = 1.7
PERSON_PARK = (-4.0, -6.0, -3.0)  # outside the walls and under the floor: out of every view
PATH_LOG_STEP = 0.02  # metres between logged points of the driven path
RATE_WINDOW = 0.25  # wall seconds over which the sim/wall rate is measured
VIEWER_PERIOD = 1.0 / 60.0
LOC_NOISE = (0.01, 0.01, math.radians(0.5))  # sigma of x, y (m) and yaw (rad) with --loc-noise

Handler = Callable[[dict[str, Any]], dict[str, Any]]


def _r(value: float, digits: int = 4) -> float:
    return round(float(value), digits)


class World:
    """Physics, the robot's controllers, and the command handlers."""

    def __init__(self, scene: Scene, seed: int = 0, loc_noise: bool = False, run_dir: Path | None = None,
                 scene_name: str = "lab") -> None:
        self.scene = scene
        self.model = scene.model
        self.data = mujoco.MjData(self.model)
        self.dt = scene.timestep
        self.rng = np.random.default_rng(seed)
        self.loc_noise = loc_noise
        self.run_dir = run_dir or Path.cwd()
        self.scene_name = scene_name
        self.base = BaseController(self.dt, BaseLimits())
        self.player = JointPlayer(scene.joint_names, scene.lower, scene.upper, scene.home)
        self.hands = Hands(self.player, self.model, scene.hand_sites, scene.objects)
        self.person: tuple[float, float] | None = None
        self._cameras: Cameras | None = None
        self.recorders: list[Recorder] = []
        self.path_log: list[tuple[float, float]] = [(0.0, 0.0)]
        self.collision: list[str] = []
        self.collided = False
        self.grid = grid_from_model(self.model)
        self._footprint_mask = self.grid.dilated(FOOTPRINT_RADIUS)
        self._footprints = static_footprints(self.model)
        self._renders = 0
        self._park_person()
        self._write_robot()
        mujoco.mj_forward(self.model, self.data)
        self.stop_requested = False
        self.commands: dict[str, Handler] = {
            "ping": lambda args: {"t": _r(self.t)},
            "info": self.cmd_info,
            "state": self.cmd_state,
            "base_velocity": self.cmd_base_velocity,
            "base_path": self.cmd_base_path,
            "base_stop": self.cmd_base_stop,
            "set_base": self.cmd_set_base,
            "arm_trajectory": self.cmd_arm_trajectory,
            "arm_stop": self.cmd_arm_stop,
            "hand": self.cmd_hand,
            "person": self.cmd_person,
            "set_object": self.cmd_set_object,
            "surface": self.cmd_surface,
            "render": self.cmd_render,
            "record": self.cmd_record,
            "record_stop": self.cmd_record_stop,
            "map": self.cmd_map,
            "shutdown": self.cmd_shutdown,
        }

    @property
    def t(self) -> float:
        return float(self.data.time)

    @property
    def cameras(self) -> Cameras:
        if self._cameras is None:  # a GL context costs seconds: only when something renders
            self._cameras = Cameras(self.model)
        return self._cameras

    # -- stepping --------------------------------------------------------------------------

    def step(self) -> None:
        t = self.t
        lidar = self.scene.lidar_site
        lidar_xy = (float(self.data.site_xpos[lidar, 0]), float(self.data.site_xpos[lidar, 1])) \
            if lidar is not None else (self.base.x, self.base.y)
        self.base.step(t, PersonCheck(self.person, lidar_xy))
        self.player.step(t)
        self.hands.step(self.data, t)
        self._write_robot()
        mujoco.mj_step(self.model, self.data)
        self._after_step()

    def _write_robot(self) -> None:
        """Put the robot where its controllers say (it is kinematic: physics never moves it)."""
        d, s, b = self.data, self.scene, self.base
        d.qpos[s.base_qpos] = (b.x, b.y, b.yaw)
        c, sn = math.cos(b.yaw), math.sin(b.yaw)
        d.qvel[s.base_dof] = (c * b.vx - sn * b.vy, sn * b.vx + c * b.vy, b.wz)
        d.qpos[s.joint_qpos] = self.player.q
        d.qvel[s.joint_dof] = 0.0
        act = s.joint_actuator
        has = act >= 0
        if has.any():
            d.ctrl[act[has]] = self.player.q[has]

    def _after_step(self) -> None:
        b = self.base
        row, col = self.grid.world_to_cell(b.x, b.y)
        hit = not self.grid.inside(row, col) or bool(self._footprint_mask[row, col])
        if hit:  # the grid is coarse: confirm with the exact outlines
            self.collision = footprint_hits(self._footprints, b.x, b.y, FOOTPRINT_RADIUS, RAISED)
            self.collided = self.collided or bool(self.collision)
        else:
            self.collision = []
        last = self.path_log[-1]
        if abs(b.x - last[0]) + abs(b.y - last[1]) >= PATH_LOG_STEP:
            self.path_log.append((b.x, b.y))
        for recorder in self.recorders:
            if recorder.due(self.t):
                self.sync_pose()
                recorder.capture(self.data, self.t)

    def sync_pose(self) -> None:
        """Make the model's positions match the controllers exactly (before rendering)."""
        self._write_robot()
        mujoco.mj_forward(self.model, self.data)

    def _park_person(self) -> None:
        mocap = self.scene.person_mocap
        if mocap is not None:
            self.data.mocap_pos[mocap] = PERSON_PARK
        self.person = None

    def close(self) -> list[dict[str, Any]]:
        done = [r.close() for r in self.recorders]
        self.recorders.clear()
        if self._cameras is not None:
            self._cameras.close()
        return done

    # -- queries ---------------------------------------------------------------------------

    def objects(self) -> dict[str, dict[str, float]]:
        out = {}
        for label, obj in self.scene.objects.items():
            x, y, z = self.data.qpos[obj.qpos:obj.qpos + 3]
            out[label] = {"x": _r(x), "y": _r(y), "z": _r(z)}
        return out

    def localised_base(self) -> dict[str, float]:
        """The base pose as localisation reports it (noisy with ``--loc-noise``)."""
        b = self.base
        x, y, yaw = b.x, b.y, b.yaw
        if self.loc_noise:
            nx, ny, nyaw = self.rng.normal(0.0, LOC_NOISE)
            x, y, yaw = x + nx, y + ny, wrap(yaw + nyaw)
        return {"x": _r(x), "y": _r(y), "yaw": _r(yaw, 5)}

    def cmd_state(self, args: dict[str, Any]) -> dict[str, Any]:
        b = self.base
        hand_points = {side: [_r(v) for v in self.data.site_xpos[site]] for side, site in self.scene.hand_sites.items()}
        return {
            "t": _r(self.t),
            "base": self.localised_base(),
            "base_velocity": {"vx": _r(b.vx), "vy": _r(b.vy), "wz": _r(b.wz)},
            "base_status": b.status,
            "arrival_error": b.arrival_error,
            "collision": bool(self.collision),
            "collision_with": self.collision,
            "collided": self.collided,
            "joints": self.player.joint_dict(),
            "arm_busy": {side: self.player.busy(side) for side in SIDES},
            "trajectories": self.player.active_ids(),
            "hands": dict(self.hands.state),
            "held": {side: self.hands.held_label(side) for side in SIDES},
            "hand_points": hand_points,
            "objects": self.objects(),
            "person": None if self.person is None else {"x": _r(self.person[0]), "y": _r(self.person[1])},
        }

    def cmd_info(self, args: dict[str, Any]) -> dict[str, Any]:
        s = self.scene
        return {
            "scene": self.scene_name,
            "robot": str(s.robot_path),
            "timestep": self.dt,
            "joints": {n: {"lower": _finite(lo), "upper": _finite(hi), "home": _r(h, 5)}
                       for n, lo, hi, h in zip(s.joint_names, s.lower, s.upper, s.home, strict=True)},
            "objects": sorted(s.objects),
            "cameras": sorted(s.cameras),
            "limits": vars(self.base.limits),
            "map": {"resolution": self.grid.resolution, "origin": list(self.grid.origin)},
        }

    # -- base ------------------------------------------------------------------------------

    def cmd_base_velocity(self, args: dict[str, Any]) -> dict[str, Any]:
        cmd = "base_velocity"
        a.only_known(args, ("vx", "vy", "wz", "duration"), cmd)
        vx, vy, wz = (a.number(args, k, cmd, default=0.0) for k in ("vx", "vy", "wz"))
        duration = a.number(args, "duration", cmd, default=0.5, minimum=0.0)
        self.base.velocity(vx, vy, wz, duration, self.t)
        self.collided = False
        ignored = math.hypot(vx, vy) < self.base.limits.dead_band and (vx or vy)
        return {"expires": _r(self.t + duration), "dead_band": bool(ignored)}

    def cmd_base_path(self, args: dict[str, Any]) -> dict[str, Any]:
        cmd = "base_path"
        a.only_known(args, ("waypoints", "final_yaw", "max_speed", "tolerance", "yaw_tolerance"), cmd)
        raw = args.get("waypoints")
        if not isinstance(raw, list) or not raw:
            raise WorldError("bad_request", "base_path: 'waypoints' must be a non-empty list of [x, y]")
        waypoints = []
        for n, p in enumerate(raw):
            if not isinstance(p, (list, tuple)) or len(p) != 2 or not all(is_finite_number(v) for v in p):
                raise WorldError("bad_request", f"base_path: waypoint {n} must be [x, y], got {p!r}")
            waypoints.append((float(p[0]), float(p[1])))
        final_yaw = a.optional_number(args, "final_yaw", cmd)
        max_speed = a.number(args, "max_speed", cmd, default=0.6, minimum=0.0)
        tolerance = a.number(args, "tolerance", cmd, default=0.10, minimum=0.0)
        yaw_tolerance = a.number(args, "yaw_tolerance", cmd, default=math.radians(5.0), minimum=0.0)
        self.base.follow(waypoints, final_yaw, max_speed, tolerance, yaw_tolerance)
        self.collided = False
        return {"legs": len(self.base.path.legs) if self.base.path else 0}

    def cmd_base_stop(self, args: dict[str, Any]) -> dict[str, Any]:
        a.only_known(args, (), "base_stop")
        self.base.stop()
        return {"velocity": {"vx": _r(self.base.vx), "vy": _r(self.base.vy), "wz": _r(self.base.wz)}}

    def cmd_set_base(self, args: dict[str, Any]) -> dict[str, Any]:
        cmd = "set_base"
        a.only_known(args, ("x", "y", "yaw"), cmd)
        x, y = a.number(args, "x", cmd), a.number(args, "y", cmd)
        yaw = a.number(args, "yaw", cmd, default=0.0)
        self.base.teleport(x, y, yaw)
        self.collided = False
        self.path_log.append((x, y))
        self.sync_pose()
        return {"base": {"x": _r(x), "y": _r(y), "yaw": _r(wrap(yaw), 5)}}

    # -- arms and hands ----------------------------------------------------------------------

    def cmd_arm_trajectory(self, args: dict[str, Any]) -> dict[str, Any]:
        cmd = "arm_trajectory"
        a.only_known(args, ("points", "id", "interp"), cmd)
        self._traj_count = getattr(self, "_traj_count", 0) + 1
        traj_id = a.string(args, "id", cmd, default=f"traj-{self._traj_count}")
        interp = a.string(args, "interp", cmd, default="linear", choices=("linear", "smooth"))
        return self.player.start(args.get("points"), traj_id, self.t, smooth=interp == "smooth")

    def cmd_arm_stop(self, args: dict[str, Any]) -> dict[str, Any]:
        a.only_known(args, ("side",), "arm_stop")
        side = a.string(args, "side", "arm_stop", default="both", choices=("left", "right", "both"))
        if side == "both":
            joints = [n for n in self.player.names if "_hand_" not in n]
        else:
            joints = [n for n in self.player.names if n.startswith(side + "_") and "_hand_" not in n]
        self.player.stop(joints)
        return {"joints": self.player.joint_dict()}

    def cmd_hand(self, args: dict[str, Any]) -> dict[str, Any]:
        cmd = "hand"
        a.only_known(args, ("side", "closed"), cmd)
        side = a.string(args, "side", cmd, choices=SIDES)
        closed = args.get("closed")
        if not isinstance(closed, bool):
            raise WorldError("bad_request", f"hand: 'closed' must be true or false, got {closed!r}")
        return self.hands.command(side, closed, self.data, self.t)

    # -- the person and objects --------------------------------------------------------------

    def cmd_person(self, args: dict[str, Any]) -> dict[str, Any]:
        cmd = "person"
        a.only_known(args, ("x", "y", "present"), cmd)
        present = args.get("present", True)
        if not isinstance(present, bool):
            raise WorldError("bad_request", f"person: 'present' must be true or false, got {present!r}")
        if self.scene.person_mocap is None:
            raise WorldError("not_found", "this scene has no 'person' mocap body")
        if not present:
            self._park_person()
            return {"person": None}
        x, y = a.number(args, "x", cmd), a.number(args, "y", cmd)
        self.data.mocap_pos[self.scene.person_mocap] = (x, y, PERSON_HEIGHT / 2)
        self.person = (x, y)
        return {"person": {"x": _r(x), "y": _r(y)}}

    def cmd_set_object(self, args: dict[str, Any]) -> dict[str, Any]:
        cmd = "set_object"
        a.only_known(args, ("label", "x", "y", "z", "yaw"), cmd)
        label = a.string(args, "label", cmd)
        obj = self.scene.objects.get(label)
        if obj is None:
            raise WorldError("not_found", f"no object {label!r}; objects: {', '.join(sorted(self.scene.objects))}")
        side = self.hands.holder(label)
        if side is not None:
            self.hands.release(side, self.data)
        x, y, z = (a.number(args, k, cmd) for k in ("x", "y", "z"))
        self.data.qpos[obj.qpos:obj.qpos + 3] = (x, y, z)
        yaw = a.optional_number(args, "yaw", cmd)
        if yaw is not None:
            self.data.qpos[obj.qpos + 3:obj.qpos + 7] = (math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2))
        self.data.qvel[obj.qvel:obj.qvel + 6] = 0.0
        self.sync_pose()
        return {"object": label, "x": _r(x), "y": _r(y), "z": _r(z)}

    def cmd_surface(self, args: dict[str, Any]) -> dict[str, Any]:
        """Height of the highest static surface (floor, table, bench) under a point, by a ray
        cast straight down through the scene's static geoms only: where an object can be put."""
        cmd = "surface"
        a.only_known(args, ("x", "y"), cmd)
        x, y = a.number(args, "x", cmd), a.number(args, "y", cmd)
        top = 3.0
        groups = np.zeros(6, dtype=np.uint8)
        groups[0] = 1  # the static class: floor, walls, furniture
        geom = np.array([-1], dtype=np.int32)
        distance = mujoco.mj_ray(self.model, self.data, np.array([x, y, top]), np.array([0.0, 0.0, -1.0]),
                                 groups, 1, -1, geom)
        if distance < 0:
            raise WorldError("not_found", f"no surface under ({x:.2f}, {y:.2f})")
        name = mujoco.mj_id2name(self.model, mujoco.mjtObj.mjOBJ_GEOM, int(geom[0])) or f"geom {int(geom[0])}"
        return {"z": _r(top - distance), "geom": name}

    # -- pictures ----------------------------------------------------------------------------

    def _size(self, args: dict[str, Any], cmd: str, default: tuple[int, int]) -> tuple[int, int]:
        width = args.get("width", default[0])
        height = args.get("height", default[1])
        max_w, max_h = self.cameras.limits()
        for key, value, limit in (("width", width, max_w), ("height", height, max_h)):
            if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= limit:
                raise WorldError("bad_request", f"{cmd}: {key!r} must be an integer in 1..{limit}, got {value!r}")
        return width, height

    def object_labels(self) -> tuple[list[str], np.ndarray]:
        """The objects' labels (sorted) and, per geom id, the index of the label it belongs to
        (-1: not an object), for the segmentation the sim detector starts from."""
        names = sorted(self.scene.objects)
        body_label = np.full(self.model.nbody, -1, dtype=np.int16)
        for index, name in enumerate(names):
            body_label[self.scene.objects[name].body] = index
        return names, body_label[self.model.geom_bodyid]

    def cmd_render(self, args: dict[str, Any]) -> dict[str, Any]:
        cmd = "render"
        a.only_known(args, ("camera", "width", "height", "depth", "path", "depth_path", "labels", "labels_path"), cmd)
        camera = a.string(args, "camera", cmd, default="head_camera")
        if camera not in self.scene.cameras:
            raise WorldError("not_found", f"no camera {camera!r}; cameras: {', '.join(sorted(self.scene.cameras))}")
        width, height = self._size(args, cmd, (640, 480))
        flags = {}
        for key in ("depth", "labels"):
            flags[key] = args.get(key, False)
            if not isinstance(flags[key], bool):
                raise WorldError("bad_request", f"render: {key!r} must be true or false, got {flags[key]!r}")
        path = Path(a.string(args, "path", cmd, default=str(self.run_dir / f"render_{self._renders + 1}.png")))
        if path.suffix.lower() not in (".png", ".npy"):
            raise WorldError("bad_request",
                             f"render: 'path' must end in .png (or .npy for raw pixels), got {str(path)!r}")
        depth_path = Path(a.string(args, "depth_path", cmd, default=str(path.with_name(path.stem + "_depth.npy"))))
        labels_path = Path(a.string(args, "labels_path", cmd, default=str(path.with_name(path.stem + "_labels.npy"))))
        for key, extra in (("depth_path", depth_path), ("labels_path", labels_path)):
            if extra.suffix.lower() != ".npy":
                raise WorldError("bad_request", f"render: {key!r} must end in .npy, got {str(extra)!r}")
        self._renders += 1
        self.sync_pose()
        names, geom_labels = self.object_labels() if flags["labels"] else ([], None)
        frame = self.cameras.render(self.data, camera, width, height, flags["depth"], geom_labels)
        if path.suffix.lower() == ".npy":  # raw pixels: no PNG encoding, for perception at camera rate
            path.parent.mkdir(parents=True, exist_ok=True)
            np.save(path, frame.rgb)
        else:
            save_png(frame.rgb, path)
        result: dict[str, Any] = {"t": _r(self.t), "camera": camera, "width": width, "height": height,
                                  "path": str(path), "depth_path": None,
                                  "intrinsics": {k: _r(v, 4) for k, v in frame.intrinsics.items()},
                                  "pose": frame.pose, "base": self.localised_base()}
        if frame.depth is not None:
            depth_path.parent.mkdir(parents=True, exist_ok=True)
            np.save(depth_path, frame.depth)
            result["depth_path"] = str(depth_path)
        if frame.labels is not None:
            labels_path.parent.mkdir(parents=True, exist_ok=True)
            np.save(labels_path, frame.labels)
            result["labels_path"] = str(labels_path)
            result["label_names"] = names
        return result

    def start_recording(self, path: str, fps: float, camera: str = "chase", width: int | None = None,
                        height: int | None = None) -> Recorder:
        if any(r.path == Path(path) for r in self.recorders):
            raise WorldError("busy", f"already recording to {path}")
        try:
            recorder = Recorder(path, fps, self.cameras, camera, width, height, start=self.t)
        except (ValueError, KeyError) as e:
            raise WorldError("bad_request", f"record: {e}") from None
        self.recorders.append(recorder)
        self.sync_pose()
        recorder.capture(self.data, self.t)
        return recorder

    def cmd_record(self, args: dict[str, Any]) -> dict[str, Any]:
        cmd = "record"
        a.only_known(args, ("path", "fps", "camera", "width", "height"), cmd)
        path = a.string(args, "path", cmd)
        fps = a.number(args, "fps", cmd, default=10.0, minimum=0.1)
        camera = a.string(args, "camera", cmd, default="chase")
        if camera not in self.scene.cameras:
            raise WorldError("not_found", f"no camera {camera!r}")
        width, height = None, None
        if "width" in args or "height" in args:
            width, height = self._size(args, cmd, (640, 480))
        recorder = self.start_recording(path, fps, camera, width, height)
        recorder.command_started = True  # type: ignore[attr-defined]
        return {"path": str(recorder.path), "fps": recorder.fps, "width": recorder.width, "height": recorder.height}

    def cmd_record_stop(self, args: dict[str, Any]) -> dict[str, Any]:
        a.only_known(args, ("path",), "record_stop")
        path = args.get("path")
        stopping = [r for r in self.recorders if getattr(r, "command_started", False)
                    and (path is None or r.path == Path(path))]
        if path is not None and not stopping:
            raise WorldError("not_found", f"no recording to {path}")
        for r in stopping:
            self.recorders.remove(r)
        return {"recordings": [r.close() for r in stopping]}

    def cmd_map(self, args: dict[str, Any]) -> dict[str, Any]:
        a.only_known(args, ("path",), "map")
        path = a.string(args, "path", "map")
        return {"path": str(self.draw_map(path))}

    def draw_map(self, path: str | Path) -> Path:
        """The occupancy map with the markers, the path driven so far and the objects."""
        markers_file = MAPS_DIR / f"{self.scene_name}_markers.json"
        markers = load_markers(markers_file) if markers_file.is_file() else {}
        points = self.path_log + [(self.base.x, self.base.y)]
        return draw_map_png(self.grid, markers, points, self.objects(), path)

    def cmd_shutdown(self, args: dict[str, Any]) -> dict[str, Any]:
        self.stop_requested = True
        return {"t": _r(self.t)}

    # -- dispatch ----------------------------------------------------------------------------

    def handle(self, cmd: str, args: dict[str, Any]) -> dict[str, Any]:
        handler = self.commands.get(cmd)
        if handler is None:
            from stuart_bt.core.suggest import did_you_mean

            raise WorldError("unknown_command", f"no command {cmd!r}{did_you_mean(cmd, list(self.commands))}")
        return handler(args)  # argument checks raise the daemons' CodedError: answered the same way



def _finite(value: float) -> float | None:
    return _r(value, 5) if math.isfinite(value) else None


class _Client:
    def __init__(self, sock: socket.socket) -> None:
        self.sock = sock
        self.lines = LineBuffer(MAX_LINE)
        self.out = bytearray()


class Server:
    """The loop: physics steps, paced by the clock's permit and ``speed``, with requests
    answered in between."""

    def __init__(self, world: World, socket_path: str, clock: ClockFile, speed: float = 0.0,
                 watch_stdin: bool = True, viewer: Any = None, out_fd: int = 1, hold: bool = False) -> None:
        self.world = world
        self.hold = hold  # take no step until a clock driver has attached (a run starts at t = 0)
        self.socket_path = socket_path
        self.clock = clock
        self.speed = speed
        self.viewer = viewer
        self.out_fd = out_fd
        self.selector = selectors.DefaultSelector()
        self.clients: dict[int, _Client] = {}
        self.signals: list[int] = []
        self.reason = ""
        self.listener = self._listen(socket_path)
        self.selector.register(self.listener, selectors.EVENT_READ, "listen")
        self.stdin_fd: int | None = None
        if watch_stdin:
            try:
                fd = sys.stdin.fileno()
                self.selector.register(fd, selectors.EVENT_READ, "stdin")
                self.stdin_fd = fd
            except (ValueError, OSError, AttributeError):
                pass  # no usable stdin: nothing to watch
        for signum in (signal.SIGTERM, signal.SIGINT):
            signal.signal(signum, lambda signum, _frame: self.signals.append(signum))

    @staticmethod
    def _listen(path: str) -> socket.socket:
        if os.path.exists(path):
            if not stat.S_ISSOCK(os.stat(path).st_mode):
                raise FileExistsError(f"{path} exists and is not a socket")
            os.unlink(path)  # stale socket of a world that died
        sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        sock.bind(path)
        sock.listen(32)
        sock.setblocking(False)
        return sock

    # -- the loop ----------------------------------------------------------------------------

    def run(self) -> str:
        world, clock = self.world, self.clock
        wall_ref, sim_ref = time.monotonic(), world.t
        rate_wall, rate_sim = wall_ref, world.t
        idle = 5e-5
        held_by_permit = False
        next_viewer = 0.0
        clock.publish(world.t)
        while not self._should_stop():
            now_wall = time.monotonic()
            t = world.t
            if self.hold and clock.driven():
                self.hold = False
            if self.hold or (clock.driven() and t >= clock.permit):
                held_by_permit = True
                self._serve(0.0)
                time.sleep(idle)
                idle = min(idle * 2.0, 5e-4)
            else:
                if held_by_permit:  # the speed cap counts from when the world may go again
                    held_by_permit = False
                    wall_ref, sim_ref = now_wall, t
                allowed = math.inf if self.speed <= 0 else sim_ref + self.speed * (now_wall - wall_ref)
                if t < allowed:
                    world.step()
                    clock.publish(world.t)
                    idle = 5e-5
                    if allowed - world.t > 0.1 and self.speed > 0:  # fell behind: do not burst later
                        wall_ref, sim_ref = now_wall, world.t
                    self._serve(0.0)
                else:
                    self._serve(min((t - allowed) / self.speed + 1e-4, 0.005))
            if now_wall - rate_wall >= RATE_WINDOW:
                clock.set_rate((world.t - rate_sim) / (now_wall - rate_wall))
                rate_wall, rate_sim = now_wall, world.t
            if self.viewer is not None and now_wall >= next_viewer:
                next_viewer = now_wall + VIEWER_PERIOD
                if not self.viewer.is_running():
                    self.reason = "the viewer window was closed"
                    break
                with self.viewer.lock():
                    world.sync_pose()
                    self.viewer.sync()
        return self.reason

    def _should_stop(self) -> bool:
        if self.signals:
            self.reason = f"received {signal.Signals(self.signals[0]).name}"
            return True
        if self.world.stop_requested:
            self.reason = "shutdown requested"
            return True
        return bool(self.reason)

    def _serve(self, timeout: float) -> None:
        if timeout > 0 and timeout < 0.001:  # epoll waits whole milliseconds: sleep the rest
            events = self.selector.select(0)
            if not events:
                time.sleep(timeout)
                events = self.selector.select(0)
        else:
            events = self.selector.select(timeout)
        for key, mask in events:
            if key.data == "listen":
                self._accept()
            elif key.data == "stdin":
                self._read_stdin()
            else:
                client = self.clients.get(key.fd)
                if client is None:
                    continue
                if mask & selectors.EVENT_READ:
                    self._read(client)
                if mask & selectors.EVENT_WRITE and key.fd in self.clients:
                    self._flush(client)

    def _accept(self) -> None:
        try:
            sock, _ = self.listener.accept()
        except (BlockingIOError, InterruptedError):
            return
        sock.setblocking(False)
        client = _Client(sock)
        self.clients[sock.fileno()] = client
        self.selector.register(sock, selectors.EVENT_READ, "client")

    def _read_stdin(self) -> None:
        try:
            data = os.read(self.stdin_fd, READ_CHUNK)  # type: ignore[arg-type]
        except OSError:
            data = b""
        if not data:
            self.reason = "stdin closed (the parent went away)"

    def _read(self, client: _Client) -> None:
        try:
            data = client.sock.recv(READ_CHUNK)
        except (BlockingIOError, InterruptedError):
            return
        except OSError:
            data = b""
        if not data:
            self._drop(client)
            return
        for line in client.lines.feed(data):
            self._send(client, self._answer(line))
            if client.sock.fileno() not in self.clients:
                return

    def _answer(self, line: bytes | Oversize) -> dict[str, Any]:
        if isinstance(line, Oversize):
            return {"id": None, "ok": False, "error": "bad_request",
                    "reason": f"line of {line.size}+ bytes is too long"}
        request_id: Any = None
        try:
            message = decode(line)
            request_id = message.get("id")
            cmd = message.get("cmd")
            args = message.get("args") or {}
            if not isinstance(cmd, str) or not cmd:
                raise WorldError("bad_request", "a request needs a string 'cmd'")
            if not isinstance(args, dict):
                raise WorldError("bad_request", f"'args' must be an object, got {type(args).__name__}")
            result = self.world.handle(cmd, args)
            return {"id": request_id, "ok": True, "result": result}
        except ProtocolError as e:
            return {"id": request_id, "ok": False, "error": "bad_request", "reason": e.reason}
        except CodedError as e:  # a WorldError, or an argument check shared with the daemons
            return {"id": request_id, "ok": False, "error": e.code, "reason": e.reason}
        except Exception as e:  # noqa: BLE001 - a bug must not take the world down: report it, keep running
            traceback.print_exc()
            return {"id": request_id, "ok": False, "error": "internal", "reason": f"{type(e).__name__}: {e}"}

    def _send(self, client: _Client, message: dict[str, Any]) -> None:
        try:
            client.out += encode(message)
        except ValueError as e:  # NaN or the like in a result
            client.out += encode({"id": message.get("id"), "ok": False, "error": "internal", "reason": str(e)})
        self._flush(client)

    def _flush(self, client: _Client) -> None:
        try:
            while client.out:
                sent = client.sock.send(client.out)
                del client.out[:sent]
        except (BlockingIOError, InterruptedError):
            pass
        except OSError:
            self._drop(client)
            return
        events = selectors.EVENT_READ | (selectors.EVENT_WRITE if client.out else 0)
        self.selector.modify(client.sock, events, "client")

    def _drop(self, client: _Client) -> None:
        fd = client.sock.fileno()
        if fd in self.clients:
            del self.clients[fd]
            with contextlib.suppress(KeyError, ValueError):
                self.selector.unregister(client.sock)
        client.sock.close()

    def close(self) -> None:
        for client in list(self.clients.values()):
            try:  # last replies (e.g. to shutdown) go out before the socket closes
                client.sock.setblocking(True)
                client.sock.settimeout(0.5)
                if client.out:
                    client.sock.sendall(client.out)
            except OSError:
                pass
            self._drop(client)
        self.selector.close()
        self.listener.close()
        with contextlib.suppress(FileNotFoundError):
            os.unlink(self.socket_path)


# -- the process ------------------------------------------------------------------------------

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
        ready = {"type": "ready", "socket": options.socket, "clock": options.clock, "timestep": world.dt,
                 "pid": os.getpid(), "scene": world.scene_name, "robot": str(scene.robot_path),
                 "objects": sorted(scene.objects), "speed": speed}
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
