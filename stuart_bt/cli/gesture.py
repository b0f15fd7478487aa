"""``stuart-bt gesture ...``: list the library, record gesture files, check them, preview them.

Why a module of its own: recording is the one place a user types joint angles by hand, so it
owns the parsing and the messages for that (unknown joint with a suggestion, bad number, angle
beyond its limit with the limit, time not increasing), and it checks everything before a file is
written, because the gesture daemon refuses a file with any problem only when the tree runs.

Every command prints problems one per line and exits 1 with nothing written; no tracebacks.
Heavy imports (the robot description, numpy, the world client) happen inside the commands, so
``stuart-bt --help`` stays fast.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..core.errors import StuartError

if TYPE_CHECKING:
    from ..skills.gesture.backend import Keyframe

EXIT_OK, EXIT_FAILED = 0, 1
ROUND = 5  # decimals gesture files keep (save_gesture_file rounds to these)
DEGREE_SUFFIXES = ("deg", "°")
NEUTRAL_WORD = "neutral"  # in a keyframe: every arm and hand joint back to the neutral pose


class Problems(StuartError):
    """Everything wrong with a command's input; printed one per line, exit 1."""

    def __init__(self, problems: list[str]) -> None:
        super().__init__("; ".join(problems))
        self.problems = problems


# -- parsing keyframes from the command line ---------------------------------------------------------
def resolve_joint(name: str, known: Iterable[str]) -> tuple[str | None, str]:
    """(joint, "") for a known name or one missing only its ``_joint`` suffix; (None, hint) otherwise."""
    from ..core.suggest import did_you_mean

    known = tuple(known)
    if name in known:
        return name, ""
    if f"{name}_joint" in known:
        return f"{name}_joint", ""
    return None, did_you_mean(name, known)


def parse_angle(text: str) -> float:
    """Radians from ``0.3`` or degrees from ``30deg`` / ``30°``; ValueError if not a finite number."""
    scale = 1.0
    for suffix in DEGREE_SUFFIXES:
        if text.endswith(suffix):
            text, scale = text[: -len(suffix)], math.pi / 180.0
            break
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(text)
    return value * scale


def parse_keyframe(text: str, limits: Mapping[str, tuple[float, float]]) -> tuple[float | None, dict[str, float],
                                                                                  list[str]]:
    """``"TIME joint=rad ..."`` -> (time, joints, problems). Every token is checked, so one run
    reports every mistake in the keyframe; limits are checked here too, with the limit. The
    word ``neutral`` puts every arm and hand joint back to the neutral pose (tokens after it
    still apply), so a gesture can end where it started without 28 numbers."""
    from ..skills.gesture.keyframes import NEUTRAL

    tokens = text.split()
    if not tokens:
        return None, {}, ["is empty: expected 'TIME joint=rad ...'"]
    problems: list[str] = []
    t: float | None = None
    try:
        t = float(tokens[0])
        if not math.isfinite(t) or t < 0:
            problems.append(f"time {tokens[0]!r} must be a non-negative number of seconds")
            t = None
    except ValueError:
        problems.append(f"must start with a time in seconds, got {tokens[0]!r}")
    joints: dict[str, float] = {}
    named: set[str] = set()
    for token in tokens[1:]:
        if token.lower() == NEUTRAL_WORD:
            joints.update(NEUTRAL)
            continue
        name, sep, raw = token.partition("=")
        if not sep or not name:
            problems.append(f"expected joint=radians or {NEUTRAL_WORD!r}, got {token!r}")
            continue
        joint, hint = resolve_joint(name, limits)
        if joint is None:
            problems.append(f"unknown joint {name!r}{hint}")
            continue
        try:
            value = parse_angle(raw)
        except ValueError:
            problems.append(f"{joint} = {raw!r} is not a number of radians (or degrees with 'deg')")
            continue
        if joint in named:
            problems.append(f"names {joint} twice")
            continue
        named.add(joint)
        lo, hi = limits[joint]
        if not lo - 1e-9 <= value <= hi + 1e-9:
            problems.append(f"{joint} = {value:.4f} rad is outside its limits [{lo:.4f}, {hi:.4f}]")
            continue
        joints[joint] = value
    return t, joints, problems


