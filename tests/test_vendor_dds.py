"""Joining the robot's DDS domain leaves nothing behind: the vendor SDK's config for a named
interface would have CycloneDDS write a trace to /tmp/cdds.LOG in every process that joins."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("unitree_sdk2py", reason="the 'robot' extra is not installed (make test installs it)")
TRACE = Path("/tmp/cdds.LOG")
JOIN = "from stuart_bt.skills.vendor import join_dds; join_dds(97, 'lo'); print('joined')"


def test_joining_dds_on_an_interface_writes_no_trace_file_in_tmp():
    before = TRACE.stat().st_mtime_ns if TRACE.exists() else None
    done = subprocess.run([sys.executable, "-c", JOIN], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and "joined" in done.stdout, done.stderr
    after = TRACE.stat().st_mtime_ns if TRACE.exists() else None
    assert after == before, "joining DDS wrote /tmp/cdds.LOG"
