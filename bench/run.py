"""``python -m bench.run [--quick] [-o PATH] [--only NAME]``: run the benchmarks, print a table,
write results JSON.

With ``--only``, the figures of the benchmarks not run this time are carried over from the
existing output file (``kept`` in the JSON says which, and when and how they were measured), so
re-running one benchmark never loses the others' results.

Each benchmark module exposes ``run(quick) -> list[Result]``; this module only schedules them
and reports. Every row of the table shows the absolute figure, its anchor and their ratio; a goal
on a time or a speed is judged on the ratio (bench/result.py), and the absolute goal it replaced
is in the last column as information. Exit status: 0 when every benchmark ran (goals unmet are reported, not fatal: a
loaded machine should not fail a build), 1 when one crashed, 2 for bad arguments.
"""

from __future__ import annotations

import argparse
import contextlib
import datetime
import importlib.metadata
import json
import os
import platform
import shutil
import sys
import tempfile
import time
import traceback
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from . import hearing, htn, ik, llm, mission, parse, perception, ros, roundtrip, sim, soak, tick_overhead, unitree, web
from .result import Result

BENCHMARKS: dict[str, Callable[[bool], list[Result]]] = {
    tick_overhead.NAME: tick_overhead.run,
    roundtrip.NAME: roundtrip.run,
    ik.NAME: ik.run,
    sim.NAME: sim.run,
    htn.NAME: htn.run,
    parse.NAME: parse.run,
    hearing.NAME: hearing.run,
    mission.NAME: mission.run,
    llm.NAME: llm.run,
    ros.NAME: ros.run,
    perception.NAME: perception.run,
    web.NAME: web.run,
    unitree.NAME: unitree.run,
    soak.NAME: soak.run,
}
DEFAULT_OUTPUT = Path(__file__).with_name("results.json")
PACKAGES = ("py_trees", "behaviortreepy", "ros-rclpy", "gtpyhop", "stuart-bt")
COLUMNS = ("benchmark", "figure", "value", "unit", "anchor", "anchor value", "ratio", "goal", "met?", "was")


def machine() -> dict[str, Any]:
    return {
        "cpu_count": os.cpu_count(),
        "python": platform.python_version(),
        "platform": platform.platform(),
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
    }


def package_versions() -> dict[str, str | None]:
    versions: dict[str, str | None] = {}
    for name in PACKAGES:
        try:
            versions[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            versions[name] = None
    return versions


def _num(value: float | None) -> str:
    if value is None:
        return "-"
    return f"{value:.3g}" if abs(value) < 1000 else f"{value:.0f}"


def _short(text: str, width: int = 44) -> str:
    return text if len(text) <= width else text[: width - 1] + "~"


def table(results: list[Result]) -> str:
    rows = [COLUMNS]
    for r in results:
        met = "-" if r.met is None else ("yes" if r.met else "NO")
        anchor = "none" if r.anchor is None else _short(r.anchor.name) + ("" if r.anchor.timed else " (constant)")
        rows.append((r.benchmark, r.figure, _num(r.value), r.unit, anchor, _num(r.anchor.value if r.anchor else None),
                     _num(r.ratio), r.goal.text if r.goal else "-", met, (r.goal and r.goal.was) or "-"))
    widths = [max(len(row[i]) for row in rows) for i in range(len(COLUMNS))]
    lines = ["  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)).rstrip() for row in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def benchmark_of(result: dict[str, Any]) -> str:
    return str(result.get("name", "")).split(".", 1)[0]


def merge_previous(report: dict[str, Any], path: Path, selected: list[str]) -> None:
    """Carry over from the report at ``path`` every figure (and error) of a benchmark that is
    not in ``selected``; a missing or unreadable file carries nothing over."""
    try:
        previous = json.loads(path.read_text(encoding="utf-8"))
        old_results = [r for r in previous.get("results", []) if benchmark_of(r) not in selected]
        old_errors = {k: v for k, v in previous.get("errors", {}).items() if k not in selected}
    except (OSError, ValueError, AttributeError, TypeError):
        return
    if not old_results and not old_errors:
        return
    # when each carried-over benchmark really ran: a figure kept twice keeps its first date
    earlier = previous.get("kept", {}) if isinstance(previous.get("kept"), dict) else {}
    this = {"from": previous.get("machine", {}).get("date"), "quick": previous.get("quick")}
    names = sorted({benchmark_of(r) for r in old_results} | set(old_errors))
    order = {name: i for i, name in enumerate(BENCHMARKS)}
    report["results"] = sorted(old_results + report["results"], key=lambda r: order.get(benchmark_of(r), len(order)))
    report["errors"] = {**old_errors, **report["errors"]}
    report["kept"] = {name: earlier.get(name, this) for name in names}


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="python -m bench.run", description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="few repetitions: a smoke test, not a measurement")
    parser.add_argument("-o", "--output", type=Path, default=DEFAULT_OUTPUT, help="results JSON (default: %(default)s)")
    parser.add_argument("--only", choices=sorted(BENCHMARKS), action="append",
                        help="run only this benchmark (repeatable)")
    return parser.parse_args(argv)


@contextlib.contextmanager
def private_temporary_folder() -> Iterator[Path]:
    """Everything the benchmarks and their processes write to a temporary folder goes to one of
    this run's own, removed at the end; so does PortAudio's PulseAudio client (listing
    microphones), which would otherwise leave a runtime folder in /tmp linked from ~/.config/pulse."""
    folder = Path(tempfile.mkdtemp(prefix="stuart_bt-bench-"))
    saved = {k: os.environ.get(k) for k in ("TMPDIR", "PULSE_RUNTIME_PATH")}
    os.environ["TMPDIR"], os.environ["PULSE_RUNTIME_PATH"] = str(folder), str(folder / "pulse")
    tempfile.tempdir = None  # gettempdir() looks at TMPDIR again
    try:
        yield folder
    finally:
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value
        tempfile.tempdir = None
        shutil.rmtree(folder, ignore_errors=True)


def main(argv: list[str] | None = None) -> int:
    try:
        args = parse_args(argv)
    except SystemExit as e:
        return int(e.code or 0)
    selected = args.only or list(BENCHMARKS)
    results: list[Result] = []
    errors: dict[str, str] = {}
    started = time.monotonic()
    with private_temporary_folder():
        for name in selected:
            print(f"running {name}{' (quick)' if args.quick else ''} ...", file=sys.stderr, flush=True)
            try:
                results += BENCHMARKS[name](args.quick)
            except Exception as e:  # noqa: BLE001 - one broken benchmark must not hide the others' figures
                traceback.print_exc()
                errors[name] = f"{type(e).__name__}: {e}"
    report = {
        "machine": machine(),
        "packages": package_versions(),
        "quick": args.quick,
        "seconds": round(time.monotonic() - started, 1),
        "results": [r.to_dict() for r in results],
        "errors": errors,
    }
    if args.only:
        merge_previous(report, args.output, selected)
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(report, indent=2) + "\n", encoding="utf-8")
    print(table(results))
    for name, message in errors.items():
        print(f"{name} FAILED: {message}", file=sys.stderr)
    unmet = [r.name for r in results if r.met is False]
    kept = list(report.get("kept", {}))
    print(f"\n{len(results)} figures, {len(unmet)} goal(s) unmet{': ' + ', '.join(unmet) if unmet else ''}; "
          f"written to {args.output}{' (kept from before: ' + ', '.join(kept) + ')' if kept else ''}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
