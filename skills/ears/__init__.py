"""The ears daemon: what the robot hears, one utterance per progress line of ``listen``.

``BACKENDS`` maps backend names to ``"module:Class"``; only the chosen one is imported, so a
dry daemon never loads a recogniser or a vendor SDK.
"""

BACKENDS: dict[str, str] = {
    "dry": "stuart_bt.skills.ears.dry:DryEars",
    "unitree": "stuart_bt.skills.ears.unitree:UnitreeEars",
}
