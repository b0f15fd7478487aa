"""hearing: how fast and how well the robot hears, on spoken audio generated in the run.

The corpus is made here, not kept: command sentences built from the lab's own words (every
marker by name and display name, every object, turns, walks, gestures, stops, two-step
commands) and non-commands (chit-chat with and without the wake phrase, questions, statements
about places and objects), each spoken by espeak-ng in one of six voices at 140-185 words a
minute. The truth of an utterance is what the grammar makes of its *text*, resolved against the
map and the object labels as the robot would resolve it, so the figures measure hearing alone.
The recogniser is the default engine (``whisper+grammar``); without the vocabulary it is whisper
alone, so "without the vocabulary prompt" below also means without the grammar engine.

Figures, each beside an anchor timed in the same run:

- ``latency.p50`` / ``p99``: end of an utterance's audio -> intents (recognition + parse);
  anchor: the same recogniser **without** the vocabulary prompt on the same clips, each clip
  heard both ways back to back (order alternating), so the ratio is what the prompt costs and a
  machine with a slower CPU moves both. Goals on that ratio (they replaced p50 <= 0.8 s and p99
  <= 1.5 s of issue 14, which stay as information, as does the audio duration in the note);
- ``rtf``: recognition seconds per second of audio (median), anchor 1.0 (real time);
- ``accuracy.clean`` / ``accuracy.snr10``: exact intents from audio, clean and with white noise,
  as the robot would act on them (a reading in doubt, heard with low confidence or with a rival
  reading, is asked about, so its tasks count as nothing done; a stop stops all the same, as in
  the mission executor)
  at 10 dB SNR (goals 95 %, 90 %); anchor: the same recogniser **without** the vocabulary prompt,
  which is what the prompt buys;
- ``false_commands``: intents heard in non-command audio (goal 0), anchor the same without prompt;
- ``false_commands.said_to_others``: intents heard in commands said to someone else, several
  with names that start like the robot's ("Hey Steve, go to the kitchen"; goal 0);
- ``barge_in.p99``: a "Hey Stuart, stop" said over the robot's voice -> the tts stop command,
  from the end of the stop's audio; anchor: the silence the segmenter waits for while the robot
  talks (``barge_in_silence_s``, a constant), the wait no recogniser can avoid; goal: ratio
  <= 2.8 (was <= 1.0 s: a deadline, so its anchor is the constant it is made of);
- ``memory``: resident memory of the hearing process with the model loaded and used, anchor the
  same process before the model was loaded.
"""

from __future__ import annotations

import random
import resource
import statistics
import tempfile
import time
from pathlib import Path
from typing import Any

from .result import Anchor, Bound, Goal, Result
from .stats import percentile

NAME = "hearing"
GOAL_P50_S, GOAL_P99_S = 0.8, 1.5  # the absolute goals the ratio goals replace (information)
# Latency with the vocabulary prompt over latency without, same clips, same run: each absolute goal
# over the latency without the prompt on the machine that wrote bench/results.json, which that
# run did not time: its 0.41 / 0.52 s with the prompt over the ratios measured on the same machine
# kind for issue 16 (1.09 / 1.14), i.e. 0.38 / 0.45 s; rounded down.
GOAL_P50 = Goal(2.1, was=f"<= {GOAL_P50_S:g} s")
GOAL_P99 = Goal(3.3, was=f"<= {GOAL_P99_S:g} s")
GOAL_CLEAN, GOAL_NOISY = 95.0, 90.0
GOAL_BARGE_P99_S = 1.0
GOAL_BARGE = Goal(2.8, was=f"<= {GOAL_BARGE_P99_S:g} s")  # 1.0 s over the 0.35 s of silence, rounded down
SPEEDS = (140, 150, 160, 170, 175, 185)


