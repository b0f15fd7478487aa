"""The tts daemon: speech out.

``BACKENDS`` maps backend names to ``"module:Class"``; only the chosen one is imported, so a
dry daemon never loads a simulator or a vendor SDK.
"""

BACKENDS: dict[str, str] = {
    "dry": "stuart_bt.skills.tts.dry:DryTts",
    "sim": "stuart_bt.skills.tts.audio:AudioTts",
    "unitree": "stuart_bt.skills.tts.unitree:UnitreeTts",
}
