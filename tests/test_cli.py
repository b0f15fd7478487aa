"""``stuart-bt`` end to end, the way a user drives it: every test starts the real console script in
a subprocess (from the repository root, with relative paths, as in the README) and looks only at
what a user can see: exit status, stdout, stderr, the files it writes, and the processes it leaves.

Malformed trees used here live in ``tests/data/cli/``; trees that only make sense next to a test
(the run trees, binary garbage) are written into ``tmp_path``.
"""

from __future__ import annotations

import json
import math
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import yaml

REPO = Path(__file__).resolve().parents[1]
DATA = Path("tests/data/cli")  # relative to REPO, where every command runs
MARKERS = REPO / "sim" / "maps" / "lab_markers.json"
TOUR = "trees/lab_tour.yaml"
STATIONS = [f"station_{i}" for i in range(1, 7)]
FAMILIES = {"loco", "tts", "gesture"}
ERROR_LINE = re.compile(r"^(?P<file>\S+?):(?P<line>\d+):(?P<col>\d+): (?P<message>.+)$")


def _console_script() -> list[str]:
    script = Path(sys.executable).with_name("stuart-bt")
    if script.exists():
        return [str(script)]
    found = shutil.which("stuart-bt")
    return [found] if found else [sys.executable, "-m", "stuart_bt.cli"]


CLI = _console_script()


# -- helpers -----------------------------------------------------------------------------------------
def stuart(*args: Any, timeout: float = 30) -> subprocess.CompletedProcess[str]:
    """``stuart-bt ARGS`` from the repository root; stdout and stderr captured as text."""
    return subprocess.run([*CLI, *map(str, args)], cwd=REPO, capture_output=True, stdin=subprocess.DEVNULL,
                          encoding="utf-8", errors="replace", timeout=timeout, check=False)


def assert_no_traceback(*outputs: str) -> None:
    for out in outputs:
        assert "Traceback" not in out, out


def error_lines(stderr: str) -> list[re.Match[str]]:
    """Every line of stderr must be one ``file:line:col: message`` problem."""
    lines = [line for line in stderr.splitlines() if line.strip()]
    assert lines, "expected at least one error line on stderr"
    matches = [ERROR_LINE.match(line) for line in lines]
    bad = [line for line, m in zip(lines, matches, strict=True) if m is None]
    assert not bad, f"lines not in file:line:col: form: {bad}"
    return matches  # type: ignore[return-value]


def locate(file: str | Path, needle: str, occurrence: int = 1) -> tuple[int, int]:
    """1-based (line, column) of ``needle`` in a file, comment lines skipped."""
    seen = 0
    for number, text in enumerate((REPO / file).read_text(encoding="utf-8").splitlines(), 1):
        if text.lstrip().startswith("#"):
            continue
        start = 0
        while (index := text.find(needle, start)) >= 0:
            seen += 1
            if seen == occurrence:
                return number, index + 1
            start = index + 1
    raise AssertionError(f"{needle!r} (occurrence {occurrence}) not in {file}")


def read_events(path: Path) -> list[dict[str, Any]]:
    """The complete lines of an event log written so far (a line still being written is skipped)."""
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        return []
    return [json.loads(line) for line in text.splitlines(keepends=True) if line.endswith("\n") and line.strip()]


def daemon_pids(events: list[dict[str, Any]]) -> set[int]:
    return {e["pid"] for e in events if e["kind"] == "daemon_state" and isinstance(e.get("pid"), int)}


def assert_no_leftovers(pids: set[int]) -> None:
    assert pids, "no daemon pid in the event log"
    found = leftovers(pids)
    assert not found, "processes left behind:\n" + "\n".join(found)


