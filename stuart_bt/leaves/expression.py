"""Leaves that express: ``speak`` (tts daemon) and ``gesture`` (gesture daemon).

Both take ``wait: false`` to succeed as soon as the daemon accepts, so speech and gestures can
overlap what follows; inside a ``parallel`` they simply run side by side.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from ..core import gestures
from ..core.suggest import did_you_mean
from ..tree.include_params import base_dir_of
from ..tree.spec import NodeSpec
from .base import LeafFailure, RunContext, SkillLeaf


class Speak(SkillLeaf):
    kind = "speak"

    def __init__(self, spec: NodeSpec, ctx: RunContext) -> None:
        super().__init__(spec, ctx)
        self.wait_for_completion = bool(spec.params.get("wait", True))

    def command(self) -> tuple[str, dict[str, Any]]:
        text = str(self.param("text"))
        if not text.strip():
            raise LeafFailure("nothing to say: text is empty")
        return "say", {"text": text}


class Gesture(SkillLeaf):
    kind = "gesture"

    def __init__(self, spec: NodeSpec, ctx: RunContext) -> None:
        super().__init__(spec, ctx)
        self.wait_for_completion = bool(spec.params.get("wait", True))

    def command(self) -> tuple[str, dict[str, Any]]:
        if self.has("file"):
            where = self.spec.param_locations.get("file")
            base = base_dir_of(where.file) if where else self.ctx.tree_dir
            return "play", {"keyframes": load_gesture_file(base / str(self.param("file")))}
        if self.has("sequence"):
            names = self.param("sequence")
            if isinstance(names, str):
                names = [names]
            return "play", {"sequence": [canonical_gesture(str(n)) for n in names]}
        return "play", {"name": canonical_gesture(str(self.param("play")))}


def canonical_gesture(name: str) -> str:
    found = gestures.lookup(name)
    if found is None:
        raise LeafFailure(f"unknown gesture {name!r}{did_you_mean(name, gestures.names())}")
    return found.name


def load_gesture_file(path: Path) -> list[dict[str, Any]]:
    """Keyframes from a recorded gesture file: ``{"keyframes": [{"t": s, "joints": {name: rad}}]}``."""
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
        frames = doc["keyframes"]
        if not isinstance(frames, list) or not frames:
            raise ValueError("'keyframes' must be a non-empty list")
        return [{"t": float(f["t"]), "joints": {str(k): float(v) for k, v in f["joints"].items()}} for f in frames]
    except FileNotFoundError:
        raise LeafFailure(f"gesture file not found: {path}") from None
    except (ValueError, KeyError, TypeError, AttributeError) as e:
        raise LeafFailure(f"bad gesture file {path}: {e}") from None
