"""Runs the rclpy round trip (:mod:`bench.ros_pingpong`) in child processes with the right environment.

The PyPI ROS wheels (``ros-rclpy`` and friends) keep their shared libraries in
``<venv>/lib`` and ``site-packages/ros_*.libs``, which the dynamic loader only searches when
``LD_LIBRARY_PATH`` says so *at process start*. Their ``ros_wheels_bootstrapper.pth`` handles it
by re-executing every interpreter of the venv with that path set; this module does not rely on
it: it builds the same path itself, marks the bootstrap as done (so the child is not re-executed
a second time), and keeps DDS on this machine (``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST``, a
private ``ROS_DOMAIN_ID``).
"""

from __future__ import annotations

import contextlib
import glob
import importlib.util
import json
import os
import selectors
import subprocess
import sys
import sysconfig
import tempfile
from pathlib import Path

SCRIPT = Path(__file__).with_name("ros_pingpong.py")
DOMAIN_ID = os.environ.get("STUART_BENCH_ROS_DOMAIN_ID", "87")
START_TIMEOUT = 60.0  # seconds for start-up, discovery and warm-up
BATCH_TIMEOUT = 120.0  # seconds for one batch


class RosUnavailable(RuntimeError):
    """rclpy is missing or its round trip could not run; the message says why."""


def missing() -> str | None:
    """Why the rclpy anchor cannot run, or None when its packages are installed."""
    for module, package in (("rclpy", "ros-rclpy[fastrtps]==9.1.2"), ("std_msgs", "ros-std-msgs")):
        if importlib.util.find_spec(module) is None:
            return f"{module} is not installed (pip install '{package}', or the 'ros' extra)"
    return None


def ros_env() -> dict[str, str]:
    """This process's environment plus what rclpy's wheels need to load, DDS kept local."""
    env = dict(os.environ)
    site = sysconfig.get_paths()["platlib"]
    paths = [os.path.join(sys.prefix, "lib"), *sorted(glob.glob(os.path.join(site, "ros_*.libs")))]
    paths += [p for p in env.get("LD_LIBRARY_PATH", "").split(os.pathsep) if p and p not in paths]
    env["LD_LIBRARY_PATH"] = os.pathsep.join(paths)
    env["_ROS_WHEELS_BOOTSTRAP_COMPLETE"] = "1"
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    env["ROS_DOMAIN_ID"] = DOMAIN_ID
    env.pop("ROS_LOCALHOST_ONLY", None)  # deprecated; would conflict with the range above
    return env


class RosPeer:
    """One ``ros_pingpong.py`` child in ``mode`` ("same" or "two" processes), serving batches."""

    def __init__(self, mode: str) -> None:
        reason = missing()
        if reason:
            raise RosUnavailable(reason)
        self.mode = mode
        self._stderr = tempfile.TemporaryFile()  # noqa: SIM115 - kept open for the child's life; closed in close()
        self._child = subprocess.Popen(
            [sys.executable, str(SCRIPT), mode, f"{os.getpid()}_{mode}"], env=ros_env(), text=True,
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=self._stderr,
        )
        try:
            if self._line(START_TIMEOUT) != "READY":
                raise self._failure("did not report READY")
        except BaseException:
            self.close()
            raise

    def batch(self, count: int) -> list[float]:
        """Round-trip seconds of ``count`` sequential pings, measured inside the child."""
        assert self._child.stdin is not None
        try:
            self._child.stdin.write(f"{count}\n")
            self._child.stdin.flush()
        except BrokenPipeError:
            raise self._failure("exited early") from None
        return json.loads(self._line(BATCH_TIMEOUT))["samples"]

    def _line(self, timeout: float) -> str:
        assert self._child.stdout is not None
        with selectors.DefaultSelector() as selector:
            selector.register(self._child.stdout, selectors.EVENT_READ)
            if not selector.select(timeout):
                raise self._failure(f"sent nothing for {timeout:g} s")
        line = self._child.stdout.readline()
        if not line:
            raise self._failure("exited early")
        return line.strip()

    def _failure(self, what: str) -> RosUnavailable:
        self._stderr.seek(0)
        lines = self._stderr.read().decode(errors="replace").strip().splitlines()
        tail = " | ".join(lines[-3:]) or "no stderr"
        return RosUnavailable(f"the rclpy round trip ({self.mode} process) {what}: {tail}")

    def close(self) -> None:
        if self._child.stdin is not None and not self._child.stdin.closed:
            with contextlib.suppress(BrokenPipeError):  # the child exits at end of input
                self._child.stdin.close()
        try:
            self._child.wait(timeout=15)
        except subprocess.TimeoutExpired:
            self._child.kill()
            self._child.wait()
        if self._child.stdout is not None:
            self._child.stdout.close()
        self._stderr.close()