def corpus(markers: dict[str, str], objects: tuple[str, ...], seed: int = 3) -> list[str]:
    """Commands and non-commands, in a fixed shuffled order (gestures as people ask for them:
    "wave", "give me a high five")."""
    rng = random.Random(seed)
    places = [n.replace("_", " ") for n in markers] + [d for d in markers.values() if d]
    say = ["wave", "clap", "give me a high five", "shake hands", "give me a hug"]
    commands = [f"Hey Stuart, go to the {p}" for p in places]
    commands += [f"Hey Stuart, {v} the {o}" for o in objects for v in ("pick up", "find")]
    commands += [f"Hey Stuart, turn {d} {a} degrees" for d in ("left", "right") for a in (45, 90, 180)]
    commands += [f"Hey Stuart, turn {d}" for d in ("left", "right", "around")]
    commands += [f"Hey Stuart, walk forward {n} metres" for n in ("one", "two", "three")]
    commands += [f"Hey Stuart, move back {n}" for n in ("one metre", "half a metre")]
    commands += [f"Hey Stuart, {g}" for g in say] + ["Hey Stuart, stop", "Stuart, stop", "Hey Stuart, stop now"]
    commands += [f"Hey Stuart, go to the {rng.choice(places)} and {rng.choice(say)}" for _ in range(20)]
    commands += [f"Hey Stuart, go to the {rng.choice(places)} and pick up the {rng.choice(objects)}"
                 for _ in range(20)]
    commands += [f"Hey Stuart, could you go to the {p} please" for p in places]
    commands += [f"Hey Stuart, look for the {o} in the {rng.choice(places)}" for o in objects]
    commands += [f"Hey Stuart, turn {d} {a} degrees" for d in ("left", "right") for a in (30, 60, 120)]
    commands += [f"Hey Stuart, go to the {rng.choice(places)} and then turn around" for _ in range(10)]
    talk = ["what a lovely day it is", "I think the kitchen is closed today", "Hey Stuart, how are you",
            "Hey Stuart, what can you do", "did you see my keys anywhere", "the bathroom is down the hall",
            "Hey Stuart, thank you very much", "the meeting starts at three", "I left the cup on the table",
            "Hey Stuart, tell me about the lab", "we went to the workbench yesterday", "nice to meet you",
            "Hey Stuart, where are you", "can someone open the window", "the drone cage is locked"]
    talk += [f"I put the {o} in the {rng.choice(places)}" for o in objects]
    talk += [f"is the {p} open today" for p in places[:8]]
    talk += [f"the {p} looks much tidier than last week" for p in places]
    talk += [f"Hey Stuart, do you like the {o}" for o in objects]
    talk += ["I need to go home early today", "could you believe the weather this morning",
             "Hey Stuart, good morning", "we should order more parts for the lab", "the robot looks happy",
             "my phone is almost out of battery", "let's have lunch at noon", "Hey Stuart, you are doing great",
             "the printer is making a strange noise", "has anyone seen the manual for the arm"]
    utterances = commands + talk
    rng.shuffle(utterances)
    return utterances


# people in a lab, several with names that start like the robot's ("Steve", "Stella"): what is said
# to them must not move the robot, however close the name sounds
OTHER_NAMES = ("Steve", "Stella", "Stan", "Stacy", "Sarah", "Stephen", "Susan", "Sue", "Tom", "Sam", "team", "guys")


def said_to_others(markers: dict[str, str], objects: tuple[str, ...], seed: int = 5) -> list[str]:
    """Commands said to someone else, greeted ("Hey Steve, go to the kitchen") or named alone
    ("Stella, pick up the cup"): talk, as far as the robot is concerned."""
    rng = random.Random(seed)
    places = [n.replace("_", " ") for n in markers] + [d for d in markers.values() if d]
    asks = [f"go to the {p}" for p in places] + [f"pick up the {o}" for o in objects] + ["turn left", "stop"]
    return [f"{'Hey ' if k % 2 == 0 else ''}{name}, {rng.choice(asks)}" for k, name in enumerate(OTHER_NAMES * 2)]


