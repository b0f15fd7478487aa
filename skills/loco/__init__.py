"""The loco daemon: walking and turning.

``BACKENDS`` maps backend names to ``"module:Class"``; only the chosen one is imported, so a
dry daemon never loads a simulator or a vendor SDK.
"""

BACKENDS: dict[str, str] = {
    "dry": "stuart_bt.skills.loco.dry:DryLoco",
    "sim": "stuart_bt.skills.loco.sim:SimLoco",
    "unitree": "stuart_bt.skills.loco.unitree:UnitreeLoco",
}
