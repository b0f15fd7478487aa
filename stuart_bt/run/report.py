"""The run report: what a run did, built only from the event stream.

:class:`ReportBuilder` subscribes to the events of a run and, at the end, folds them into one JSON
document: status, duration, visited markers in order, spoken lines (with start and end so overlap
with gestures can be checked), gestures, picks and releases, final pose, failures with node path
and reason, and every event. The same function (:func:`build_report`) works on a saved JSON-lines
log, so a report can be rebuilt after the fact.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ..core.events import Event, EventRecorder, EventStream
from ..core.jsonfile import to_json


class ReportBuilder(EventRecorder):
    def __init__(self, stream: EventStream, limit: int | None = None) -> None:
        super().__init__(stream, limit)

    def build(self, **summary: Any) -> dict[str, Any]:
        return build_report(self.events, **summary)


def build_report(events: Iterable[Event], **summary: Any) -> dict[str, Any]:
    """Fold events into the report. ``summary`` adds or overrides top-level fields (status, ...)."""
    events = list(events)
    commands: dict[tuple[str, str], dict[str, Any]] = {}  # (family, id) -> record
    visited: list[str] = []
    spoken: list[dict[str, Any]] = []
    gestures: list[dict[str, Any]] = []
    picks: list[dict[str, Any]] = []
    releases: list[dict[str, Any]] = []
    found: list[dict[str, Any]] = []
    failures: list[dict[str, Any]] = []
    final_pose: dict[str, Any] | None = None
    warnings: list[str] = []

    for e in events:
        d = e.data
        if e.kind == "command":
            commands[(d.get("family", ""), str(d.get("id")))] = {
                "cmd": d.get("cmd"), "args": d.get("args") or {}, "path": e.path, "start": e.t,
            }
        elif e.kind == "daemon" and d.get("type") in ("done", "error"):
            record = commands.get((d.get("family", ""), str(d.get("id"))))
            if record is None:
                continue
            result = d.get("result") or {}
            if "pose" in result:
                final_pose = result["pose"]
            if d["type"] != "done":
                continue
            _collect(record, result, e.t, visited, spoken, gestures, picks, releases, found)
        elif e.kind == "leaf" and d.get("outcome") == "FAILURE" and d.get("skill") != "condition":
            # a false condition is an answer (control flow), not a failure
            failures.append({"path": e.path, "skill": d.get("skill"), "reason": d.get("reason"), "t": e.t,
                             **({"detail": d["detail"]} if d.get("detail") else {})})
        elif e.kind == "warning":
            warnings.append(str(d.get("message")))
        elif e.kind == "pose":
            final_pose = {k: d[k] for k in ("x", "y", "yaw") if k in d}

    run_events = [e for e in events if e.kind == "run"]
    start = run_events[0].t if run_events else (events[0].t if events else 0.0)
    end = run_events[-1].t if len(run_events) > 1 else (events[-1].t if events else 0.0)
    report: dict[str, Any] = {
        "status": None,
        "duration": round(end - start, 3),
        "visited": visited,
        "spoken": spoken,
        "gestures": gestures,
        "picks": picks,
        "releases": releases,
        "found": found,
        "final_pose": final_pose,
        "failures": failures,
        "warnings": warnings,
    }
    report.update(summary)
    report["events"] = [e.to_dict() for e in events]
    return report


def _collect(record: dict[str, Any], result: dict[str, Any], t: float, visited: list[str],
             spoken: list[dict[str, Any]], gestures: list[dict[str, Any]], picks: list[dict[str, Any]],
             releases: list[dict[str, Any]], found: list[dict[str, Any]]) -> None:
    cmd, args, path = record["cmd"], record["args"], record["path"]
    span = {"path": path, "start": round(record["start"], 3), "end": round(t, 3)}
    if cmd == "navigate" and (result.get("marker") or args.get("marker")):
        visited.append(result.get("marker") or args["marker"])
    elif cmd == "say":
        spoken.append({"text": result.get("text", args.get("text")), **span})
    elif cmd == "play":
        name = args.get("name") or args.get("sequence") or "recorded"
        gestures.append({"name": name, **span})
    elif cmd == "pick":
        picks.append({"object": result.get("object", args.get("object")), "arm": result.get("arm"), **span})
    elif cmd == "release":
        releases.append({"object": result.get("object"), "position": result.get("position"), **span})
    elif cmd == "find":
        found.append({"object": result.get("object", args.get("object")), "position": result.get("position"), **span})


def write_report(report: dict[str, Any], path: str | Path) -> None:
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(to_json(report, indent=2, default=str) + "\n", encoding="utf-8")