def inward(value: float, lo: float, hi: float) -> float:
    """``value`` rounded as the file keeps it, never rounded past a limit (a joint recorded at
    its limit must load again)."""
    q = round(min(max(value, lo), hi), ROUND)
    if q > hi:
        q = math.floor(hi * 10**ROUND) / 10**ROUND
    if q < lo:
        q = math.ceil(lo * 10**ROUND) / 10**ROUND
    return q


def world_pose(socket_path: str, limits: Mapping[str, tuple[float, float]]) -> dict[str, float]:
    """The arm and hand joints of the world at ``socket_path`` right now."""
    from ..sim.world.client import WorldClient, WorldError
    from ..skills.gesture.keyframes import NEUTRAL

    try:
        with WorldClient(socket_path, timeout=10.0, connect_timeout=2.0) as client:
            joints = client.call("state").get("joints", {})
    except WorldError as e:
        raise Problems([f"cannot read the pose from the world at {socket_path}: {e.reason}"]) from None
    except OSError as e:
        raise Problems([f"cannot reach the world at {socket_path}: {e.strerror or e}"]) from None
    missing = [name for name in NEUTRAL if name not in joints]
    if missing:
        raise Problems([f"the world at {socket_path} has no joint(s) {', '.join(missing)}"])
    pose: dict[str, float] = {}
    problems = []
    for name in NEUTRAL:
        lo, hi = limits[name]
        value = float(joints[name])
        if not lo - 1e-6 <= value <= hi + 1e-6:  # physics may sit a hair past a limit, no more
            problems.append(f"--from-world: {name} = {value:.4f} rad is outside its limits [{lo:.4f}, {hi:.4f}]")
        pose[name] = value
    if problems:
        raise Problems(problems)
    return pose


def build_keyframes(texts: list[str], previous: list[Keyframe], world: dict[str, float] | None,
                    at: float | None, limits: Mapping[str, tuple[float, float]]) -> list[Keyframe]:
    """``previous`` frames, then one full frame per ``--keyframe``, then the world's pose at
    ``at``. A joint a frame does not name keeps the previous frame's value (NEUTRAL before the
    first frame). Raises :class:`Problems` with every problem found."""
    from ..skills.gesture.backend import Keyframe
    from ..skills.gesture.keyframes import NEUTRAL

    carry = dict(NEUTRAL)
    for frame in previous:
        carry.update(frame.joints)
    last_t = previous[-1].t if previous else None
    frames = list(previous)
    problems: list[str] = []

    def add(label: str, t: float | None, joints: dict[str, float]) -> None:
        nonlocal last_t
        if t is not None:
            if last_t is not None and t <= last_t:
                problems.append(f"{label}: time {t:g} s does not come after the previous keyframe's {last_t:g} s")
            else:
                last_t = t
        carry.update(joints)
        if t is not None:
            frames.append(Keyframe(t, {k: inward(v, *limits[k]) for k, v in carry.items()}))

    for n, text in enumerate(texts, 1):
        t, joints, found = parse_keyframe(text, limits)
        label = f"--keyframe {n}" + (f" (t = {t:g} s)" if t is not None else "")
        problems += [f"{label}: {p}" for p in found]
        add(label, t, joints)
    if world is not None:
        if at is None:
            at = last_t + 1.0 if last_t is not None else 1.0
        add(f"--from-world (t = {at:g} s)", at, world)
    if problems:
        raise Problems(problems)
    if len(frames) == len(previous):
        raise Problems(["nothing to record: give --keyframe 'TIME joint=rad ...' and/or --from-world SOCKET"])
    return frames


