"""The planner's symbolic state: named state variables, as a GTPyhop user knows them.

A :class:`State` is a mapping from variable names to plain values (``at``, ``held``, ``objects``
{label: place name or {x, y, z}}, ``markers``, ``visited``, ...); hooks may also read them as
attributes (``state.objects``). Values are treated as immutable: an effect replaces a variable's
value (a key effect ``objects[obj]`` copies the mapping first), so the planner can undo effects
by putting old values back and a state handed out is never changed behind the caller's back.

The start state comes from the executor's :class:`~stuart_bt.core.world.WorldState` (pose, held
object, known objects, markers, last marker) via :meth:`State.from_world`; variables the world
does not know (``visited``, ``speaker_at``, domain settings) come from the domain's declared
defaults (:meth:`stuart_bt.htn.domain.Domain.initial_state`).
"""

from __future__ import annotations

import json
from collections.abc import Iterator, MutableMapping
from importlib.resources import files
from pathlib import Path
from typing import Any

from ..core.errors import StuartError
from ..core.jsonfile import read_json
from ..core.world import KnownObject, Pose, WorldState
from ..maps.markers import load_markers

ARRIVAL_TOLERANCE = 0.5  # metres: within this of a marker the robot counts as being there (thesis)
START_MARKER = "entrance"


class StateFileError(StuartError, ValueError):
    """A start-state file that cannot be read; the message names the file."""


class State(MutableMapping[str, Any]):
    """Named state variables. ``state["at"]`` and ``state.at`` read the same variable."""

    __slots__ = ("_vars",)

    def __init__(self, variables: dict[str, Any] | None = None, /, **more: Any) -> None:
        object.__setattr__(self, "_vars", {**(variables or {}), **more})

    def __getitem__(self, name: str) -> Any:
        return self._vars[name]

    def __setitem__(self, name: str, value: Any) -> None:
        self._vars[name] = value

    def __delitem__(self, name: str) -> None:
        del self._vars[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._vars)

    def __len__(self) -> int:
        return len(self._vars)

    def __contains__(self, name: object) -> bool:
        return name in self._vars

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):  # copy/pickle probing, or _vars before it is set
            raise AttributeError(name)
        try:
            return self._vars[name]
        except KeyError:
            raise AttributeError(f"state has no variable {name!r}") from None

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("set state variables with state[name] = value")

    def __repr__(self) -> str:
        return f"State({self._vars!r})"

    def copy(self) -> State:
        """A state with the same variables; values are shared (they are never changed in place)."""
        return State(dict(self._vars))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready variables (task values become their text)."""
        return {k: jsonable(v) for k, v in self._vars.items()}

    @classmethod
    def from_world(cls, world: WorldState, speaker_at: Any = None) -> State:
        """The symbolic view of the executor's world. ``at`` is the last marker when the robot
        still stands within 0.5 m of it, else null; ``speaker_at`` (where a command came from,
        for ``bring``) defaults to where the robot is now."""
        at = world.last_marker
        marker = world.markers.get(at) if at is not None else None
        if marker is None or marker.pose.distance_to(world.pose) > ARRIVAL_TOLERANCE:
            at = None
        pose = world.pose.to_dict()
        return cls(
            at=at,
            pose=pose,
            held=world.held,
            near=None,
            objects={label: _position(o) for label, o in world.objects.items()},
            markers={name: {"x": m.x, "y": m.y, "yaw": m.yaw} for name, m in world.markers.items()},
            names={name: spoken_name(m.label) for name, m in world.markers.items()},
            speaker_at=speaker_at if speaker_at is not None else (at if at is not None else dict(pose)),
        )

    @classmethod
    def load(cls, path: str | Path) -> State:
        """A state from a JSON object of variables, e.g. ``{"at": "kitchen", "held": null}``."""
        path = Path(path)
        doc = read_json(path, StateFileError, "state file")
        if not isinstance(doc, dict):
            raise StateFileError(f"{path}: a state file holds one JSON object of state variables")
        return cls(doc)


def spoken_name(label: str) -> str:
    """'Kitchen' -> 'kitchen', 'Drone cage' -> 'drone cage', '3D printers' stays: for speech."""
    if len(label) > 1 and label[0].isupper() and label[1].islower():
        return label[0].lower() + label[1:]
    return label


def with_marker_names(values: dict[str, Any]) -> dict[str, Any]:
    """``values`` with a spoken name for every marker that has none ('charging_dock' -> 'charging
    dock'): a hand-written state file lists markers and rarely bothers with names."""
    markers, names = values.get("markers"), values.get("names")
    if not isinstance(markers, dict):
        return values
    names = dict(names) if isinstance(names, dict) else {}
    for marker in markers:
        names.setdefault(marker, str(marker).replace("_", " "))
    return {**values, "names": names}


def _position(o: KnownObject) -> dict[str, float]:
    return {"x": o.x, "y": o.y, "z": o.z}


def lab_world(markers_file: str | Path | None = None, objects_file: str | Path | None = None,
              start: str = START_MARKER) -> WorldState:
    """The lab as the dry and sim backends know it: markers (sim/maps/lab_markers.json), objects
    (skills/objects.json) and the robot standing at ``start``."""
    default_markers = Path(str(files("stuart_bt.sim").joinpath("maps/lab_markers.json")))
    markers = load_markers(markers_file or default_markers)
    objects_path = Path(str(objects_file or files("stuart_bt.skills").joinpath("objects.json")))
    try:
        entries = json.loads(objects_path.read_text(encoding="utf-8"))["objects"]
        objects = {label: KnownObject(label, float(v["x"]), float(v["y"]), float(v.get("z", 0.0)))
                   for label, v in entries.items()}
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
        raise StateFileError(f"{objects_path}: cannot read objects: {e}") from None
    if start not in markers:
        raise StateFileError(f"start marker {start!r} is not in the marker file")
    return WorldState(pose=Pose(markers[start].x, markers[start].y, markers[start].yaw),
                      objects=objects, markers=markers, last_marker=start)


def jsonable(value: Any, depth: int = 0) -> Any:
    """Plain JSON data for a state value (tuples become lists, other objects their text)."""
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if depth > 50:
        return "..."
    if isinstance(value, dict):
        return {str(k): jsonable(v, depth + 1) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v, depth + 1) for v in value]
    return str(value)
