"""perception: how well and how fast the camera -> detector -> projection -> memory pipeline works.

- **Position error** (torso frame) against the sim's ground truth over seeded random placements of
  the bottle, the cup and the apple on the kitchen table, the robot at the kitchen marker and at
  two poses near it: every object the detector reports counts. Anchor: the original system's
  estimate on the same frames (median depth in the shrunk box at the box centre, no shape
  model), so the ratio says what the centre reconstruction buys.
- **Pipeline rate** on recorded frames (PNG colour + 16-bit depth + labels, preloaded, so file
  decoding is not counted): detection + projection + memory per frame at 424x240, on this
  machine. Anchor: the original system's 17 Hz (colour detection, from the thesis; not measured
  here, there is nothing of it to run).
- **Render rate** of the sim head camera as perception asks for it (colour + depth + segmentation,
  raw .npy through /dev/shm). Anchor: colour + depth written as PNG + .npy (``sim.render.fps``'s
  request), interleaved in the same world.
- **Tour speed with vision on**: a short tour (kitchen: find the bottle; workbench: find the cup)
  on --backend sim, sim s per wall s. Anchor: the same tour without the finds.
"""

from __future__ import annotations

import math
import statistics
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from .result import Anchor, Bound, Goal, Result
from .stats import paired_ratio

NAME = "perception"
GOAL_MEAN_M = 0.01
GOAL_MAX_M = 0.025
GOAL_RATE_HZ = 30.0  # the absolute goal the ratio goal replaces (information)
# The rate over the original system's 17 Hz, a constant (nothing of it runs here to time): 30/17,
# rounded up. The only speed goal here whose anchor is not timed: with ~15x headroom it says
# "not slower than 30 Hz", which a machine 3.5x slower still meets.
GOAL_RATE = Goal(1.8, ">=", was=f">= {GOAL_RATE_HZ:g} Hz")
ORIGINAL_RATE_HZ = 17.0
TABLE_X, TABLE_Y = (3.97, 4.62), (0.96, 2.04)  # kitchen table top, objects' centres kept 6 cm inside
REST_Z = {"bottle": 0.855, "cup": 0.80, "apple": 0.79}
VIEWS = ((3.5, 1.5, 0.0), (3.45, 1.25, 0.25), (3.45, 1.75, -0.25))  # kitchen marker and two nearby poses
SIZE = (424, 240)


def placements(world: Any, count: int, seed: int) -> tuple[list[float], list[float], list[Any]]:
    """Errors (m) of the pipeline and of the original estimate, and the frames, over ``count``
    placements."""
    from stuart_bt.perception.pipeline import Perception
    from stuart_bt.perception.projection import CameraMount, back_project, box_centre, median_depth, world_to_torso
    from stuart_bt.perception.sim_camera import SimCamera
    from stuart_bt.perception.sim_detector import SimDetector

    rng = np.random.default_rng(seed)
    mount = CameraMount.sim()
    perception = Perception(SimDetector(), mount)
    camera = SimCamera(world.client(), *SIZE)
    ours: list[float] = []
    original: list[float] = []
    frames = []
    driver = world.clock(driver=True)
    try:
        for i in range(count):
            x, y, yaw = VIEWS[i % len(VIEWS)]
            world.call("set_base", x=x, y=y, yaw=yaw)
            spots: list[tuple[float, float]] = []
            for label in REST_Z:
                while True:
                    px, py = rng.uniform(*TABLE_X), rng.uniform(*TABLE_Y)
                    if all(math.hypot(px - a, py - b) > 0.15 for a, b in spots):
                        break
                spots.append((px, py))
                world.call("set_object", label=label, x=float(px), y=float(py), z=REST_Z[label] + 0.002, yaw=0.0)
            driver.sleep_until(driver.now() + 0.4)  # settle
            truth = world.call("state")["objects"]
            frame = camera.read()
            frames.append(frame)
            for p in perception.process(frame)[0]:
                t = truth[p.detection.label]
                true_torso = world_to_torso(np.array([t["x"], t["y"], t["z"]]), frame.robot_pose)
                ours.append(float(np.linalg.norm(p.torso - true_torso)))
                depth = median_depth(frame.depth, p.detection.box, 0.5)
                if depth is not None:
                    u, v = box_centre(p.detection.box)
                    naive = mount.to_torso(back_project(u, v, depth, frame.intrinsics))
                    original.append(float(np.linalg.norm(naive - true_torso)))
    finally:
        driver.close()
        camera.close()
    return ours, original, frames


def pipeline_rate(frames: list[Any], seconds: float) -> tuple[float, int]:
    """Frames per second of detection + projection + memory on recorded frames read back."""
    from stuart_bt.core.clock import ManualClock
    from stuart_bt.perception.memory import SpatialMemory
    from stuart_bt.perception.pipeline import Perception
    from stuart_bt.perception.projection import CameraMount
    from stuart_bt.perception.recorded import RecordedFrames, save_frame
    from stuart_bt.perception.sim_detector import SimDetector

    with tempfile.TemporaryDirectory(prefix="stuart-bench-frames-") as tmp:
        for i, frame in enumerate(frames):
            save_frame(tmp, i, frame)
        source = RecordedFrames(tmp, loop=True, preload=True)
    clock = ManualClock()
    perception = Perception(SimDetector(), CameraMount.sim(), SpatialMemory(clock))
    for _ in range(5):  # warm up
        perception.process(source.read())
    done = 0
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        clock.advance(1 / 30)
        frame = source.read()
        perception.process(frame)
        done += 1
    return done / (time.perf_counter() - start), done


