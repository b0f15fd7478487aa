"""The simulated world: the MuJoCo model and data, the robot's base and arm controllers, the
free objects, the cameras and recordings, and the commands a client may send (``cmd_*``).

The robot is kinematic: every step its base pose comes from :class:`.base.BaseController` and
its joints from :class:`.arms.JointPlayer`; only the free objects are simulated. The server
(:mod:`.server`) steps the world and answers requests between steps, so every command here
runs on the one physics thread and sees a consistent state.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

from stuart_bt.core.jsonfile import is_finite_number
from stuart_bt.daemon import args as a
from stuart_bt.maps.markers import load_markers
from stuart_bt.maps.picture import draw_map_png

from .arms import SIDES, Hands, JointPlayer
from .base import BaseController, BaseLimits, PersonCheck, wrap
from .errors import WorldError
from .occupancy import footprint_hits, grid_from_model, static_footprints
from .render import Cameras, Recorder, save_png
from .scene import MAPS_DIR, Scene

FOOTPRINT_RADIUS = 0.2  # the base's own footprint (legs and feet) for the collision flag (m)
RAISED = (0.45, 0.12)  # above knee height (m), e.g. a table top, only the hips and torso (radius m) can touch
PERSON_HEIGHT = 1.7
PERSON_PARK = (-4.0, -6.0, -3.0)  # outside the walls and under the floor: out of every view
PATH_LOG_STEP = 0.02  # metres between logged points of the driven path
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
                                  "camera_pose": frame.pose, "base": self.localised_base()}
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
