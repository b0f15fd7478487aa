"""``python -m stuart_bt.sim.world``: run the world server (see :mod:`.process`, :mod:`.server` and docs/sim.md).

The GL backend must be chosen before MuJoCo is imported: EGL renders offscreen without a
display (this machine kind has no GPU; OSMesa does not work here), while the interactive viewer
needs GLFW and a display.
"""

from __future__ import annotations

import os
import sys

if __name__ == "__main__":
    os.environ.setdefault("MUJOCO_GL", "glfw" if "--viewer" in sys.argv[1:] else "egl")
    from .process import main

    raise SystemExit(main(sys.argv[1:]))
