"""The vision daemon: the head camera, the detector, projection and the spatial memory.

Perception runs here, in its own process at the camera's rate, so detection never slows the
tree's tick; results reach the framework as daemon results (``find``, ``look``, ``memory``).
``BACKENDS`` maps backend names to ``"module:Class"``; only the chosen one is imported.
"""

BACKENDS: dict[str, str] = {
    "dry": "stuart_bt.skills.vision.dry:DryVision",
    "sim": "stuart_bt.skills.vision.sim:SimVision",
    "unitree": "stuart_bt.skills.vision.unitree:UnitreeVision",
}
