"""The gesture daemon: arm gestures.

``BACKENDS`` maps backend names to ``"module:Class"``; only the chosen one is imported, so a
dry daemon never loads a simulator or a vendor SDK.
"""

BACKENDS: dict[str, str] = {
    "dry": "stuart_bt.skills.gesture.dry:DryGesture",
    "sim": "stuart_bt.skills.gesture.sim:SimGesture",
    "unitree": "stuart_bt.skills.gesture.unitree:UnitreeGesture",
}
