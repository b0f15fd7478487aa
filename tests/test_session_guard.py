"""The session guard (tests/session_guard.py): a process a test leaves running fails the session
by name and is killed; a suite that ends its processes passes; temporary files stay private."""

from __future__ import annotations

import re
import uuid
from pathlib import Path

import pytest

TESTS = Path(__file__).parent
CONFTEST = f"import sys\nsys.path.insert(0, {str(TESTS)!r})\npytest_plugins = ['session_guard']\n"


def _running(token: str) -> list[int]:
    """Live processes whose command line holds ``token``."""
    found = []
    for proc in Path("/proc").iterdir():
        try:
            if proc.name.isdigit() and token.encode() in (proc / "cmdline").read_bytes():
                found.append(int(proc.name))
        except OSError:
            continue
    return found


def test_a_process_a_test_leaves_running_fails_the_session_names_it_and_is_killed(pytester: pytest.Pytester):
    token = f"left_behind_{uuid.uuid4().hex[:8]}"
    pytester.makeconftest(CONFTEST)
    pytester.makepyfile(f"""
        import subprocess, sys
        def test_forgets_its_helper():
            subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)", "{token}"],
                             start_new_session=True)  # even in its own group, even re-parented
        """)
    result = pytester.runpytest_subprocess()
    assert result.ret == pytest.ExitCode.TESTS_FAILED
    result.stdout.fnmatch_lines(["*processes left behind*", f"*time.sleep(120) {token}*"])
    assert not _running(token)


def test_a_suite_that_ends_its_processes_passes_and_leaves_no_temporary_files(pytester: pytest.Pytester):
    pytester.makeconftest(CONFTEST)
    pytester.makepyfile("""
        import subprocess, sys, tempfile, pathlib, os
        def test_ends_its_helper():
            folder = tempfile.mkdtemp(prefix="stuart_bt-leak-")
            print("FOLDER", folder)
            assert folder.startswith(os.environ["TMPDIR"])
            subprocess.run([sys.executable, "-c", "pass"], check=True)
        """)
    result = pytester.runpytest_subprocess("-s")
    assert result.ret == pytest.ExitCode.OK
    folder = re.search(r"FOLDER (\S+)", result.stdout.str()).group(1)
    assert not Path(folder).exists()
