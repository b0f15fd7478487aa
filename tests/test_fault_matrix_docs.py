"""docs/running.md's fault matrix promises that each row is a test: every test it names exists,
and every row names at least one."""

from __future__ import annotations

import re
from pathlib import Path

TESTS = Path(__file__).parent
RUNNING_MD = TESTS.parent / "docs" / "running.md"
NAMED = re.compile(r"`(?:(test_\w+\.py)::)?(test_\w+)`")


def fault_rows() -> list[str]:
    section = RUNNING_MD.read_text(encoding="utf-8").split("## Faults", 1)[1].split("\n## ", 1)[0]
    return [line for line in section.splitlines() if line.startswith("| ") and not line.startswith("| process")]


def defines(test_file: Path, name: str) -> bool:
    return re.search(rf"^def {name}\b", test_file.read_text(encoding="utf-8"), re.MULTILINE) is not None


def test_every_row_of_the_fault_matrix_names_a_test_or_points_at_the_row_above():
    rows = fault_rows()
    assert len(rows) >= 20
    for row in rows:
        assert NAMED.search(row) or row.rstrip(" |").endswith("the same test"), row


def test_every_test_the_fault_matrix_names_exists():
    missing = []
    for row in fault_rows():
        for file_name, test in NAMED.findall(row):
            files = [TESTS / file_name] if file_name else sorted(TESTS.glob("test_*.py"))
            if not any(path.exists() and defines(path, test) for path in files):
                missing.append(f"{file_name or 'tests/'}::{test}")
    assert not missing, f"docs/running.md names tests that do not exist: {missing}"
