"""``python -m bench.run [--quick] [-o PATH] [--only NAME]``: run the benchmarks, print a table,
write results JSON.

Each benchmark module exposes ``run(quick) -> list[Result]``; this module only schedules them
and reports. Exit status: 0 when every benchmark ran (goals unmet are reported, not fatal: a
loaded machine should not fail a build), 1 when one crashed, 2 for bad arguments.
"""

from __future__ import annotations

import argparse
import datetime
import importlib.metadata
import json
import os
import platform
import sys
import time
import traceback
from pathlib import Path
from typing import Any, Callable

from . import roundtrip, tick_overhead
from .result import Result

BENCHMARKS: dict[str, Callable[[bool], list[Result]]] = {
    tick_overhead.NAME: tick_overhead.run,
    roundtrip.NAME: roundtrip.run,
}
DEFAULT_OUTPUT = Path(__file__).with_name("results.json")
PACKAGES = ("py_trees", "behaviortreepy", "ros-rclpy", "stuart-bt")
COLUMNS = ("benchmark", "figure", "value", "unit", "anchor", "anchor value", "ratio", "goal", "met?")


def machine() -> dict[str, Any]:
    return {
        "cpu_count": os.cpu_count(),
        "python": platform.python_version(),
        "platform": platform.platform(),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
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
        rows.append((r.benchmark, r.figure, _num(r.value), r.unit, _short(r.anchor.name) if r.anchor else "none",
                     _num(r.anchor.value if r.anchor else None), _num(r.ratio), r.goal or "-", met))
    widths = [max(len(row[i]) for row in rows) for i in range(len(COLUMNS))]
    lines = ["  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip() for row in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="python -m bench.run", description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="few repetitions: a smoke test, not a measurement")
    parser.add_argument("-o", "--output", type=Path, default=DEFAULT_OUTPUT, help="results JSON (default: %(default)s)")
    parser.add_argument("--only", choices=sorted(BENCHMARKS), action="append",
                        help="run only this benchmark (repeatable)")
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    try:
        args = parse_args(argv)
    except SystemExit as e:
        return int(e.code or 0)
    selected = args.only or list(BENCHMARKS)
    results: list[Result] = []
    errors: dict[str, str] = {}
    started = time.monotonic()
    for name in selected:
        print(f"running {name}{' (quick)' if args.quick else ''} ...", file=sys.stderr, flush=True)
        try:
            results += BENCHMARKS[name](args.quick)
        except Exception as e:  # one broken benchmark must not hide the others' figures
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
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(report, indent=2) + "\n", encoding="utf-8")
    print(table(results))
    for name, message in errors.items():
        print(f"{name} FAILED: {message}", file=sys.stderr)
    unmet = [r.name for r in results if r.met is False]
    print(f"\n{len(results)} figures, {len(unmet)} goal(s) unmet{': ' + ', '.join(unmet) if unmet else ''}; "
          f"written to {args.output}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
