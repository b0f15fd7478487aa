"""``stuart-bt perceive``: one look through the camera, printed and drawn.

    stuart-bt perceive --backend sim --at kitchen -o out/kitchen.png --map-out out/kitchen_map.png
    stuart-bt perceive --backend sim --at kitchen --place cup=4.2,1.25 --frames 5 --json
    stuart-bt perceive --backend recorded --from out/frames -o out/replay.png
    stuart-bt perceive --backend realsense --detector yolo --weights models/yolov8n.onnx

Prints each detection (label, confidence, box, depth, torso and world position; in the sim also
the sim's own position of the object and the error), writes the annotated picture, and with
``--map-out`` the lab map with the spatial memory drawn on it.
"""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

from ..core.errors import StuartError
from ..core.jsonfile import to_json

HELP = "look once: detections with torso and world positions, an annotated picture"
EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2


class PerceiveError(StuartError):
    """Bad input or a camera that cannot start: one sentence, no traceback, exit 2."""


def add_command(subparsers: Any) -> argparse.ArgumentParser:
    p = subparsers.add_parser("perceive", help=HELP, description=__doc__.split("\n\n")[0])
    p.add_argument("--backend", choices=("sim", "recorded", "realsense"), default="sim")
    p.add_argument("--at", metavar="MARKER", help="sim: stand the robot at this marker (default: kitchen)")
    p.add_argument("--place", action="append", default=[], metavar="LABEL=X,Y",
                   help="sim: stand an object at map (x, y) on whatever surface is there first (repeatable)")
    p.add_argument("--from", dest="folder", metavar="DIR", help="recorded: the folder of frames")
    p.add_argument("--resolution", default="424x240", help="424x240 (default) or 640x480")
    p.add_argument("--frames", type=int, default=1, help="frames to look at (memory smooths them; default 1)")
    p.add_argument("--threshold", type=float, default=0.75, help="detector confidence threshold (default 0.75)")
    p.add_argument("--detector", choices=("sim", "yolo"), default=None, help="default: sim, or yolo on realsense")
    p.add_argument("--weights", metavar="FILE", help="yolo: local ONNX weights (nothing is downloaded)")
    p.add_argument("--mount", choices=("sim", "thesis"), default="sim",
                   help="camera -> torso transform: the sim robot's mount or the thesis's (theta 48 deg)")
    p.add_argument("-o", "--output", metavar="PNG", help="write the annotated camera image here")
    p.add_argument("--map-out", metavar="PNG", help="sim: write the lab map with the spatial memory")
    p.add_argument("--save-frames", metavar="DIR", help="also record the frames (replay with --backend recorded)")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the table")
    p.set_defaults(func=cmd_perceive)
    return p


def cmd_perceive(args: argparse.Namespace) -> int:
    try:
        return _perceive(args)
    except PerceiveError as e:
        print(f"stuart-bt perceive: {e}", file=sys.stderr)
        return EXIT_USAGE


def _perceive(args: argparse.Namespace) -> int:
    from ..core.clock import ManualClock
    from ..perception.frames import CameraError
    from ..perception.memory import SpatialMemory
    from ..perception.pipeline import Perception
    from ..perception.projection import CameraMount
    from ..perception.sim_camera import parse_resolution

    if args.frames < 1:
        raise PerceiveError(f"--frames must be at least 1, got {args.frames}")
    if not 0.0 <= args.threshold <= 1.0:
        raise PerceiveError(f"--threshold must be in 0..1, got {args.threshold}")
    try:
        width, height = parse_resolution(args.resolution)
    except ValueError as e:
        raise PerceiveError(str(e)) from None
    if args.backend != "sim" and (args.at or args.place or args.map_out):
        raise PerceiveError("--at, --place and --map-out need --backend sim")
    if args.backend == "recorded" and not args.folder:
        raise PerceiveError("--backend recorded needs --from DIR")
    clock = ManualClock()
    memory = SpatialMemory(clock)
    mount = CameraMount.thesis() if args.mount == "thesis" else CameraMount.sim()
    perception = Perception(_detector(args), mount, memory)
    with _Source(args, width, height) as source:
        frames = []
        try:
            for _ in range(args.frames):
                frame = source.camera.read()
                clock.set(frame.t)
                frames.append((frame, perception.process(frame)[0]))
        except CameraError as e:
            raise PerceiveError(str(e)) from None
        truth = source.truth()
        if args.map_out:
            source.draw_map(args.map_out, memory.summary()["objects"])
    frame, located = frames[-1]
    if args.save_frames:
        from ..perception.recorded import save_frame

        for i, (f, _) in enumerate(frames):
            save_frame(args.save_frames, i, f)
    if args.output:
        from ..perception.annotate import save_annotated

        save_annotated(frame.rgb, located, args.output)
    report = _report(frame, located, memory.summary(), truth)
    if args.json:
        print(to_json(report, indent=2))
    else:
        _print_table(report, args)
    return EXIT_OK if located else EXIT_FAILED


def _detector(args: argparse.Namespace) -> Any:
    kind = args.detector or ("yolo" if args.backend == "realsense" else "sim")
    if kind == "yolo":
        from ..perception.yolo import DetectorConfigError, YoloDetector

        try:
            return YoloDetector(args.weights, threshold=args.threshold)
        except DetectorConfigError as e:
            raise PerceiveError(str(e)) from None
    if args.backend == "realsense":
        raise PerceiveError("the sim detector needs the simulator's segmentation; use --detector yolo on a RealSense")
    from ..perception.sim_detector import SimDetector

    return SimDetector(args.threshold)