def _speak_all(texts: list[str], folder: Path) -> list[Any]:
    from stuart_bt.hearing.audio import read_audio
    from stuart_bt.testing import VOICES, speak

    return [read_audio(speak(t, folder / f"{n}.wav", VOICES[n % len(VOICES)], SPEEDS[n % len(SPEEDS)]))
            for n, t in enumerate(texts)]


def _meaning(parser: Any, text: str, resolver: Any = None) -> list[tuple[str, str, float, float, float]]:
    """What the robot would do: each intent's action, its target as resolved against the map and
    the object labels (so "electronic bench" and "Electronics bench" both mean station_4), amounts."""
    intents = parser.parse(text).intents
    resolved = resolver.resolve_all(intents) if resolver is not None else [None] * len(intents)
    return [(i.action, r.name if r is not None and r.ok else i.target, round(i.x, 2), round(i.y, 2), round(i.yaw, 2))
            for i, r in zip(intents, resolved, strict=True)]


Heard = tuple[list[list], list[float], list[float]]  # intents, latency s and real-time factor per clip


def _hear_both(recogniser: Any, clips: list[Any], vocabulary: Any, parser: Any, resolver: Any) -> tuple[Heard, Heard]:
    """Every clip heard with the vocabulary prompt and without, back to back, the order
    alternating from clip to clip: the two latencies of a clip sit side by side in time."""
    heard: dict[bool, Heard] = {True: ([], [], []), False: ([], [], [])}
    for k, clip in enumerate(clips):
        for prompted in ((True, False) if k % 2 == 0 else (False, True)):
            meant, latency, rtf = _hear(recogniser, clip, vocabulary if prompted else None, parser, resolver)
            heard[prompted][0].append(meant)
            heard[prompted][1].append(latency)
            heard[prompted][2].append(rtf)
    return heard[True], heard[False]


def _hear(recogniser: Any, clip: Any, vocabulary: Any, parser: Any, resolver: Any) -> tuple[list, float, float]:
    """(intents, latency s, real-time factor) of one clip."""
    from stuart_bt.hearing.pipeline import is_speech, transcribe
    from stuart_bt.language.readings import choose_reading, rival_reading

    heard = transcribe(recogniser, clip, vocabulary)
    t = heard.transcript
    readings = t.readings() if is_speech(t) else []
    chosen = choose_reading(readings, parser, resolver) if readings else 0
    text = readings[chosen][0] if readings else ""
    rival = rival_reading(readings, chosen, parser, resolver) if readings else None
    return _done(parser, resolver, text, t.confidence, rival is not None), heard.latency_s, \
        t.seconds / max(t.audio_s, 1e-6)


def _done(parser: Any, resolver: Any, text: str, confidence: float, rival: bool) -> list:
    """What the robot does on hearing ``text``, decided as the mission executor decides it
    (``interpret`` and ``hearing_doubts``): in doubt (the words, a low confidence, a rival reading)
    it asks, so its tasks count as nothing done, but a stop it heard stops it all the same."""
    from stuart_bt.mission.commands import STOP, hearing_doubts, interpret

    command = interpret(parser, text)
    doubt = bool(command.parse.doubt) or bool(hearing_doubts(command, {"confidence": confidence,
                                                                       "rival_reading": rival}))
    meant = _meaning(parser, text, resolver)
    if not doubt:
        return meant
    return meant[:1] if command.kind == STOP else []


def _score(truth: list[list], got: list[list], is_command: list[bool]) -> tuple[float, int]:
    """(% of commands heard exactly, intents heard in non-commands)."""
    commands = [k for k, c in enumerate(is_command) if c]
    right = sum(truth[k] == got[k] for k in commands)
    false = sum(len(got[k]) for k, c in enumerate(is_command) if not c)
    return 100.0 * right / max(1, len(commands)), false


