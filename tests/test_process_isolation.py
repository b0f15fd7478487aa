"""Process isolation: the framework never loads a vendor SDK, a daemon never loads ROS, and the ROS
bridge process (the only one with rclpy) refuses the vendor SDK.

Each process runs under a tiny import recorder (a ``sys.meta_path`` entry that writes down every
module name asked for, imported or not, as it happens), so an attempt counts even when the
package is not installed here and even if the process has to be killed. The test iterates over
every family and every backend in each family's registry, so later ``sim`` and ``unitree``
backends are covered as soon as they are registered.
"""

from __future__ import annotations

import importlib
import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

from stuart_bt.core.catalogue import FAMILIES

VENDOR = ("unitree_sdk2py", "unitree_sdk2", "cyclonedds")
ROS = ("rclpy", "rosidl", "std_msgs", "geometry_msgs", "rmw", "rcl_interfaces", "builtin_interfaces")

RECORDER = r"""
import sys

class ImportRecorder:
    def __init__(self, path):
        self.file = open(path, "a", buffering=1)

    def find_spec(self, name, path=None, target=None):
        self.file.write(name + "\n")
        return None

recorder = ImportRecorder(sys.argv[1])
recorder.file.write("\n".join(sys.modules) + "\n")
sys.meta_path.insert(0, recorder)
mode, target, rest = sys.argv[2], sys.argv[3], sys.argv[4:]
if mode == "daemon":
    import runpy
    sys.argv = [target, *rest]
    runpy.run_module(target, run_name="__main__", alter_sys=True)
elif mode == "code":
    exec(target)
"""

FRAMEWORK = r"""
import pkgutil
import stuart_bt
for info in pkgutil.walk_packages(stuart_bt.__path__, "stuart_bt.", onerror=lambda name: None):
    if info.name.endswith(".__main__"):  # a program (python -m ...), not a module to import
        continue
    try:
        __import__(info.name)
    except Exception:
        pass  # a missing optional dependency: the attempt is recorded all the same
from stuart_bt.core.clock import ScaledClock
from stuart_bt.core.events import EventStream
from stuart_bt.daemon.supervisor import Supervisor
with Supervisor("dry", ScaledClock(20), EventStream(ScaledClock(20))) as sup:
    for family in sup.families:
        assert sup.wait(sup.client(family).request("ping")).ok
"""


def imports_of(tmp_path: Path, name: str, mode: str, target: str, *rest: str) -> set[str]:
    """Every module the process asked for; it gets stdin EOF at once (daemons then exit)."""
    record = tmp_path / f"{name}.imports"
    subprocess.run([sys.executable, "-c", RECORDER, str(record), mode, target, *rest], stdin=subprocess.DEVNULL,
                   capture_output=True, timeout=60)
    return set(record.read_text().split())


def forbidden(modules: set[str], tops: tuple[str, ...]) -> list[str]:
    return sorted(m for m in modules if m.split(".")[0].startswith(tops))


def backends() -> list[tuple[str, str]]:
    return [(family, backend) for family in FAMILIES
            for backend in importlib.import_module(f"stuart_bt.skills.{family}").BACKENDS]


@pytest.mark.parametrize("family, backend", backends())
def test_a_daemon_never_imports_ros(tmp_path, family, backend):
    modules = imports_of(tmp_path, f"{family}-{backend}", "daemon", f"stuart_bt.skills.{family}",
                         "--backend", backend, "--clock", "wall")
    assert "stuart_bt.skills.runtime" in modules  # the daemon really ran under the recorder
    module_name = importlib.import_module(f"stuart_bt.skills.{family}").BACKENDS[backend].partition(":")[0]
    assert module_name in modules
    assert forbidden(modules, ROS) == []


def test_the_framework_never_imports_a_vendor_sdk(tmp_path):
    modules = imports_of(tmp_path, "framework", "code", FRAMEWORK)
    assert {"stuart_bt.daemon.supervisor", "stuart_bt.daemon.client"} <= modules
    assert forbidden(modules, VENDOR) == []


def vendor_families() -> list[str]:
    """The families whose unitree backend talks to the vendor's services (not vision: a camera)."""
    return [f for f in FAMILIES if "unitree" in importlib.import_module(f"stuart_bt.skills.{f}").BACKENDS]


@pytest.mark.parametrize("family", vendor_families())
def test_a_unitree_daemon_loads_the_vendor_sdk_itself(tmp_path, family):
    """The SDK lives in the daemon process (it exits before READY here: no robot answers)."""
    pytest.importorskip("unitree_sdk2py", reason="the unitree backends need the 'robot' extra")
    modules = imports_of(tmp_path, f"{family}-unitree", "daemon", f"stuart_bt.skills.{family}", "--backend", "unitree",
                         "--clock", "wall", "--options", '{"interface": "lo", "domain": 231, "probe_timeout": 0.2}')
    assert "unitree_sdk2py" in modules and "cyclonedds" in modules
    assert forbidden(modules, ROS) == []