class _Source:
    """The camera, and for the sim the world around it (started, arranged, closed)."""

    def __init__(self, args: argparse.Namespace, width: int, height: int) -> None:
        self.args, self.width, self.height = args, width, height
        self.world: Any = None
        self.camera: Any = None

    def __enter__(self) -> _Source:
        from ..perception.frames import CameraError

        try:
            if self.args.backend == "sim":
                self._start_sim()
            elif self.args.backend == "recorded":
                from ..perception.recorded import RecordedFrames

                self.camera = RecordedFrames(self.args.folder, loop=True)
            else:
                from ..perception.realsense import RealSenseCamera

                self.camera = RealSenseCamera(self.width, self.height)
        except CameraError as e:
            self.__exit__()
            raise PerceiveError(str(e)) from None
        except BaseException:
            self.__exit__()
            raise
        return self

    def _start_sim(self) -> None:
        import os

        os.environ.setdefault("MUJOCO_GL", "egl")
        from ..core.suggest import did_you_mean
        from ..maps.markers import load_markers
        from ..perception.sim_camera import SimCamera
        from ..sim.world.client import WorldError, launch_world
        from ..sim.world.scene import MAPS_DIR

        markers = load_markers(MAPS_DIR / "lab_markers.json")
        at = self.args.at or "kitchen"
        if at not in markers:
            raise PerceiveError(f"unknown marker {at!r}{did_you_mean(at, markers)}; "
                                f"markers: {', '.join(sorted(markers))}")
        places = [_parse_place(text) for text in self.args.place]
        m = markers[at]
        import subprocess

        self.world = launch_world(start=(m.x, m.y, m.yaw), stderr=subprocess.DEVNULL)
        objects = self.world.call("info")["objects"]
        for label, x, y in places:
            if label not in objects:
                raise PerceiveError(f"no object {label!r} in the scene{did_you_mean(label, objects)}; "
                                    f"objects: {', '.join(sorted(objects))}")
            try:
                self._stand(label, x, y)
            except WorldError as e:
                raise PerceiveError(f"cannot place the {label} at ({x}, {y}): {e}") from None
        driver = self.world.clock(driver=True)
        driver.sleep_until(driver.now() + 0.5)  # let what was placed settle
        driver.close()
        self.camera = SimCamera(self.world.client(), self.width, self.height)

    def _stand(self, label: str, x: float, y: float) -> None:
        from ..perception.centre import SHAPES

        surface = self.world.call("surface", x=x, y=y)["z"]
        shape = SHAPES.get(label)
        rest = shape.base_to_centre if shape else 0.05
        self.world.call("set_object", label=label, x=x, y=y, z=surface + rest + 0.002, yaw=0.0)

    def truth(self) -> dict[str, dict[str, float]]:
        return self.world.call("state")["objects"] if self.world is not None else {}

    def draw_map(self, out: str, memory: list[dict[str, Any]]) -> None:
        from ..maps.markers import load_markers
        from ..maps.picture import draw_map_png
        from ..sim.world.occupancy import scene_grid
        from ..sim.world.scene import MAPS_DIR

        state = self.world.call("state")
        base = state["base"]
        draw_map_png(scene_grid(), load_markers(MAPS_DIR / "lab_markers.json"), [(base["x"], base["y"])],
                     state["objects"], out, memory=memory)

    def __exit__(self, *exc: object) -> None:
        if self.camera is not None:
            self.camera.close()
        if self.world is not None:
            self.world.close()


def _parse_place(text: str) -> tuple[str, float, float]:
    label, _, where = text.partition("=")
    try:
        x, y = (float(v) for v in where.split(","))
    except ValueError:
        raise PerceiveError(f"--place wants LABEL=X,Y (metres, map frame), got {text!r}") from None
    if not label:
        raise PerceiveError(f"--place wants LABEL=X,Y, got {text!r}")
    return label, x, y


def _report(frame: Any, located: list[Any], memory: dict[str, Any], truth: dict[str, Any]) -> dict[str, Any]:
    detections = []
    for p in located:
        entry = p.to_dict()
        entry["distance"] = round(math.hypot(p.world[0] - frame.robot_pose.x, p.world[1] - frame.robot_pose.y), 3)
        if p.detection.label in truth:
            t = truth[p.detection.label]
            entry["sim"] = [t["x"], t["y"], t["z"]]
            entry["error"] = round(math.dist(entry["sim"], entry["world"]), 4)
        detections.append(entry)
    return {"t": frame.t, "robot_pose": frame.robot_pose.to_dict(), "detections": detections, "memory": memory}


def _print_table(report: dict[str, Any], args: argparse.Namespace) -> None:
    pose = report["robot_pose"]
    print(f"robot at ({pose['x']:.2f}, {pose['y']:.2f}) facing {math.degrees(pose['yaw']):.0f} deg; "
          f"{len(report['detections'])} detection(s)")
    if report["detections"]:
        print(f"{'label':<8} {'conf':>5} {'box (u0 v0 u1 v1)':<19} {'depth':>6}  {'torso x y z (m)':<22} "
              f"{'world x y z (m)':<22} {'sim error':>9}")
    for d in report["detections"]:
        box = " ".join(str(v) for v in d["box"])
        torso = " ".join(f"{v:6.3f}" for v in d["torso"])
        world = " ".join(f"{v:6.3f}" for v in d["world"])
        error = f"{d['error'] * 100:6.1f} cm" if "error" in d else ""
        print(f"{d['label']:<8} {d['confidence']:>5.2f} {box:<19} {d['depth']:>6.3f}  {torso:<22} {world:<22} "
              f"{error:>9}")
    for path, what in ((args.output, "annotated image"), (args.map_out, "map with memory"),
                       (args.save_frames, "frames")):
        if path:
            print(f"wrote {what}: {path}")
