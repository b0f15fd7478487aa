"""Recorded frames: a folder of PNG colour, 16-bit depth PNG and one intrinsics JSON.

Layout (what ``stuart-bt perceive --save-frames`` writes, and what a RealSense recording
converted by hand can look like)::

    intrinsics.json        {"fx", "fy", "cx", "cy", "width", "height", "depth_scale": 0.001,
                            "label_names": [...] (optional, for sim label images)}
    000000_color.png       8-bit RGB
    000000_depth.png       16-bit, depth = value x depth_scale metres, 0 = no reading
    000000_labels.png      optional 16-bit: 0 nothing, i + 1 = label_names[i] (sim recordings)
    000000.json            optional {"t": s, "robot_pose": {"x", "y", "yaw"}}

Frames are read in name order and, with ``loop``, replayed forever (benchmarks, demos).
"""

from __future__ import annotations

import json
from pathlib import Path

import cv2
import numpy as np

from ..core.jsonfile import to_json
from ..core.world import Pose
from .frames import CameraError, CameraSource, Frame, Intrinsics

DEPTH_SCALE = 0.001  # metres per depth unit (the RealSense default: millimetres)


class RecordedFrames(CameraSource):
    name = "recorded"

    def __init__(self, folder: str | Path, loop: bool = False, preload: bool = False) -> None:
        self.folder = Path(folder)
        meta_path = self.folder / "intrinsics.json"
        if not meta_path.is_file():
            raise CameraError(f"recorded frames: no intrinsics.json in {self.folder}")
        try:
            meta = json.loads(meta_path.read_text(encoding="utf-8"))
            self.intrinsics = Intrinsics.from_dict(meta)
        except (ValueError, KeyError, TypeError) as e:
            raise CameraError(f"recorded frames: {meta_path} needs fx, fy, cx, cy, width, height ({e})") from None
        self.depth_scale = float(meta.get("depth_scale", DEPTH_SCALE))
        self.label_names = tuple(meta.get("label_names", ()))
        self.stems = sorted(p.name[: -len("_color.png")] for p in self.folder.glob("*_color.png"))
        if not self.stems:
            raise CameraError(f"recorded frames: no *_color.png in {self.folder}")
        self.loop = loop
        self.index = 0
        self._cache: list[Frame] | None = [self._load(s) for s in self.stems] if preload else None

    def __len__(self) -> int:
        return len(self.stems)

    def read(self) -> Frame:
        if self.index >= len(self.stems):
            if not self.loop:
                raise CameraError(f"recorded frames: all {len(self.stems)} frames of {self.folder} read")
            self.index = 0
        i = self.index
        self.index += 1
        return self._cache[i] if self._cache is not None else self._load(self.stems[i])

    def _load(self, stem: str) -> Frame:
        base = self.folder / stem
        bgr = cv2.imread(f"{base}_color.png", cv2.IMREAD_COLOR)
        raw = cv2.imread(f"{base}_depth.png", cv2.IMREAD_UNCHANGED)
        if bgr is None or raw is None or raw.dtype != np.uint16:
            raise CameraError(f"recorded frames: {stem} needs {stem}_color.png and a 16-bit {stem}_depth.png")
        labels = None
        label_path = Path(f"{base}_labels.png")
        raw_labels = cv2.imread(str(label_path), cv2.IMREAD_UNCHANGED) if label_path.is_file() else None
        if raw_labels is not None:
            labels = raw_labels.astype(np.int16) - 1
        t, pose = 0.0, Pose()
        info = Path(f"{base}.json")
        if info.is_file():
            doc = json.loads(info.read_text(encoding="utf-8"))
            t, pose = float(doc.get("t", 0.0)), Pose.from_dict(doc.get("robot_pose", {}))
        return Frame(cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB), raw.astype(np.float32) * self.depth_scale, self.intrinsics,
                     t, pose, labels, self.label_names)


def save_frame(folder: str | Path, index: int, frame: Frame, depth_scale: float = DEPTH_SCALE) -> Path:
    """Write one frame in the layout above (and intrinsics.json, if missing)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    meta = folder / "intrinsics.json"
    if not meta.exists():
        meta.write_text(to_json({**frame.intrinsics.to_dict(), "depth_scale": depth_scale,
                                    "label_names": list(frame.label_names)}, indent=2) + "\n", encoding="utf-8")
    base = folder / f"{index:06d}"
    cv2.imwrite(f"{base}_color.png", cv2.cvtColor(frame.rgb, cv2.COLOR_RGB2BGR))
    depth_units = np.clip(np.round(frame.depth / depth_scale), 0, 65535).astype(np.uint16)
    cv2.imwrite(f"{base}_depth.png", depth_units)
    if frame.labels is not None:
        cv2.imwrite(f"{base}_labels.png", (frame.labels.astype(np.int32) + 1).astype(np.uint16))
    Path(f"{base}.json").write_text(to_json({"t": frame.t, "robot_pose": frame.robot_pose.to_dict()}) + "\n",
                                    encoding="utf-8")
    return base
