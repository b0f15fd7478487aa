"""The G1 robot model: one description (``description.py``), two generated files.

``sim/models/g1.xml`` (MuJoCo) and ``sim/models/g1.urdf`` (Pinocchio, PlaCo) are written by
``python -m stuart_bt.sim.robot`` and checked against the description by the tests, so they
never drift apart. Import the paths from here rather than spelling them out.
"""

from __future__ import annotations

from pathlib import Path

from .description import NEUTRAL, REACH, SIDES, Robot, arm_joints, arm_limits, g1, hand_joints, shoulder_xyz

MODELS_DIR = Path(__file__).resolve().parents[1] / "models"
MJCF_PATH = MODELS_DIR / "g1.xml"
URDF_PATH = MODELS_DIR / "g1.urdf"

__all__ = ["MJCF_PATH", "MODELS_DIR", "NEUTRAL", "REACH", "SIDES", "URDF_PATH", "Robot", "arm_joints", "arm_limits",
           "g1", "hand_joints", "shoulder_xyz"]