def test_the_map_command_leaves_the_vendor_sdk_to_the_loco_daemon(tmp_path):
    code = "from stuart_bt.cli import main\nmain(['map', 'close', '--interface', 'lo', '--domain', '231'])"
    modules = imports_of(tmp_path, "map-cli", "code", code)
    assert {"stuart_bt.cli.map", "stuart_bt.daemon.supervisor"} <= modules
    assert forbidden(modules, VENDOR) == []


def test_the_recorder_notices_an_import_attempt_of_a_package_that_is_not_installed(tmp_path):
    probe = "try:\n    import rosidl_probe_absent\nexcept ImportError:\n    pass"
    modules = imports_of(tmp_path, "probe", "code", probe)
    assert forbidden(modules, ROS) == ["rosidl_probe_absent"]


BRIDGE = r"""
import os, signal, threading
threading.Timer(4.0, lambda: os.kill(os.getpid(), signal.SIGTERM)).start()  # a short life, then a clean stop
from stuart_bt.cli import main
raise SystemExit(main(["ros", "--backend", "dry"]))
"""


def _ros_env() -> dict[str, str]:
    return {**os.environ, "ROS_DOMAIN_ID": str(1 + os.getpid() % 100), "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}


def test_the_ros_bridge_process_imports_rclpy_and_never_a_vendor_sdk(tmp_path):
    pytest.importorskip("rclpy", reason="the ros extra (real rclpy) is not installed")
    record = tmp_path / "bridge.imports"
    run = subprocess.run([sys.executable, "-c", RECORDER, str(record), "code", BRIDGE], stdin=subprocess.DEVNULL,
                         capture_output=True, text=True, timeout=90, env=_ros_env())
    modules = set(record.read_text().split())
    assert run.returncode == 0, run.stderr[-500:]
    assert "ros bridge: node /stuart_bridge" in run.stdout
    assert {"rclpy", "stuart_bt.ros.node", "stuart_bt.mission.executor"} <= modules
    assert forbidden(modules, VENDOR) == []


@pytest.mark.parametrize("first, then", [("unitree_sdk2py", "stuart_bt.ros.node"),
                                         ("stuart_bt.ros.node", "unitree_sdk2py"),
                                         ("stuart_bt.ros.node", "cyclonedds")])
def test_a_process_cannot_hold_both_the_ros_bridge_and_the_vendor_sdk(first, then):
    pytest.importorskip("rclpy", reason="the ros extra (real rclpy) is not installed")
    if importlib.util.find_spec("unitree_sdk2py") is None:  # not imported here: this process stays clean
        pytest.skip("the robot extra (vendor SDK) is not installed")
    run = subprocess.run([sys.executable, "-c", f"import {first}\nimport {then}"], stdin=subprocess.DEVNULL,
                         capture_output=True, text=True, timeout=60, env=_ros_env())
    assert run.returncode != 0
    last = run.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError:") and "vendor SDK" in last and "daemons" in last


def test_the_vision_daemon_renders_through_the_world_and_never_loads_mujoco_itself(tmp_path):
    """Perception runs in its own process with OpenCV; MuJoCo (and its GL context) stays in the
    world server, so a vision daemon costs no second renderer."""
    modules = imports_of(tmp_path, "vision-sim", "daemon", "stuart_bt.skills.vision", "--backend", "sim",
                         "--clock", "wall")
    assert {"stuart_bt.skills.vision.sim", "stuart_bt.perception.pipeline", "cv2"} <= modules
    assert forbidden(modules, ("mujoco",)) == []
    assert forbidden(modules, VENDOR + ROS) == []


WEB_SERVER = r"""
import os, signal, socket, threading, time, urllib.request
from stuart_bt.cli import main

with socket.socket() as s:
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]


def visit_then_stop():
    for _ in range(600):
        try:
            urllib.request.urlopen(f"http://127.0.0.1:{port}/api/state", timeout=2).read()
            urllib.request.urlopen(f"http://127.0.0.1:{port}/api/markers", timeout=2).read()
            break
        except OSError:
            time.sleep(0.1)
    os.kill(os.getpid(), signal.SIGINT)


threading.Thread(target=visit_then_stop, daemon=True).start()
main(["serve", TREE, "--paused", "--port", str(port)])
"""


def test_the_web_server_never_imports_a_vendor_sdk_or_ros(tmp_path):
    pytest.importorskip("starlette", reason="the web view needs the web extra")
    tree = Path(__file__).resolve().parents[1] / "trees" / "greet.yaml"
    modules = imports_of(tmp_path, "web", "code", WEB_SERVER.replace("TREE", repr(str(tree))))
    assert {"stuart_bt.web.app", "stuart_bt.web.control", "uvicorn", "starlette"} <= modules
    assert forbidden(modules, VENDOR) == []
    assert forbidden(modules, ROS) == []