def leftovers(pids: set[int]) -> list[str]:
    """Processes still there from the daemons ``pids``, zombies included.

    Daemons lead their own session (``start_new_session``), so anything whose session id is one of
    those pids is the daemon itself or something it started; a pid reused by an unrelated process
    has another session id."""
    found = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            text = stat.read_text()
            cmdline = (stat.parent / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        fields = text[text.rindex(")") + 2:].split()
        state, ppid, session = fields[0], int(fields[1]), int(fields[3])
        if session in pids:
            found.append(f"pid {stat.parent.name} state {state} ppid {ppid} session {session}: {cmdline.strip()}")
    return found


class BackgroundRun:
    """``stuart-bt run ...`` started as from a terminal: its own process group, output to files."""

    def __init__(self, tmp: Path, *args: Any) -> None:
        self.tmp = tmp
        self.log = tmp / "events.jsonl"
        self.report = tmp / "report.json"
        self._out = open(tmp / "stdout.txt", "w+", encoding="utf-8")  # noqa: SIM115 - closed in cleanup()
        self._err = open(tmp / "stderr.txt", "w+", encoding="utf-8")  # noqa: SIM115
        argv = [*CLI, "run", *map(str, args), "--report", str(self.report), "--log", str(self.log)]
        self._events: list[dict[str, Any]] = []
        self._offset = 0
        self.proc = subprocess.Popen(argv, cwd=REPO, stdin=subprocess.DEVNULL, stdout=self._out, stderr=self._err,
                                     start_new_session=True)

    def events(self) -> list[dict[str, Any]]:
        """Every event logged so far (read incrementally: polling stays cheap as the log grows)."""
        try:
            with open(self.log, "rb") as f:
                f.seek(self._offset)
                chunk = f.read()
        except FileNotFoundError:
            return self._events
        complete = chunk[: chunk.rfind(b"\n") + 1]
        self._offset += len(complete)
        self._events.extend(json.loads(line) for line in complete.splitlines() if line.strip())
        return self._events

    def wait_for(self, what: str, predicate: Callable[[dict[str, Any]], bool], timeout: float = 20) -> dict[str, Any]:
        """The first event matching ``predicate``, as soon as it is in the log."""
        deadline = time.monotonic() + timeout
        while True:
            exited = self.proc.poll() is not None
            for event in self.events():
                if predicate(event):
                    return event
            if exited or time.monotonic() > deadline:
                raise AssertionError(f"no {what} in the event log (exit {self.proc.poll()}); stderr: {self.stderr}")
            time.sleep(0.002)

    def ctrl_c(self) -> None:
        """What the terminal does on Ctrl-C: SIGINT to the foreground process group."""
        os.killpg(self.proc.pid, signal.SIGINT)

    def finish(self, timeout: float) -> int:
        """The exit status; a run still going after ``timeout`` is asked for its threads' stacks
        (SIGUSR1: docs/running.md) and the test fails with them."""
        try:
            return self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.proc.send_signal(signal.SIGUSR1)
            time.sleep(1.0)
            stacks = self.stderr[-6000:]
            raise AssertionError(f"the run did not end within {timeout} s; its threads:\n{stacks}") from None

    @property
    def stdout(self) -> str:
        self._out.flush()
        return (self.tmp / "stdout.txt").read_text(encoding="utf-8")

    @property
    def stderr(self) -> str:
        self._err.flush()
        return (self.tmp / "stderr.txt").read_text(encoding="utf-8")

    def cleanup(self) -> None:
        """After a failed test: end what this run started, by pid, so later tests are not disturbed.
        A daemon is only ours while it still runs our skill program as a child of this CLI (or as an
        orphan after the CLI died); a reused pid belongs to someone else and is left alone."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait(5)
        for pid in daemon_pids(self.events()):
            try:
                fields = Path(f"/proc/{pid}/stat").read_text()
                cmdline = Path(f"/proc/{pid}/cmdline").read_bytes()
                ppid, session = (int(x) for x in fields[fields.rindex(")") + 2:].split()[1:4:2])
                if session == pid and ppid in (self.proc.pid, 1) and b"stuart_bt.skills" in cmdline:
                    os.killpg(pid, signal.SIGKILL)
            except (OSError, ValueError):
                pass
        self._out.close()
        self._err.close()


@pytest.fixture
def background(tmp_path: Path):
    runs: list[BackgroundRun] = []

    def start(*args: Any) -> BackgroundRun:
        run = BackgroundRun(tmp_path, *args)
        runs.append(run)
        return run

    yield start
    for run in runs:
        run.cleanup()


def tour_scripts() -> dict[str, str]:
    """Station name -> what Stuart says there, read from the tour file itself."""
    doc = yaml.safe_load((REPO / TOUR).read_text(encoding="utf-8"))
    scripts = {}
    for child in doc["root"]["sequence"]["children"]:
        if "include" in child:
            scripts[child["include"]["name"]] = child["include"]["with"]["script"]
    assert sorted(scripts) == STATIONS
    return scripts


def write_tree(tmp: Path, name: str, body: str) -> Path:
    """A tree in ``tmp`` whose ``markers:`` is the lab map, given relative to the tree file."""
    path = tmp / name
    markers = os.path.relpath(MARKERS, tmp)
    path.write_text(f"markers: {markers}\n{body}", encoding="utf-8")
    return path


# -- help ----------------------------------------------------------------------------------------------
COMMANDS = [[], ["validate"], ["show"], ["run"], ["gesture"], ["gesture", "list"], ["gesture", "record"],
            ["gesture", "show"], ["gesture", "play"], ["parse"], ["plan"], ["mission"], ["chat"], ["schema"]]


@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: " ".join(c) or "stuart-bt")
def test_help_of_every_command(command: list[str]) -> None:
    result = stuart(*command, "--help")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith(f"usage: {' '.join(['stuart-bt', *command])}"), result.stdout
    if not command:
        for sub in ("validate", "show", "run", "gesture", "schema"):
            assert re.search(rf"^\s+{sub}\s", result.stdout, re.MULTILINE), f"top-level help does not list {sub}"
    assert_no_traceback(result.stdout, result.stderr)


# -- validate ------------------------------------------------------------------------------------------
def test_validate_the_shipped_trees() -> None:
    trees = sorted(str(p.relative_to(REPO)) for p in (REPO / "trees").glob("*.yaml"))
    assert len(trees) >= 5
    result = stuart("validate", *trees)
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    assert result.stdout.splitlines() == [f"{tree}: ok" for tree in trees]


@dataclass
class Problem:
    needle: str  # where the error points: the first occurrence (comments skipped) ...
    message: str  # a fragment of the message
    occurrence: int = 1  # ... or this one
    suggestion: str | None = None  # "did you mean 'suggestion'?"
    in_file: str | None = None  # reported in another file than the one validated (include cycles)
    exact_column: bool = True  # False: the column only has to fall inside the needle


BAD_TREES = [
    pytest.param("typo_skill.yaml", [Problem("navigte", "unknown node kind 'navigte'", suggestion="navigate")],
                 id="typo'd skill"),
    pytest.param("mistyped_param.yaml", [Problem("two", "parameter 'times' for retry: expected an integer")],
                 id="mistyped param"),
    pytest.param("tab_indented.yaml", [Problem("\t", "tab")], id="tab-indented"),
    pytest.param("mis_indented.yaml", [Problem("name: greet", "wrong indentation: 'name: greet' is indented 5 spaces")],
                 id="mis-indented"),
    pytest.param("duplicate_keys.yaml", [Problem("text", "duplicate key 'text' (first defined at line 5)", 2)],
                 id="duplicate keys"),
    pytest.param("unknown_marker.yaml", [Problem("kitchn", "unknown marker 'kitchn'", suggestion="kitchen")],
                 id="unknown marker"),
    pytest.param("cycle_one.yaml", [Problem("cycle_one.yaml", "include cycle: tests/data/cli/cycle_one.yaml -> "
                                            "tests/data/cli/cycle_two.yaml -> tests/data/cli/cycle_one.yaml",
                                            in_file="cycle_two.yaml")], id="include cycle"),
    pytest.param("many_errors.yaml", [
        Problem("tolerence", "unknown parameter 'tolerence' for navigate", suggestion="tolerance"),
        Problem("-1", "parameter 'seconds' for wait"),
        Problem("lefft", "parameter 'arm' for pick", suggestion="left"),
        Problem('"battery >"', "syntax error in expression", exact_column=False),
        Problem("speek", "unknown node kind 'speek'", suggestion="speak"),
    ], id="several errors"),
]


@pytest.mark.parametrize(("name", "problems"), BAD_TREES)
def test_validate_points_at_each_problem(name: str, problems: list[Problem]) -> None:
    file = f"{DATA}/{name}"
    result = stuart("validate", file)
    assert result.returncode == 1, result.stdout + result.stderr
    assert_no_traceback(result.stdout, result.stderr)
    errors = error_lines(result.stderr)
    assert len(errors) == len(problems), result.stderr
    for problem, error in zip(problems, errors, strict=True):
        where = f"{DATA}/{problem.in_file}" if problem.in_file else file
        line, col = locate(where, problem.needle, problem.occurrence)
        assert error["file"] == where, error.group(0)
        assert int(error["line"]) == line, error.group(0)
        if problem.exact_column:
            assert int(error["col"]) == col, error.group(0)
        else:
            assert col <= int(error["col"]) < col + len(problem.needle), error.group(0)
        assert problem.message in error["message"], error.group(0)
        if problem.suggestion:
            assert f"(did you mean '{problem.suggestion}'?)" in error["message"], error.group(0)
        else:
            assert "did you mean" not in error["message"], error.group(0)


def test_validate_an_empty_file() -> None:
    result = stuart("validate", f"{DATA}/empty.yaml")
    assert result.returncode == 1
    assert_no_traceback(result.stdout, result.stderr)
    [error] = error_lines(result.stderr)
    assert (error["file"], error["line"], error["col"]) == (f"{DATA}/empty.yaml", "1", "1")
    assert "empty" in error["message"]


def test_validate_binary_garbage(tmp_path: Path) -> None:
    garbage = tmp_path / "photo.yaml"  # a PNG someone saved under the wrong name
    garbage.write_bytes(b"\x89PNG\r\n\x1a\n" + random.Random(7).randbytes(2000))
    result = stuart("validate", garbage)
    assert result.returncode == 1
    assert_no_traceback(result.stdout, result.stderr)
    [error] = error_lines(result.stderr)
    assert (error["file"], error["line"], error["col"]) == (str(garbage), "1", "1")  # 0x89 is never valid UTF-8
    assert "UTF-8" in error["message"]


def test_validate_a_file_that_does_not_exist() -> None:
    result = stuart("validate", f"{DATA}/no_such_tree.yaml")
    assert result.returncode == 1
    assert_no_traceback(result.stdout, result.stderr)
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, result.stderr
    assert f"{DATA}/no_such_tree.yaml" in lines[0] and "not found" in lines[0]


def test_validate_good_and_bad_together_reports_only_the_bad() -> None:
    good, bad = "trees/greet.yaml", f"{DATA}/many_errors.yaml"
    result = stuart("validate", good, bad)
    assert result.returncode == 1
    assert_no_traceback(result.stdout, result.stderr)
    assert {e["file"] for e in error_lines(result.stderr)} == {bad}
    assert len(error_lines(result.stderr)) == 5
    assert result.stdout.splitlines() == [f"{good}: ok"]


# -- show ----------------------------------------------------------------------------------------------
def _need_dot() -> str:
    dot = shutil.which("dot")
    if dot is None:
        print("graphviz 'dot' is not installed (`make` installs it through scripts/system-deps.sh)")
        pytest.skip("graphviz 'dot' is not installed (`make` installs it through scripts/system-deps.sh)")
    return dot


def test_show_dot_is_valid_graphviz() -> None:
    """``stuart-bt show trees/lab_tour.yaml --format dot | dot -Tsvg``"""
    dot = _need_dot()
    show = subprocess.Popen([*CLI, "show", TOUR, "--format", "dot"], cwd=REPO, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
    svg = subprocess.run([dot, "-Tsvg"], stdin=show.stdout, capture_output=True, timeout=30, check=False)
    show.stdout.close()  # type: ignore[union-attr]
    show_stderr = show.stderr.read().decode()  # type: ignore[union-attr]
    show.stderr.close()  # type: ignore[union-attr]
    assert show.wait(30) == 0, show_stderr
    assert svg.returncode == 0, svg.stderr.decode()
    assert svg.stdout.lstrip().startswith((b"<?xml", b"<svg")) and b"</svg>" in svg.stdout
    for station in STATIONS:
        assert station.encode() in svg.stdout
    source = stuart("show", TOUR, "--format", "dot").stdout
    assert source.lstrip().startswith(("digraph", "strict digraph"))


@pytest.mark.parametrize("fmt", ["unicode", "ascii"])
def test_show_text_drawing_has_every_station(fmt: str) -> None:
    result = stuart("show", TOUR, "--format", fmt)
    assert result.returncode == 0, result.stderr
    drawing = result.stdout
    assert "station_3" in drawing
    for station in STATIONS:
        assert re.search(rf"\b{station}\b.*<- trees/station\.yaml", drawing), f"{station} missing:\n{drawing}"
        assert f"marker={station}" in drawing
    if fmt == "ascii":
        assert drawing.isascii(), [c for c in drawing if not c.isascii()]
    else:
        assert "├──" in drawing and "└──" in drawing


def test_show_ascii_is_ascii_even_for_non_ascii_names() -> None:
    """Names and texts outside ASCII must be escaped too (a terminal or log that only takes ASCII)."""
    result = stuart("show", f"{DATA}/non_ascii.yaml", "--format", "ascii")
    assert result.returncode == 0, result.stderr
    assert result.stdout.isascii(), result.stdout


@pytest.mark.parametrize(("suffix", "magic"), [("svg", b"<svg"), ("png", b"\x89PNG\r\n\x1a\n")])
def test_show_writes_pictures(tmp_path: Path, suffix: str, magic: bytes) -> None:
    _need_dot()
    out = tmp_path / "drawings" / f"tour.{suffix}"
    result = stuart("show", TOUR, "-o", out)
    assert result.returncode == 0, result.stderr
    assert result.stdout == ""
    data = out.read_bytes()
    if suffix == "png":
        assert data.startswith(magic)
    else:
        assert data.lstrip().startswith((b"<?xml", b"<svg")) and magic in data[:1000]
        assert data.rstrip().endswith(b"</svg>")
    assert f"wrote {out}" in result.stderr


def test_show_draws_the_wide_tour_left_to_right_unless_told_otherwise(tmp_path: Path) -> None:
    _need_dot()
    sizes = {}
    for direction in ("auto", "tb", "lr"):
        out = tmp_path / f"tour_{direction}.svg"
        result = stuart("show", TOUR, "--direction", direction, "-o", out)
        assert result.returncode == 0, result.stderr
        found = re.search(r'<svg width="([\d.]+)pt" height="([\d.]+)pt"', out.read_text(encoding="utf-8"))
        assert found
        sizes[direction] = (float(found[1]), float(found[2]))
    assert sizes["auto"] == sizes["lr"]
    assert sizes["tb"][0] > 5 * sizes["tb"][1]  # forced top to bottom: the strip it used to be
    assert "rankdir=TB" in stuart("show", TOUR, "--format", "dot", "--direction", "tb").stdout


def test_show_yaml_export_validates_and_draws_the_same(tmp_path: Path) -> None:
    trees = tmp_path / "trees"
    trees.mkdir()
    shutil.copy(REPO / "trees" / "station.yaml", trees)
    exported = trees / "lab_tour_expanded.yaml"
    result = stuart("show", TOUR, "--format", "yaml", "-o", exported)
    assert result.returncode == 0, result.stderr
    text = exported.read_text(encoding="utf-8")
    # Relative paths in the export are rewritten for the folder it is saved in.
    (line,) = [ln for ln in text.splitlines() if ln.startswith("markers: ")]
    assert (trees / line.split(": ", 1)[1]).resolve() == MARKERS.resolve()
    again = stuart("validate", exported)
    assert again.returncode == 0, again.stderr
    original = stuart("show", TOUR, "--format", "unicode").stdout
    redrawn = stuart("show", exported, "--format", "unicode").stdout
    assert "<- trees/station.yaml" in original
    # Includes are inlined by the export, so only the "<- station.yaml" origin notes may go.
    origin = re.compile(r"  <- \S+$", re.MULTILINE)
    assert origin.sub("", redrawn) == origin.sub("", original)


# -- run: the tour -------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def tour_run(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    tmp = tmp_path_factory.mktemp("tour")
    report, log = tmp / "r.json", tmp / "e.jsonl"
    result = stuart("run", TOUR, "--backend", "dry", "--speed", 40, "--view", "log",
                    "--report", report, "--log", log, timeout=60)
    return {"result": result, "report": report, "log": log, "leftovers": leftovers(daemon_pids(read_events(log)))}


def test_run_tour_succeeds(tour_run: dict[str, Any]) -> None:
    result = tour_run["result"]
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr
    assert_no_traceback(result.stdout, result.stderr)
    summary = rf"^SUCCESS in [\d.]+ s; visited {' -> '.join(STATIONS)};"
    assert re.search(summary, result.stdout, re.MULTILINE), result.stdout


def test_run_tour_report(tour_run: dict[str, Any]) -> None:
    report = json.loads(tour_run["report"].read_text(encoding="utf-8"))
    assert report["status"] == "SUCCESS"
    assert report["visited"] == STATIONS
    spoken = [line["text"] for line in report["spoken"]]
    for station, script in tour_scripts().items():
        assert script in spoken, f"{station}'s script was not spoken"
    assert report["failures"] == []
    assert report["backend"] == "dry" and report["tree"] == TOUR


def test_run_tour_event_log(tour_run: dict[str, Any]) -> None:
    lines = tour_run["log"].read_text(encoding="utf-8").splitlines()
    assert len(lines) > 100
    for number, line in enumerate(lines, 1):
        event = json.loads(line)
        assert isinstance(event, dict), f"line {number}"
        assert isinstance(event.get("t"), (int, float)) and isinstance(event.get("kind"), str), f"line {number}: {line}"
    events = [json.loads(line) for line in lines]
    assert {e["kind"] for e in events} >= {"run", "status", "command", "daemon", "daemon_state", "leaf"}
    stopped = {e["family"] for e in events if e["kind"] == "daemon_state" and e["state"] == "stopped"}
    assert stopped == FAMILIES


def test_run_tour_leaves_no_daemon(tour_run: dict[str, Any]) -> None:
    assert len(daemon_pids(read_events(tour_run["log"]))) == 3
    assert not tour_run["leftovers"], "\n".join(tour_run["leftovers"])


# -- run: stopping -------------------------------------------------------------------------------------
def _is_navigate(event: dict[str, Any]) -> bool:
    return event["kind"] == "command" and event.get("cmd") == "navigate"


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["ctrl-c", "sigterm"])
def test_interrupted_run_stops_every_daemon(background, sig: signal.Signals) -> None:
    run = background(TOUR, "--backend", "dry", "--speed", 5, "--view", "log")
    run.wait_for("navigate command", _is_navigate)
    ready = {e["family"] for e in run.events() if e["kind"] == "daemon_state" and e["state"] == "ready"}
    assert ready == FAMILIES
    sent = time.monotonic()
    if sig == signal.SIGINT:
        run.ctrl_c()
    else:
        run.proc.send_signal(sig)
    code = run.finish(timeout=10)
    assert code == 128 + sig, run.stderr  # 130 after Ctrl-C, 143 after SIGTERM
    assert time.monotonic() - sent < 3
    assert_no_traceback(run.stdout, run.stderr)
    assert re.search(r"^STOPPED in ", run.stdout, re.MULTILINE), run.stdout
    assert json.loads(run.report.read_text(encoding="utf-8"))["status"] == "STOPPED"

    events = run.events()
    [halt] = [i for i, e in enumerate(events) if e["kind"] == "halt"]
    assert sig.name in events[halt]["reason"]
    [end] = [i for i, e in enumerate(events) if e["kind"] == "run" and e["phase"] == "end"]
    stops = {e["family"]: e["id"] for e in events[halt:end] if e["kind"] == "command" and e["cmd"] == "stop"}
    assert set(stops) == ready, "every running daemon gets 'stop' before the run ends"
    acknowledged = {e["family"] for e in events if e["kind"] == "daemon" and e["type"] == "done"
                    and stops.get(e["family"]) == e["id"]}
    assert acknowledged == ready
    assert_no_leftovers(daemon_pids(events))


def test_more_ctrl_c_while_shutting_down_still_reaps_the_daemons(background) -> None:
    """docs/running.md: a second Ctrl-C skips the waiting; the daemons are still stopped and reaped.
    Here the user keeps pressing Ctrl-C while the daemons are being shut down, after the run ended."""
    run = background(TOUR, "--backend", "dry", "--speed", 5, "--view", "log")
    run.wait_for("navigate command", _is_navigate)
    run.ctrl_c()
    run.wait_for("daemon shutdown", lambda e: e["kind"] == "command" and e["cmd"] == "shutdown", timeout=5)
    deadline = time.monotonic() + 5
    while run.proc.poll() is None and time.monotonic() < deadline:
        run.ctrl_c()
        time.sleep(0.001)
    # A shell shows 130 both for exit(130) and for death by SIGINT.
    assert run.finish(timeout=5) in (130, -signal.SIGINT)
    assert_no_traceback(run.stdout, run.stderr)
    events = run.events()
    stopped = {e["family"] for e in events if e["kind"] == "command" and e["cmd"] == "stop"}
    assert stopped == FAMILIES
    assert_no_leftovers(daemon_pids(events))


# -- run: failures -------------------------------------------------------------------------------------
def test_run_with_a_failing_leaf(tmp_path: Path) -> None:
    tree = write_tree(tmp_path, "grab.yaml", """\
description: Pick the bottle up at the workbench, but the bottle is in the kitchen.
root:
  sequence:
    name: grab
    children:
      - navigate: workbench
      - pick: {object: bottle, arm: right}
""")
    report = tmp_path / "r.json"
    result = stuart("run", tree, "--backend", "dry", "--speed", 40, "--view", "log", "--report", report)
    assert result.returncode == 1, result.stdout + result.stderr
    assert_no_traceback(result.stdout, result.stderr)
    assert re.search(r"^FAILURE in [\d.]+ s; visited workbench;", result.stdout, re.MULTILINE), result.stdout
    failed = re.search(r"^  failed: grab/pick: (?P<reason>.+)$", result.stdout, re.MULTILINE)
    assert failed, result.stdout
    assert "unreachable" in failed["reason"] and "bottle" in failed["reason"]
    data = json.loads(report.read_text(encoding="utf-8"))
    assert data["status"] == "FAILURE"
    assert [(f["path"], f["reason"]) for f in data["failures"]] == [("grab/pick", failed["reason"])]


def test_run_a_bad_tree_starts_nothing(tmp_path: Path) -> None:
    bad = f"{DATA}/many_errors.yaml"
    log, report = tmp_path / "e.jsonl", tmp_path / "r.json"
    result = stuart("run", bad, "--backend", "dry", "--speed", 40, "--view", "log", "--log", log, "--report", report)
    assert result.returncode == 1
    assert_no_traceback(result.stdout, result.stderr)
    errors = error_lines(result.stderr)
    assert len(errors) == 5 and {e["file"] for e in errors} == {bad}
    assert [int(e["line"]) for e in errors] == [8, 9, 10, 11, 12]
    assert "daemon" not in result.stdout
    assert not report.exists()
    assert not [e for e in read_events(log) if e["kind"] == "daemon_state"], "no daemon may start for a bad tree"


# -- gestures, schema ----------------------------------------------------------------------------------
def test_gesture_list() -> None:
    result = stuart("gesture", "list")
    assert result.returncode == 0, result.stderr
    row = re.compile(r"^(?P<name>\S.*?)\s+(?P<id>\d+)\s+[\d.]+\s", re.MULTILINE)  # name, id, seconds, ...
    ids = {m["name"]: int(m["id"]) for m in row.finditer(result.stdout)}
    assert ids["high wave"] == 26
    assert ids["shake hand"] == 27
    assert len(ids) >= 10


def test_schema_matches_the_committed_one(tmp_path: Path) -> None:
    committed = json.loads((REPO / "docs" / "tree.schema.json").read_text(encoding="utf-8"))
    result = stuart("schema")
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout) == committed
    out = tmp_path / "schema.json"
    assert stuart("schema", "-o", out).returncode == 0
    assert json.loads(out.read_text(encoding="utf-8")) == committed


# -- kill -9 of a daemon mid-run -----------------------------------------------------------------------
LONG_WALK = """\
description: Walk to the bathroom; if that fails, wait, look around and check where we are.
root:
  selector:
    name: trip
    memory: true
    children:
      - navigate: {marker: bathroom, name: walk}
      - sequence:
          name: recover
          children:
            - wait: {seconds: 1.0, name: settle}
            - turn: {degrees: 10, name: look_around}
            - condition: {expr: "world.last_marker == 'bathroom'", name: arrived}
"""


@pytest.fixture(scope="module")
def killed_loco(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """Run a long walk, ``kill -9`` the locomotion daemon while the robot walks, let the run end.

    The walk is the only leaf that can reach the bathroom; after it fails, the tree waits one
    second, turns (which needs the restarted daemon) and ends in FAILURE since it did not arrive."""
    tmp = tmp_path_factory.mktemp("kill9")
    tree = write_tree(tmp, "long_walk.yaml", LONG_WALK)
    run = BackgroundRun(tmp, tree, "--backend", "dry", "--speed", 1, "--start", "entrance", "--view", "log")
    try:
        navigate = run.wait_for("navigate command", _is_navigate)
        ready = run.wait_for("loco ready", lambda e: e["kind"] == "daemon_state" and e["family"] == "loco"
                             and e["state"] == "ready")
        run.wait_for("the robot walking", lambda e: e["kind"] == "pose" and math.hypot(e["x"], e["y"]) > 0.25)
        killed_at = time.time()
        os.kill(ready["pid"], signal.SIGKILL)
        code = run.finish(timeout=30)
        events = run.events()
        return {"code": code, "events": events, "navigate": navigate, "pid": ready["pid"], "killed_at": killed_at,
                "stdout": run.stdout, "stderr": run.stderr,
                "report": json.loads(run.report.read_text(encoding="utf-8")),
                "leftovers": leftovers(daemon_pids(events))}
    finally:
        run.cleanup()


def test_kill_9_of_the_loco_daemon_fails_the_walk_and_restarts_it(killed_loco: dict[str, Any]) -> None:
    events, navigate = killed_loco["events"], killed_loco["navigate"]
    died = [i for i, e in enumerate(events) if e["kind"] == "daemon" and e["type"] == "error"
            and e.get("code") == "daemon_died"]
    assert len(died) == 1, "exactly one request was lost"
    lost = events[died[0]]
    assert (lost["family"], lost["id"], lost["path"]) == ("loco", navigate["id"], navigate["path"])
    delay = lost["wall"] - killed_loco["killed_at"]
    assert -0.01 <= delay <= 0.1, f"the lost request was failed {delay:.3f} s after the kill"

    walk = [e for e in events if e["kind"] == "leaf" and e["path"] == "trip/walk"]
    assert [(e["outcome"], "daemon_died" in (e["reason"] or "")) for e in walk] == [("FAILURE", True)]

    later = events[died[0]:]
    restarted = [e for e in later if e["kind"] == "daemon_state" and e["family"] == "loco" and e["state"] == "ready"]
    assert restarted and restarted[0]["pid"] != killed_loco["pid"], "the loco daemon is restarted"
    turned = [e for e in later if e["kind"] == "leaf" and e["path"] == "trip/recover/look_around"]
    assert [e["outcome"] for e in turned] == ["SUCCESS"], "the restarted daemon takes commands"

    assert killed_loco["code"] == 1
    assert killed_loco["report"]["status"] == "FAILURE"
    assert re.search(r"^FAILURE in ", killed_loco["stdout"], re.MULTILINE)
    assert "failed: trip/walk: daemon_died" in killed_loco["stdout"]
    assert_no_traceback(killed_loco["stdout"], killed_loco["stderr"])
    assert len(daemon_pids(events)) == 2
    assert not killed_loco["leftovers"], "\n".join(killed_loco["leftovers"])


def test_restarted_loco_daemon_keeps_the_robot_where_it_was(killed_loco: dict[str, Any]) -> None:
    """A crash of the daemon does not move the robot: after the restart the pose continues from the
    last one reported before the kill, not from the start marker."""
    events = killed_loco["events"]
    died = next(i for i, e in enumerate(events) if e["kind"] == "daemon" and e.get("code") == "daemon_died")
    before = [e for e in events[:died] if e["kind"] == "pose"][-1]
    after = next(e for e in events[died:] if e["kind"] == "pose")
    assert math.hypot(before["x"], before["y"]) > 0.25
    jump = math.hypot(after["x"] - before["x"], after["y"] - before["y"])
    assert jump < 0.1, f"the robot jumped {jump:.2f} m from {before} to {after} when the daemon restarted"
