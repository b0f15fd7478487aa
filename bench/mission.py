"""mission: how fast the robot reacts to what it is told, with its daemons already up.

Two reaction times of one long-running :class:`~stuart_bt.mission.executor.MissionExecutor` on
the dry backend, measured in the same loop, many times:

- **utterance -> first daemon command**: from ``submit("Hey Stuart, go to the kitchen")`` to the
  first ``command`` event sent to a daemon for that mission (the acknowledgement's ``say``).
  Inside: wake filter and grammar, resolving the place, HTN planning from the world state,
  compiling, building the tree, waking the mission worker and its first tick;
- **"stop" -> every daemon stopped**: from ``submit("Hey Stuart, stop")``, said while the robot
  walks (the navigate command is in flight), to the ``command`` event that sends ``stop`` to the
  last daemon. Inside: interpreting the stop, waking the executor from its tick sleep, halting
  the tree (the walking leaf cancels) and ``stop`` to every daemon.

Timestamps are ``perf_counter`` readings taken by an event subscriber, which runs synchronously
on the publishing thread, so they are when the command was written to the daemon's pipe.

Anchor, measured in the same run between repetitions while the robot is idle: the **daemon
ping round trip through the supervisor** (``ping`` to the tts daemon and its reply, as in the
roundtrip benchmark): the cheapest thing any command can cost, so the ratio says how many
round trips' worth of work the reaction takes. The executor's tick period (50 ms at 20 Hz) is in
the note: the stop figure would be bounded by it if the executor did not wake early on a stop.
"""

from __future__ import annotations

import threading
import time
from dataclasses import dataclass, field

from stuart_bt.core.events import Event
from stuart_bt.mission.executor import MissionExecutor, MissionOptions

from .result import Anchor, Goal, Result
from .stats import percentile

NAME = "mission"
GOAL_FIRST_P99_MS = 20.0  # the absolute goals the ratio goals replace (information)
GOAL_STOP_P99_MS = 50.0
# p99 over the ping round trip's p99, timed in the same run: each absolute goal over the ping's
# p99 on the machine that wrote bench/results.json (0.3568 ms), rounded down.
GOALS = {"utterance_to_first_command": Goal(56, was=f"<= {GOAL_FIRST_P99_MS:g} ms"),
         "stop_to_all_daemons": Goal(140, was=f"<= {GOAL_STOP_P99_MS:g} ms")}
SPEED = 20.0  # dry clock seconds per wall second: the ack takes ~1.5 clock s, so ~75 ms wall
RATE = 20.0
PLACES = ("kitchen", "bathroom")  # alternated, so the robot is never already there
PINGS_PER_REP = 4
WALK_BEFORE_STOP = 0.01  # wall seconds of walking before "stop" is said
TIMEOUT = 10.0  # wall seconds; a step that takes this long is a failure, not a sample


@dataclass
class _Probe:
    """Watches ``command`` events for one repetition (an event subscriber)."""

    families: frozenset[str]
    cond: threading.Condition = field(default_factory=threading.Condition)
    armed: bool = False
    first: float | None = None
    walking: float | None = None
    stopped: dict[str, float] = field(default_factory=dict)

    def reset(self) -> None:
        with self.cond:
            self.armed, self.first, self.walking, self.stopped = True, None, None, {}

    def __call__(self, event: Event) -> None:
        if event.kind != "command" or not self.armed:
            return
        now = time.perf_counter()
        family, cmd = event.data.get("family"), event.data.get("cmd")
        with self.cond:
            if self.first is None:
                self.first = now
            if family == "loco" and cmd not in ("stop", "cancel", "ping") and self.walking is None:
                self.walking = now
            if cmd == "stop" and family not in self.stopped:
                self.stopped[family] = now
            self.cond.notify_all()

    def wait(self, predicate, what: str) -> None:
        with self.cond:
            if not self.cond.wait_for(predicate, TIMEOUT):
                raise RuntimeError(f"mission benchmark: no {what} within {TIMEOUT} s")


def _ping(robot: MissionExecutor, count: int) -> list[float]:
    """Round trips of ``ping`` to the tts daemon (only while idle: the worker polls the
    supervisor when a tree runs, and the supervisor is not shared between threads)."""
    supervisor = robot.session.supervisor
    assert supervisor is not None
    client = supervisor.client("tts")
    samples = []
    for _ in range(count):
        start = time.perf_counter()
        request = supervisor.wait(client.request("ping", {}), TIMEOUT)
        samples.append(time.perf_counter() - start)
        if not request.ok:
            raise RuntimeError(f"ping failed: {request!r}")
    return samples


def measure(reps: int, warmup: int = 3) -> tuple[list[float], list[float], list[float]]:
    """Seconds: utterance -> first command, stop -> last daemon stopped, ping round trips."""
    first: list[float] = []
    stop: list[float] = []
    pings: list[float] = []
    options = MissionOptions(backend="dry", speed=SPEED, rate=RATE, max_repairs=0)
    with MissionExecutor(options) as robot:
        supervisor = robot.session.supervisor
        assert supervisor is not None
        probe = _Probe(frozenset(supervisor.families))
        robot.events.subscribe(probe)
        for i in range(warmup + reps):
            place = PLACES[i % len(PLACES)]
            probe.reset()
            start = time.perf_counter()
            robot.submit(f"Hey Stuart, go to the {place}")
            probe.wait(lambda: probe.first is not None, "first command")
            probe.wait(lambda: probe.walking is not None, "navigate command")
            time.sleep(WALK_BEFORE_STOP)
            said = time.perf_counter()
            robot.submit("Hey Stuart, stop")
            probe.wait(lambda: set(probe.stopped) >= probe.families, "stop to every daemon")
            if not robot.wait_idle(TIMEOUT):
                raise RuntimeError("mission benchmark: the robot did not go idle after stop")
            probe.armed = False
            if i >= warmup:
                assert probe.first is not None
                first.append(probe.first - start)
                stop.append(max(probe.stopped.values()) - said)
            pings += _ping(robot, PINGS_PER_REP)
    return first, stop, pings


def run(quick: bool) -> list[Result]:
    reps = 12 if quick else 300
    first, stop, pings = measure(reps, warmup=1 if quick else 5)
    ms = 1000.0
    ping = {q: percentile(pings, q) * ms for q in (50, 99)}
    note = (f"{len(first)} repetitions on one MissionExecutor (dry backend, speed {SPEED:g}, {RATE:g} Hz: "
            f"tick period {1000 / RATE:g} ms of clock, {1000 / RATE / SPEED:g} ms wall), daemons up before "
            f"timing; utterances 'Hey Stuart, go to the kitchen/bathroom' alternating; anchor: {len(pings)} "
            "tts pings through the supervisor between repetitions, same percentile")
    results = []
    for label, samples in (("utterance_to_first_command", first), ("stop_to_all_daemons", stop)):
        for q in (50, 99):
            value = percentile(samples, q) * ms
            anchor = Anchor(f"daemon ping round trip p{q} (supervisor -> dry tts)", ping[q])
            results.append(Result(f"{NAME}.{label}.p{q}", value, "ms", anchor,
                                  goal=GOALS[label] if q == 99 else None, note=note))
    return results