# -- describing keyframes ----------------------------------------------------------------------------
def moved_groups(frames: list[Keyframe]) -> list[str]:
    """Which limbs a gesture moves (differs from NEUTRAL anywhere, or changes between frames)."""
    names = _moving_joints(frames)
    groups = []
    from ..skills.gesture.keyframes import JOINT_GROUPS

    for label, prefix, is_hand in JOINT_GROUPS:
        if any(n.startswith(prefix) and ("_hand_" in n) == is_hand for n in names):
            groups.append(label)
    return groups


def _moving_joints(frames: list[Keyframe]) -> list[str]:
    from ..skills.gesture.keyframes import GESTURE_JOINTS, NEUTRAL

    named = [j for j in GESTURE_JOINTS if any(j in f.joints for f in frames)]
    out = []
    for j in named:
        values = [f.joints[j] for f in frames if j in f.joints]
        if max(values) - min(values) > 1e-9 or abs(values[0] - NEUTRAL.get(j, 0.0)) > 1e-9:
            out.append(j)
    return out


def keyframe_table(frames: list[Keyframe], limits: Mapping[str, tuple[float, float]], degrees: bool = False,
                   all_joints: bool = False) -> str:
    """One row per joint, one column per keyframe time, then the joint's limits. Only joints
    that move are shown unless ``all_joints``; a joint a frame does not name is blank."""
    from ..skills.gesture.keyframes import GESTURE_JOINTS

    rows = [j for j in GESTURE_JOINTS if any(j in f.joints for f in frames)] if all_joints else _moving_joints(frames)
    scale, unit = (180.0 / math.pi, "deg") if degrees else (1.0, "rad")
    digits = 1 if degrees else 3

    def cell(v: float | None) -> str:
        return "" if v is None else f"{v * scale:.{digits}f}"

    header = [f"joint ({unit})", *(f"{f.t:g} s" for f in frames), "limits"]
    body = [[j, *(cell(f.joints.get(j)) for f in frames), f"[{cell(limits[j][0])}, {cell(limits[j][1])}]"]
            for j in rows]
    if not body:
        body = [["(no joint moves: every frame is the neutral pose)", *([""] * (len(header) - 1))]]
    table = [header, *body]
    widths = [max(len(r[i]) for r in table) for i in range(len(header))]
    lines = []
    for r in table:
        cells = [r[0].ljust(widths[0]), *(c.rjust(w) for c, w in zip(r[1:-1], widths[1:-1], strict=True)), r[-1]]
        lines.append("  ".join(cells).rstrip())
    return "\n".join(lines)


# -- commands ----------------------------------------------------------------------------------------
def cmd_gesture_list(args: argparse.Namespace) -> int:
    from ..core import gestures

    aliases: dict[str, list[str]] = {}
    for alias, target in gestures.ALIASES.items():
        aliases.setdefault(target, []).append(alias)
    print(f"{'name':<16} {'id':>4}  {'seconds':>7}  {'holds':<5}  aliases")
    for g in gestures.LIBRARY.values():
        print(f"{g.name:<16} {g.action_id:>4}  {g.duration:>7.1f}  {'yes' if g.holds else 'no':<5}  "
              f"{', '.join(aliases.get(g.name, []))}")
    return EXIT_OK


def cmd_gesture_record(args: argparse.Namespace) -> int:
    from ..skills.gesture.keyframes import GestureFileError, load_gesture_file, save_gesture_file

    out = Path(args.output)
    try:
        if not args.name.strip():
            raise Problems(["NAME must not be empty"])
        if args.at is not None and not args.from_world:
            raise Problems(["--at needs --from-world"])
        if args.at is not None and (not math.isfinite(args.at) or args.at < 0):
            raise Problems([f"--at {args.at:g} must be a non-negative number of seconds"])
        from ..skills.gesture.keyframes import joint_limits

        limits = joint_limits()
        previous = []
        if args.append and out.exists():
            try:
                previous = load_gesture_file(out).keyframes
            except GestureFileError as e:
                raise Problems([f"--append: {out}: {p}" for p in e.problems]) from None
        world = world_pose(args.from_world, limits) if args.from_world else None
        frames = build_keyframes(args.keyframe or [], previous, world, args.at, limits)
        try:
            save_gesture_file(out, args.name.strip(), frames)
            load_gesture_file(out)  # what the player will read must load
        except GestureFileError as e:
            out.unlink(missing_ok=True)
            raise Problems([f"{out}: {p}" for p in e.problems]) from None
    except Problems as e:
        for problem in e.problems:
            print(f"stuart-bt: {problem}", file=sys.stderr)
        print(f"stuart-bt: nothing written to {out}", file=sys.stderr)
        return EXIT_FAILED
    added = len(frames) - len(previous)
    print(f"wrote {out}: {args.name.strip()!r}, {_count(len(frames))} ({added} new) over {frames[-1].t:g} s; "
          f"moves {', '.join(moved_groups(frames)) or 'nothing'}", file=sys.stderr)
    return EXIT_OK


