"""The gesture recorder's server side: joints and limits, and gesture files in one folder.

Joint names, limits and the neutral pose come from the robot description (through the gesture
skill's own tables), so a slider can never go where the player would refuse to. Files are written
with the gesture skill's ``save_gesture_file`` (it checks every keyframe first and writes nothing
on a problem) and read back with ``load_gesture_file``: what the page saves is exactly what the
``gesture`` leaf's ``file:`` plays.
"""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path
from typing import Any

from ..core.errors import StuartError
from ..skills.gesture.keyframes import JOINT_GROUPS, joint_limits

FILE_NAME = re.compile(r"[a-z0-9][a-z0-9_\-]{0,39}")  # used with fullmatch: "$" would let a trailing newline in


class GestureDeskError(StuartError, ValueError):
    """A request the recorder refuses; ``problems`` lists every reason."""

    def __init__(self, problems: list[str]) -> None:
        super().__init__("; ".join(problems))
        self.problems = problems


@cache  # the robot description does not change while serving
def joint_table() -> list[dict[str, Any]]:
    """Every joint a gesture may move, grouped as the sliders are: name, group, limits, neutral."""
    from ..skills.gesture.keyframes import NEUTRAL

    limits = joint_limits()
    rows = []
    for name, (lo, hi) in limits.items():
        group = next(g for g, prefix, hand in reversed(JOINT_GROUPS)
                     if name.startswith(prefix) and hand == ("_hand_" in name))
        rows.append({"name": name, "group": group, "lower": lo, "upper": hi,
                     "neutral": float(NEUTRAL.get(name, min(max(0.0, lo), hi)))})
    return rows


class GestureFolder:
    """Gesture files ``<folder>/<name>.json``; the name is the file name, a gesture's name inside."""

    def __init__(self, folder: str | Path) -> None:
        self.folder = Path(folder)

    def path_for(self, name: str) -> Path:
        if not isinstance(name, str) or not FILE_NAME.fullmatch(name):
            raise GestureDeskError([f"gesture name {name!r} must be lower-case letters, digits, '_' or '-' "
                                    "(at most 40, e.g. 'big_wave')"])
        return self.folder / f"{name}.json"

    def names(self) -> list[str]:
        if not self.folder.is_dir():
            return []
        return sorted(p.stem for p in self.folder.glob("*.json") if FILE_NAME.fullmatch(p.stem))

    def save(self, name: str, keyframes: Any) -> Path:
        from ..skills.gesture.backend import Keyframe
        from ..skills.gesture.keyframes import GestureFileError, save_gesture_file, validate_keyframes

        path = self.path_for(name)
        if not isinstance(keyframes, list):
            raise GestureDeskError(["'keyframes' must be a list of {t, joints}"])
        problems = validate_keyframes(keyframes)
        if problems:
            raise GestureDeskError(problems)
        frames = [Keyframe(float(k["t"]), {j: float(v) for j, v in k["joints"].items()}) for k in keyframes]
        try:
            return save_gesture_file(path, name, frames)
        except GestureFileError as e:
            raise GestureDeskError(e.problems) from None

    def load(self, name: str) -> dict[str, Any]:
        from ..core.suggest import did_you_mean
        from ..skills.gesture.keyframes import GestureFileError, load_gesture_file

        path = self.path_for(name)
        if not path.exists():
            raise GestureDeskError([f"no gesture {name!r}{did_you_mean(name, self.names())}"])
        try:
            gesture = load_gesture_file(path)
        except GestureFileError as e:
            raise GestureDeskError([f"{path.name}: {p}" for p in e.problems]) from None
        return {"name": gesture.name, "file": str(path),
                "keyframes": [{"t": k.t, "joints": dict(k.joints)} for k in gesture.keyframes]}
