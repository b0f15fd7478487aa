"""Keep the vendor SDK out of the ROS bridge process.

Both rclpy and the Unitree SDK (through cyclonedds) bring a DDS implementation with its own
threads, discovery and shared libraries; in one process they fight over sockets and symbols, and
the framework's design puts the SDK in daemon processes only. So the bridge refuses to start in a
process that has loaded the SDK, and, once it is loaded, the SDK cannot be imported any more.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys
from typing import Any

VENDOR_SDK = ("unitree_sdk2py", "unitree_sdk2", "cyclonedds")


class VendorSdkBlocker(importlib.abc.MetaPathFinder):
    """Fails every import of a vendor SDK package with a message that says why."""

    def find_spec(self, name: str, path: Any = None, target: Any = None) -> None:
        if name.split(".")[0] in VENDOR_SDK:
            raise ImportError(f"{name} cannot be imported in the ROS bridge process: the vendor SDK runs "
                              "only inside skill daemons (docs/architecture.md, process isolation)")
        return None


def forbid_vendor_sdk() -> None:
    """Raise ImportError if a vendor SDK is loaded already; block later imports of one.

    The blocker goes just before the path finder, so import recorders placed first (the process
    isolation test's) still see an attempt."""
    loaded = sorted(m for m in sys.modules if m.split(".")[0] in VENDOR_SDK)
    if loaded:
        raise ImportError(f"the ROS bridge cannot run in a process that imported the vendor SDK ({loaded[0]}): "
                          "the SDK belongs in skill daemons only")
    if any(isinstance(f, VendorSdkBlocker) for f in sys.meta_path):
        return
    where = next((i for i, f in enumerate(sys.meta_path) if f is importlib.machinery.PathFinder), len(sys.meta_path))
    sys.meta_path.insert(where, VendorSdkBlocker())