def _count(n: int) -> str:
    return f"{n} keyframe{'' if n == 1 else 's'}"


def load_for_show(source: str) -> tuple[str, list[Keyframe], str]:
    """(name, keyframes, where) of a gesture file, or of a library gesture when ``source`` is no
    file but a gesture name (its sim keyframes). Raises :class:`Problems`."""
    from ..core import gestures
    from ..skills.gesture.keyframes import gesture_file_problems, keyframes, load_gesture_file

    path = Path(source)
    library = gestures.lookup(source) if not path.exists() else None
    if library is not None:
        return library.name, keyframes(library.name), f"library gesture, vendor id {library.action_id}"
    problems = gesture_file_problems(path)
    if problems:
        if problems == ["file not found"]:
            from ..core.suggest import did_you_mean

            problems = [f"file not found{did_you_mean(source, gestures.names())}"]
        raise Problems([f"{source}: {p}" for p in problems])
    gesture = load_gesture_file(path)
    return gesture.name, gesture.keyframes, str(path)


def _load_or_report(source: str) -> tuple[str, list[Keyframe], str] | None:
    """:func:`load_for_show`, or ``None`` after printing each problem on stderr."""
    try:
        return load_for_show(source)
    except Problems as e:
        for problem in e.problems:
            print(problem, file=sys.stderr)
        return None


def cmd_gesture_show(args: argparse.Namespace) -> int:
    from ..skills.gesture.keyframes import joint_limits

    loaded = _load_or_report(args.file)
    if loaded is None:
        return EXIT_FAILED
    name, frames, where = loaded
    limits = joint_limits()
    groups = moved_groups(frames)
    print(f"{name!r} ({where}): ok, {_count(len(frames))} over "
          f"{frames[-1].t:g} s; moves {', '.join(groups) or 'nothing'}")
    if frames[0].t > 0:
        print(f"the player blends from wherever the arms are into the first keyframe over {frames[0].t:g} s")
    print(keyframe_table(frames, limits, degrees=args.degrees, all_joints=args.all))
    return EXIT_OK


def cmd_gesture_play(args: argparse.Namespace) -> int:
    """Preview a gesture file or a library gesture on a running world's arms."""
    from ..sim.world.client import WorldClient, WorldError
    from ..skills.gesture.sim import BLEND_SECONDS, BLEND_THRESHOLD

    loaded = _load_or_report(args.file)
    if loaded is None:
        return EXIT_FAILED
    name, frames, _ = loaded
    try:
        with WorldClient(args.world, timeout=10.0, connect_timeout=2.0) as client:
            now = client.call("state")
            current = now.get("joints", {})
            first = frames[0]
            far = max((abs(v - float(current.get(j, v))) for j, v in first.joints.items()), default=0.0)
            offset = BLEND_SECONDS if first.t == 0 and far > BLEND_THRESHOLD else 0.0
            points = [{"t": f.t + offset, "joints": f.joints} for f in frames]
            reply = client.call("arm_trajectory", points=points, id=f"preview {name}")
            print(f"playing {name!r} on the world at {args.world}: {points[-1]['t']:g} sim s", file=sys.stderr)
            if args.no_wait:
                return EXIT_OK
            return _wait_for_arms(client, float(reply["ends_at"]), float(now.get("t", 0.0)))
    except WorldError as e:
        print(f"stuart-bt: world at {args.world}: {e.code}: {e.reason}", file=sys.stderr)
        return EXIT_FAILED
    except OSError as e:
        print(f"stuart-bt: cannot reach the world at {args.world}: {e.strerror or e}", file=sys.stderr)
        return EXIT_FAILED