def _rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def run(quick: bool = False) -> list[Result]:
    from stuart_bt.hearing.audio import add_noise
    from stuart_bt.hearing.recognisers import make_recogniser
    from stuart_bt.hearing.vad import SegmenterOptions
    from stuart_bt.language.parse import Parser
    from stuart_bt.language.resolve import Resolver
    from stuart_bt.testing import lab_markers

    resolver = Resolver.from_files(lab_markers())
    vocabulary = resolver.vocabulary()
    parser = Parser()
    texts = corpus(resolver.markers, resolver.objects)
    if quick:
        texts = texts[:6]
    truth = [_meaning(parser, t, resolver) for t in texts]
    is_command = [bool(m) for m in truth]
    rss_before = _rss_mb()
    recogniser = make_recogniser()  # the default engine: what `hear` and `listen` use
    with tempfile.TemporaryDirectory(prefix="stuart-bench-hearing-") as tmp:
        clips = _speak_all(texts, Path(tmp))
    noisy = [add_noise(c, 10.0, seed=k) for k, c in enumerate(clips)]
    (got, latency, rtf), (bare, bare_latency, _) = _hear_both(recogniser, clips, vocabulary, parser, resolver)
    (got_noisy, _, _), (bare_noisy, _, _) = _hear_both(recogniser, noisy, vocabulary, parser, resolver)
    others = _to_others(recogniser, vocabulary, parser, resolver, quick)
    rss_after = _rss_mb()
    acc, false = _score(truth, got, is_command)
    acc_noisy, false_noisy = _score(truth, got_noisy, is_command)
    acc_bare, false_bare = _score(truth, bare, is_command)
    acc_bare_noisy, _ = _score(truth, bare_noisy, is_command)
    audio = [len(c) / 16_000 for c in clips]
    n_cmd, n_talk = sum(is_command), len(texts) - sum(is_command)
    where = f"{len(texts)} utterances ({n_cmd} commands, {n_talk} non-commands), espeak-ng, 6 voices"
    barge = barge_in(recogniser, vocabulary, trials=1 if quick else 10)
    l50, l99 = percentile(latency, 50), percentile(latency, 99)
    bare_name = "same recogniser, same clips, no vocabulary prompt, heard back to back"
    return [
        Result(f"{NAME}.latency.p50", l50, "s", Anchor(bare_name, percentile(bare_latency, 50)), GOAL_P50,
               note=f"end of audio -> intents, clean, {where}; audio duration p50 {percentile(audio, 50):.2f} s"),
        Result(f"{NAME}.latency.p99", l99, "s", Anchor(bare_name, percentile(bare_latency, 99)), GOAL_P99,
               note=f"end of audio -> intents, clean; audio duration p99 {percentile(audio, 99):.2f} s"),
        Result(f"{NAME}.rtf", statistics.median(rtf), "s/s", Anchor("real time", 1.0, timed=False),
               note="recognition seconds per second of audio (median), beam 5, int8, 2 threads"),
        Result(f"{NAME}.accuracy.clean", acc, "% exact", Anchor("same recogniser, no vocabulary prompt", acc_bare),
               Bound(GOAL_CLEAN, ">=", "%"),
               note=f"commands whose intents (actions, resolved targets, amounts) were heard exactly; {where}"),
        Result(f"{NAME}.accuracy.snr10", acc_noisy, "% exact",
               Anchor("same recogniser, no vocabulary prompt", acc_bare_noisy), Bound(GOAL_NOISY, ">=", "%"),
               note="white noise at 10 dB SNR"),
        Result(f"{NAME}.false_commands", float(false + false_noisy), "intents", None, Bound(0, "=="),
               note=f"intents heard in the {n_talk} non-commands, clean + 10 dB SNR; no anchor ratio (a count that "
                    f"should be 0): the same recogniser without the vocabulary prompt heard {false_bare} (clean)"),
        Result(f"{NAME}.false_commands.said_to_others", float(others[0]), "intents", None, Bound(0, "=="),
               note=f"intents heard in {others[2]} commands said to someone else ('Hey Steve, go to the kitchen', "
                    f"'Stella, pick up the cup'), clean + 10 dB SNR; without the vocabulary prompt: {others[1]}"),
        Result(f"{NAME}.barge_in.p99", percentile(barge, 99), "s",
               Anchor("silence the segmenter waits for while the robot talks", SegmenterOptions().barge_in_silence_s,
                      timed=False), GOAL_BARGE,
               note=f"end of a spoken 'Hey Stuart, stop' over the robot's voice -> tts stop command, "
                    f"{len(barge)} trials, dry daemons"),
        Result(f"{NAME}.memory", rss_after, "MB", Anchor("the same process before the model was loaded", rss_before),
               note="peak resident memory with tiny.en (and pocketsphinx for the grammar engine) loaded and used"),
    ]


