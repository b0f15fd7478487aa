"""The pick daemon: picking, placing and finding objects.

``BACKENDS`` maps backend names to ``"module:Class"``; only the chosen one is imported, so a
dry daemon never loads a simulator or a vendor SDK.
"""

BACKENDS: dict[str, str] = {
    "dry": "stuart_bt.skills.pick.dry:DryPick",
    "sim": "stuart_bt.skills.pick.sim:SimPick",
    "unitree": "stuart_bt.skills.pick.unitree:UnitreePick",
}