def _wait_for_arms(client: Any, ends_at: float, started: float, stall: float = 3.0) -> int:
    """Poll until the world's sim time passes ``ends_at`` with the arms idle; give up (exit 1)
    when sim time stands still for ``stall`` wall seconds (a run's clock driver holds it)."""
    last_t, last_change = started, time.monotonic()
    while True:
        state = client.call("state")
        t = float(state.get("t", 0.0))
        if t >= ends_at and not any(state.get("arm_busy", {}).values()):
            print(f"done at sim t = {t:.2f} s", file=sys.stderr)
            return EXIT_OK
        if t > last_t:
            last_t, last_change = t, time.monotonic()
        elif time.monotonic() - last_change > stall:
            print(f"stuart-bt: the world's time stopped at {t:.2f} s (a run's clock holds it); the gesture "
                  "plays on when it moves again", file=sys.stderr)
            return EXIT_FAILED
        time.sleep(0.02)


# -- wiring ------------------------------------------------------------------------------------------
def add_command(subparsers: Any) -> argparse.ArgumentParser:
    """Add ``gesture list|record|show|play`` to the top-level ``stuart-bt`` subparsers."""
    p = subparsers.add_parser("gesture", help="the gesture library; record, check and preview gesture files")
    gsub = p.add_subparsers(dest="gesture_command", metavar="ACTION", required=True)

    g = gsub.add_parser("list", help="list gesture names, vendor action ids and durations")
    g.set_defaults(func=cmd_gesture_list)

    g = gsub.add_parser(
        "record", help="write a gesture file from keyframes on the command line and/or a sim world's arm pose",
        description="Keyframes are 'TIME joint=rad ...' (TIME in seconds from the start; an angle may end in "
                    "'deg'; the '_joint' suffix may be left out; the word 'neutral' puts the arms and hands back "
                    "to the neutral pose). A joint a keyframe does not name keeps the previous keyframe's value; "
                    "the first keyframe starts from the neutral pose. Everything is checked against the joint "
                    "limits before anything is written.")
    g.add_argument("name", metavar="NAME", help="the gesture's name (stored in the file)")
    g.add_argument("-o", "--output", required=True, metavar="FILE", help="gesture file to write (JSON)")
    g.add_argument("--keyframe", "-k", action="append", metavar="'TIME joint=rad ...'",
                   help="one keyframe (repeat, times increasing)")
    g.add_argument("--from-world", metavar="SOCKET", help="append the arm and hand pose of the sim world at SOCKET")
    g.add_argument("--at", type=float, metavar="TIME",
                   help="time of the --from-world keyframe (default: 1 s after the last keyframe)")
    g.add_argument("--append", action="store_true", help="add to FILE's keyframes if it exists")
    g.set_defaults(func=cmd_gesture_record)

    g = gsub.add_parser("show", help="check a gesture file (or a library gesture by name) and print its keyframes")
    g.add_argument("file", metavar="FILE|NAME")
    g.add_argument("--degrees", action="store_true", help="print angles in degrees")
    g.add_argument("--all", action="store_true", help="print every joint, not only those that move")
    g.set_defaults(func=cmd_gesture_show)

    g = gsub.add_parser("play", help="preview a gesture file or library gesture on a running sim world's arms")
    g.add_argument("file", metavar="FILE|NAME")
    g.add_argument("--world", required=True, metavar="SOCKET", help="the world server's socket")
    g.add_argument("--no-wait", action="store_true", help="return once the world accepted the trajectory")
    g.set_defaults(func=cmd_gesture_play)
    return p