def _to_others(recogniser: Any, vocabulary: Any, parser: Any, resolver: Any, quick: bool) -> tuple[int, int, int]:
    """(intents heard, the same without the vocabulary prompt, clips) for :func:`said_to_others`,
    each clean and at 10 dB SNR."""
    from stuart_bt.hearing.audio import add_noise

    texts = said_to_others(resolver.markers, resolver.objects)[:2 if quick else None]
    with tempfile.TemporaryDirectory(prefix="stuart-bench-hearing-") as tmp:
        clips = _speak_all(texts, Path(tmp))
    clips += [add_noise(c, 10.0, seed=100 + k) for k, c in enumerate(clips)]
    (got, _, _), (bare, _, _) = _hear_both(recogniser, clips, vocabulary, parser, resolver)
    return sum(len(g) for g in got), sum(len(b) for b in bare), len(clips)


def barge_in(recogniser: Any, vocabulary: Any, trials: int) -> list[float]:
    """Seconds from the end of a spoken stop (said while the robot talks) to the tts stop command."""
    import os
    import threading

    import numpy as np

    from stuart_bt.hearing.audio import RATE, read_audio
    from stuart_bt.hearing.sources import PcmSource
    from stuart_bt.mission.executor import MissionExecutor, MissionOptions
    from stuart_bt.mission.listening import Listener
    from stuart_bt.testing import VOICES, speak

    out: list[float] = []
    with tempfile.TemporaryDirectory(prefix="stuart-bench-barge-") as tmp:
        stops = [read_audio(speak("Hey Stuart, stop", Path(tmp) / f"{k}.wav", VOICES[k % len(VOICES)], 160))
                 for k in range(trials)]
    robot = MissionExecutor(MissionOptions(backend="dry", speed=0.5))
    read, write = os.pipe()
    listener = Listener(robot, PcmSource(os.fdopen(read, "rb")), recogniser, vocabulary)
    stopped = threading.Event()
    stopped_at: list[float] = []

    def on_event(e: Any) -> None:
        if e.kind == "command" and e.data.get("family") == "tts" and e.data.get("cmd") == "stop":
            stopped_at.append(time.perf_counter())
            stopped.set()

    robot.events.subscribe(on_event)
    robot.start()
    listener.start()
    try:
        for clip in stops:
            stopped.clear()
            robot.submit("Hey Stuart, what can you do?")  # the robot answers aloud (slowly: speed 0.5)
            while not listener.voice.speaking:
                time.sleep(0.01)
            ended = _play(write, np.concatenate([clip, np.zeros(int(RATE * 1.5), np.int16)]), len(clip))
            # the time of the stop command itself (it usually came while the silence after it played);
            # a stop that never came counts as infinitely late
            out.append(stopped_at[-1] - ended if stopped.wait(10.0) else float("inf"))
            robot.wait_idle(30.0)
    finally:
        os.close(write)
        listener.close()
        robot.close()
    return out or [float("inf")]


def _play(fd: int, samples: Any, speech_end: int) -> float:
    """Write ``samples`` to ``fd`` at the speed they were said; ``perf_counter()`` when sample
    ``speech_end`` (the end of the speech) was written."""
    import os

    start = time.perf_counter()
    ended = start
    for i in range(0, len(samples), 480):
        time.sleep(max(0.0, start + i / 16_000 - time.perf_counter()))
        os.write(fd, samples[i:i + 480].astype("<i2").tobytes())
        if i <= speech_end < i + 480:
            ended = time.perf_counter()
    return ended
