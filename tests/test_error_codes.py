"""One table of error codes: every code the source raises or answers with is in
``protocol.ERROR_CODES`` (docs/protocol.md), whoever sets it: a daemon, the world server, the
framework or a client. Read from the source, so a new code cannot slip past the table."""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

from stuart_bt.daemon.protocol import CLIENT_CODES, ERROR_CODES, FRAMEWORK_CODES, WORLD_CODES

REPO = Path(__file__).resolve().parents[1]
SOURCES = ("stuart_bt", "skills", "sim")
# Where the code is among a call's arguments: the error classes and the client's fail() take it
# first; protocol.error(request_id, code, ...) and the client's _fail(request, code, ...) second.
CODE_ARGUMENT = {"DaemonError": 0, "WorldError": 0, "CodedError": 0, "fail": 0, "error": 1, "_fail": 1}
PROTOCOL_MODULES = {"p", "protocol"}  # how the source names the protocol module when it calls error()


def _code_argument(node: ast.Call) -> ast.expr | None:
    func = node.func
    name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
    if name == "error" and not (isinstance(func, ast.Attribute) and getattr(func.value, "id", "") in PROTOCOL_MODULES):
        return None  # some other error(), e.g. a logger's
    index = CODE_ARGUMENT.get(name)
    return node.args[index] if index is not None and len(node.args) > index else None


def _coded_calls() -> Iterator[tuple[str, str]]:
    for folder in SOURCES:
        for path in sorted((REPO / folder).rglob("*.py")):
            for node in ast.walk(ast.parse(path.read_text(), str(path))):
                code = _code_argument(node) if isinstance(node, ast.Call) else None
                if isinstance(code, ast.Constant) and isinstance(code.value, str):
                    yield f"{path.relative_to(REPO)}:{node.lineno}", code.value


def test_every_code_the_source_raises_or_answers_with_is_in_the_one_table():
    found = list(_coded_calls())
    assert len(found) > 40, "the scan found too few coded calls to be reading the source"
    unknown = [f"{where}: {code!r}" for where, code in found if code not in ERROR_CODES]
    assert not unknown, "codes missing from protocol.ERROR_CODES:\n" + "\n".join(unknown)


def test_the_world_server_and_its_clients_use_codes_from_the_same_table():
    for group in (WORLD_CODES, CLIENT_CODES, FRAMEWORK_CODES):
        assert set(group) <= set(ERROR_CODES)
    assert {"bad_request", "unknown_command", "not_found"} <= set(WORLD_CODES)