def render_rates(world: Any, rounds: int, per_round: int) -> dict[str, list[float]]:
    from stuart_bt.perception.sim_camera import SimCamera

    camera = SimCamera(world.client(), *SIZE)
    rates: dict[str, list[float]] = {"perception": [], "png": []}
    driver = world.clock(driver=True)
    try:
        with tempfile.TemporaryDirectory(prefix="stuart-bench-render-") as tmp:
            def png() -> None:
                world.call("render", camera="head_camera", width=SIZE[0], height=SIZE[1], depth=True,
                           path=f"{tmp}/frame.png", depth_path=f"{tmp}/frame_depth.npy")

            kinds = {"perception": camera.read, "png": png}
            for _ in range(2):
                camera.read()
                png()
            for r in range(rounds):
                for kind in (("perception", "png") if r % 2 == 0 else ("png", "perception")):
                    start = time.perf_counter()
                    for _ in range(per_round):
                        kinds[kind]()
                    rates[kind].append(per_round / (time.perf_counter() - start))
    finally:
        driver.close()
        camera.close()
    return rates


VISION_TOUR = """
root:
  sequence:
    - navigate: kitchen
    - find: {object: bottle}
    - navigate: workbench
    - find: {object: cup}
"""


def tour_rate(with_vision: bool) -> float:
    from stuart_bt.run.session import RunOptions, Session
    from stuart_bt.tree.loader import load_tree_text

    text = VISION_TOUR if with_vision else "\n".join(line for line in VISION_TOUR.splitlines() if "find" not in line)
    repo = Path(__file__).resolve().parents[1]
    spec = load_tree_text(text, str(repo / "trees" / "vision_tour.yaml"),
                          markers_file=repo / "sim" / "maps" / "lab_markers.json")
    session = Session(spec, RunOptions(backend="sim", seed=0))
    try:
        session.start()
        sim0, wall0 = session.clock.now(), time.perf_counter()
        outcome = session.run()
        wall1, sim1 = time.perf_counter(), session.clock.now()
    finally:
        session.close()
    if outcome.status != "SUCCESS":
        raise RuntimeError(f"the vision tour ended {outcome.status}: {outcome.reason}")
    return (sim1 - sim0) / (wall1 - wall0)


def run(quick: bool) -> list[Result]:
    from stuart_bt.sim.world.client import launch_world

    count = 6 if quick else 60  # --quick is a smoke test; the goal needs >= 20 placements (full run)
    with launch_world(seed=0, stderr=subprocess.DEVNULL) as world:
        ours, original, frames = placements(world, count, seed=5)
        rates = render_rates(world, *((2, 2) if quick else (6, 8)))
    hz, processed = pipeline_rate(frames, 0.5 if quick else 5.0)
    tours = 1 if quick else 3
    plain, vision = [], []
    for _ in range(tours):
        plain.append(tour_rate(False))
        vision.append(tour_rate(True))

    where = (f"{count} placements of bottle, cup and apple on the kitchen table (seed 5), robot at the kitchen marker "
             f"and two poses beside it, {SIZE[0]}x{SIZE[1]}, {len(ours)} detections")
    mean, worst = statistics.fmean(ours), max(ours)
    render, png = statistics.median(rates["perception"]), statistics.median(rates["png"])
    return [
        Result(f"{NAME}.position.error_mean", mean, "m",
               Anchor("original estimate (median depth at the box centre)", statistics.fmean(original)),
               goal=Bound(GOAL_MEAN_M, "<=", "m"),
               note=f"torso frame, vs the sim's object origins; {where}"),
        Result(f"{NAME}.position.error_max", worst, "m",
               Anchor("original estimate (median depth at the box centre)", max(original)),
               goal=Bound(GOAL_MAX_M, "<=", "m"),
               note=f"torso frame; p95 {float(np.percentile(ours, 95)):.4f} m; {where}"),
        Result(f"{NAME}.pipeline.rate", hz, "frames/s",
               Anchor("original system, colour detection (thesis figure, not measured here)", ORIGINAL_RATE_HZ,
                      timed=False), goal=GOAL_RATE,
               note=(f"sim detector + projection + memory on {len(frames)} recorded {SIZE[0]}x{SIZE[1]} frames "
                     f"(preloaded, looped), {processed} frames, one thread")),
        Result(f"{NAME}.render.fps", render, "frames/s",
               Anchor(f"head_camera colour + depth to PNG + .npy, {SIZE[0]}x{SIZE[1]}", png),
               note=("SimCamera.read: colour + depth + segmentation as raw .npy in /dev/shm, world held by a driver "
                     "clock; interleaved rounds; ratio = median of per-round ratios; the issue's reference: ~23 "
                     "frames/s colour + depth at 424x240 for a simple scene"),
               paired_ratio=paired_ratio(rates["perception"], rates["png"])),
        Result(f"{NAME}.tour.real_time_factor_with_vision", statistics.median(vision), "sim s/wall s",
               Anchor("the same tour without the finds", statistics.median(plain)),
               note=(f"entrance -> kitchen (find bottle) -> workbench (find cup) on --backend sim, lockstep, "
                     f"{tours} run(s) each, interleaved; vision renders only while a find runs"),
               paired_ratio=paired_ratio(vision, plain)),
    ]
