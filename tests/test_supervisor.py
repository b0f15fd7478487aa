"""The supervisor: every family's dry daemon up, crashes and hangs noticed, restarts, clean shutdown."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from stuart_bt.core.catalogue import FAMILIES
from stuart_bt.core.clock import ScaledClock
from stuart_bt.core.events import EventRecorder, EventStream
from stuart_bt.daemon.supervisor import DaemonStartError, Supervisor

FAKES = Path(__file__).parent / "fakes"
CLOCK = ScaledClock(20)
LONG_WALK = {"pose": {"x": 40.0, "y": 0.0, "yaw": None}}  # 80 s of clock time, 4 s wall


def children_of(pid: int) -> dict[int, str]:
    """Child pid -> process state letter (``Z`` = zombie), from /proc."""
    found = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            state, ppid = stat.rpartition(")")[2].split()[:2]
            if int(ppid) == pid:
                found[int(entry.name)] = state
    return found


def our_new_children(before: dict[int, str]) -> dict[int, str]:
    """Children of this test process that were not there before (other tests may own some)."""
    return {pid: state for pid, state in children_of(os.getpid()).items() if pid not in before}


def poll_at_20hz(sup: Supervisor, until, timeout: float = 3.0) -> float:
    """Poll like an executor ticking at 20 Hz until ``until()``; returns when it became true."""
    deadline = time.monotonic() + timeout
    while not until():
        assert time.monotonic() < deadline, "condition not reached in time"
        time.sleep(0.05)
        sup.poll()
    return time.monotonic()


def wait_until_dead(pid: int, timeout: float = 5.0) -> None:
    """Until the kernel has finished the process: every thread of it a zombie or gone. The
    leader of a threaded daemon shows ``Z`` while its other threads are still exiting; its pipes
    close, and the supervisor can reap it, only once the last of them has."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if all(state in ("Z", "X") for state in _thread_states(pid)):
            return
        time.sleep(0.005)


def _thread_states(pid: int) -> list[str]:
    """The state letter of every thread of ``pid`` (none when it is gone)."""
    states = []
    for task in Path(f"/proc/{pid}/task").glob("*"):
        try:
            states.append((task / "stat").read_text().rsplit(")", 1)[1].split()[0])
        except (FileNotFoundError, ProcessLookupError):
            continue
    return states
    raise AssertionError(f"process {pid} still alive after SIGKILL")


@pytest.fixture
def stream():
    return EventStream(CLOCK)


@pytest.fixture
def recorder(stream):
    return EventRecorder(stream)


@pytest.fixture
def make(stream, tmp_path):
    made: list[Supervisor] = []

    def make(**kwargs) -> Supervisor:
        kwargs.setdefault("run_dir", tmp_path)
        made.append(Supervisor(kwargs.pop("backend", "dry"), CLOCK, stream, **kwargs))
        return made[-1]

    yield make
    for sup in made:
        for family in sup.families:  # a test may leave a daemon SIGSTOPped
            if sup.pid(family):
                with contextlib.suppress(ProcessLookupError):
                    os.kill(sup.pid(family), signal.SIGCONT)
        sup.shutdown()


def states(recorder: EventRecorder, family: str) -> list[str]:
    return [e.data["state"] for e in recorder.of_kind("daemon_state") if e.data["family"] == family]


def test_start_brings_up_a_dry_daemon_per_family(make, recorder):
    before = children_of(os.getpid())
    sup = make()
    sup.start()
    assert {f: sup.phase(f) for f in sup.families} == {f: "ready" for f in FAMILIES}
    assert sorted(our_new_children(before)) == sorted(sup.pid(f) for f in sup.families)
    for family in sup.families:
        assert states(recorder, family) == ["starting", "ready"]
        assert sup.client(family).ready["pid"] == sup.pid(family)


def test_commands_and_replies_are_events_heartbeats_only_update_state(make, recorder):
    sup = make(families=("loco",))
    sup.start()
    loco = sup.client("loco")
    ping = sup.wait(loco.request("ping", {}, path="tour/check"))
    assert ping.ok
    command, reply = [e for e in recorder.events if e.kind in ("command", "daemon")]
    assert (command.path, command.data) == ("tour/check", {"family": "loco", "id": ping.id, "cmd": "ping", "args": {}})
    assert (reply.path, reply.data["type"], reply.data["id"]) == ("tour/check", "done", ping.id)
    poll_at_20hz(sup, lambda: loco.last_heartbeat is not None and loco.state)
    assert loco.state == {"pose": {"x": 0.0, "y": 0.0, "yaw": 0.0}, "moving": False}
    assert not [e for e in recorder.events if e.data.get("type") == "heartbeat"]


def test_kill_9_mid_walk_fails_the_walk_fast_and_the_daemon_comes_back(make, recorder):
    sup = make()
    sup.start()
    loco = sup.client("loco")
    walk = loco.request("navigate", LONG_WALK)
    poll_at_20hz(sup, lambda: walk.status == "accepted")
    old_pid = sup.pid("loco")
    os.kill(old_pid, signal.SIGKILL)
    wait_until_dead(old_pid)
    sup.poll()  # the very next poll (the next tick) sees the death and fails the walk
    assert walk.finished
    assert (walk.error_code, walk.reason) == ("daemon_died", "loco daemon exited with signal SIGKILL")
    refused = loco.request("ping")  # while it is down: refused at once, not left hanging
    assert (refused.error_code, refused.reason) == ("daemon_down", "loco daemon exited with signal SIGKILL")
    poll_at_20hz(sup, lambda: sup.phase("loco") == "ready")
    assert sup.pid("loco") != old_pid
    assert states(recorder, "loco") == ["starting", "ready", "died", "starting", "ready"]
    turn = sup.wait(loco.request("turn", {"angle": 0.5}))
    assert turn.ok and turn.result["pose"]["yaw"] == 0.5


def test_a_framework_that_goes_silent_mid_walk_leaves_a_stopped_robot(make, recorder):
    """The watchdog: while the supervisor polls (as the executor does every tick) keep-alives flow
    and the walk goes on past the watchdog time; once nothing is polled (a frozen tree process),
    the daemon stops the walk by itself and says why."""
    sup = make(families=("loco",), watchdog=0.4)
    sup.start()
    loco = sup.client("loco")
    walk = loco.request("navigate", LONG_WALK)
    started = time.monotonic()
    while time.monotonic() - started < 1.0:  # 2.5 watchdog periods, polled at 20 Hz
        time.sleep(0.05)
        sup.poll()
    assert not walk.finished, walk.reason
    time.sleep(1.0)  # silence: no poll, so no keep-alive
    poll_at_20hz(sup, lambda: walk.finished)
    assert walk.error_code == "watchdog" and "heard nothing from its framework" in walk.reason, walk.reason
    stopped_at = loco.state["pose"]["x"]
    time.sleep(0.3)  # three heartbeats later
    sup.poll()
    assert loco.state["pose"]["x"] == stopped_at, "the robot kept walking"
    assert sup.phase("loco") == "ready"  # the daemon itself is fine: it only stopped the robot
    again = sup.wait(loco.request("turn", {"angle": 0.2}))
    assert again.ok


def test_a_stopped_daemon_is_declared_hung_killed_and_restarted(make, recorder):
    sup = make(families=("loco", "tts"), heartbeat_timeout=0.5)
    sup.start()
    walk = sup.client("loco").request("navigate", LONG_WALK)
    sup.wait(sup.client("tts").request("ping"))
    old_pid = sup.pid("loco")
    os.kill(old_pid, signal.SIGSTOP)
    stopped_at = time.monotonic()
    poll_at_20hz(sup, lambda: walk.finished)
    assert (walk.error_code, walk.reason) == ("daemon_hung", "loco daemon sent no heartbeat for 0.5 s")
    assert 0.4 < walk.finished_at - stopped_at < 1.0
    assert sup.phase("tts") == "ready"  # the others carry on
    poll_at_20hz(sup, lambda: sup.phase("loco") == "ready")
    assert old_pid not in children_of(os.getpid())  # killed and reaped
    assert states(recorder, "loco")[-3:] == ["hung", "starting", "ready"]


def test_a_daemon_silent_while_the_world_stands_still_is_waited_for_and_hung_only_after(make, recorder):
    world_still = threading.Event()
    world_still.set()
    sup = make(families=("loco",), heartbeat_timeout=0.5, stalled=world_still.is_set)
    sup.start()
    walk = sup.client("loco").request("navigate", LONG_WALK)
    pid = sup.pid("loco")
    os.kill(pid, signal.SIGSTOP)  # as a sim daemon blocked on a frozen world's socket
    try:
        held_until = time.monotonic() + 1.5  # three heartbeat timeouts
        while time.monotonic() < held_until:
            time.sleep(0.05)
            sup.poll()
        assert not walk.finished and sup.phase("loco") == "ready" and sup.pid("loco") == pid
        world_still.clear()  # the world moves again; the daemon does not
        moved_at = time.monotonic()
        poll_at_20hz(sup, lambda: walk.finished)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGCONT)
    assert walk.error_code == "daemon_hung" and walk.finished_at - moved_at >= 0.45  # a whole timeout after
    assert states(recorder, "loco")[-1] in ("hung", "starting", "ready")


def test_restarts_back_off_exponentially(make, recorder):
    sup = make(families=("gesture",), restart_backoff=(0.1, 5.0))
    sup.start()
    for _ in range(2):
        os.kill(sup.pid("gesture"), signal.SIGKILL)
        poll_at_20hz(sup, lambda: sup.phase("gesture") == "down")
        poll_at_20hz(sup, lambda: sup.phase("gesture") == "ready")
    delays = [e.data["restart_in"] for e in recorder.of_kind("daemon_state") if e.data["state"] == "died"]
    assert delays == [0.1, 0.2]


def test_a_daemon_that_never_sends_ready_fails_the_start_with_its_stderr(make):
    before = children_of(os.getpid())
    sup = make(families=("loco", "tts"), handshake_timeout=0.5,
               programs={"loco": [sys.executable, str(FAKES / "never_ready.py")]})
    started = time.monotonic()
    with pytest.raises(DaemonStartError) as caught:
        sup.start()
    assert time.monotonic() - started < 1.5
    assert str(caught.value) == ("loco daemon failed to start: no READY within 0.5 s "
                                 "(stderr: never_ready: connecting to a robot that never answers)")
    assert our_new_children(before) == {}  # the healthy tts daemon was shut down too


def test_an_unknown_backend_fails_the_start_naming_the_valid_ones(make):
    sup = make(backend="unitre", families=("pick",))
    with pytest.raises(DaemonStartError, match=r"^pick daemon failed to start: exited with code 2 before READY "
                                               r"\(stderr: .*unknown backend 'unitre' \(did you mean 'unitree'\?\); "
                                               r"valid backends: (\w+, )*dry(, \w+)*\)$"):
        sup.start()


def test_stop_all_stops_a_running_walk_where_it_is(make):
    sup = make()
    sup.start()
    loco = sup.client("loco")
    walk = loco.request("navigate", {"pose": {"x": 10.0, "y": 0.0, "yaw": None}})
    poll_at_20hz(sup, lambda: walk.progress is not None)
    stops = sup.stop_all()
    assert sorted(s.family for s in stops) == sorted(FAMILIES)
    for stop in stops:
        assert sup.wait(stop, timeout=2.0).ok
    assert walk.error_code == "stopped"
    frozen = walk.result["pose"]
    assert 0.0 < frozen["x"] < 10.0
    stopped_at = time.monotonic()
    poll_at_20hz(sup, lambda: loco.last_heartbeat > stopped_at)
    assert loco.state == {"pose": frozen, "moving": False}


def test_shutdown_reaps_every_daemon_even_a_stopped_one(make, recorder):
    before = children_of(os.getpid())
    sup = make(heartbeat_timeout=5.0)
    sup.start()
    walk = sup.client("loco").request("navigate", LONG_WALK)
    speech = sup.client("tts").request("say", {"text": "this sentence will not be finished " * 5})
    sup.wait(sup.client("pick").request("ping"))
    os.kill(sup.pid("gesture"), signal.SIGSTOP)
    started = time.monotonic()
    sup.shutdown(timeout=0.3)
    assert time.monotonic() - started < 2.0
    assert our_new_children(before) == {}  # nothing left, not even zombies
    assert walk.error_code == speech.error_code == "stopped"
    assert all(states(recorder, f)[-1] == "stopped" for f in sup.families)
    sup.shutdown()  # idempotent


def test_garbage_from_a_daemon_is_a_warning_and_is_otherwise_ignored(make, recorder):
    sup = make(families=("loco",), programs={"loco": [sys.executable, str(FAKES / "garbage_daemon.py")]})
    sup.start()
    loco = sup.client("loco")
    poll_at_20hz(sup, lambda: loco.state.get("seq", 0) >= 3)
    warnings = [e.data["message"] for e in recorder.of_kind("warning")]
    assert len(warnings) == 4
    assert "not protocol" in warnings[0] and "Vendor SDK" in warnings[0]
    assert "expected a JSON object, got list" in warnings[1]
    assert "unknown type 'mystery'" in warnings[2]
    assert "not protocol" in warnings[3]
    assert sup.phase("loco") == "ready"


def test_wait_gives_the_request_back_unfinished_after_its_timeout(make):
    sup = make(families=("loco",))
    sup.start()
    walk = sup.wait(sup.client("loco").request("navigate", LONG_WALK), timeout=0.1)
    assert not walk.finished and walk.status == "accepted"


def test_a_daemon_killed_while_waited_on_fails_the_request_at_once(make):
    sup = make(families=("loco",))
    sup.start()
    walk = sup.client("loco").request("navigate", LONG_WALK)
    killer = threading.Timer(0.2, os.kill, (sup.pid("loco"), signal.SIGKILL))
    killer.start()
    try:
        sup.wait(walk, timeout=30.0)
    finally:
        killer.cancel()
    assert (walk.error_code, walk.reason) == ("daemon_died", "loco daemon exited with signal SIGKILL")


def test_a_daemon_that_hangs_while_waited_on_fails_the_request_hung(make):
    """The health checks that only time can trigger still run while wait() blocks."""
    sup = make(families=("loco",), heartbeat_timeout=0.5)
    sup.start()
    walk = sup.client("loco").request("navigate", LONG_WALK)
    sup.wait(walk, timeout=0.1)  # accepted and walking
    os.kill(sup.pid("loco"), signal.SIGSTOP)
    sup.wait(walk, timeout=30.0)
    assert (walk.error_code, walk.reason) == ("daemon_hung", "loco daemon sent no heartbeat for 0.5 s")


def test_waiting_on_many_replies_checks_health_per_period_not_per_reply(make, monkeypatch):
    """A round trip through wait() used to run every daemon's health checks on each wake-up,
    twice per reply; they are about time (hangs, restarts), so once per check period is enough."""
    sup = make(families=("tts", "loco"))
    sup.start()
    tts = sup.client("tts")
    checks = []
    monkeypatch.setattr(sup, "_check", lambda d, now: checks.append(now))
    started = time.monotonic()
    for _ in range(200):
        assert sup.wait(tts.request("ping"), timeout=5.0).ok
    periods = (time.monotonic() - started) / sup.check_period
    assert len(checks) <= len(sup.families) * (periods + 2), (len(checks), periods)


def test_heartbeats_keep_coming_while_requests_follow_each_other(make):
    """The daemon queues its heartbeat before writing a turn's replies; a steady stream of
    requests must not crowd heartbeats out (the supervisor would call the daemon hung)."""
    sup = make(families=("tts",), heartbeat_timeout=0.3)
    sup.start()
    tts = sup.client("tts")
    first = tts.last_heartbeat
    pings = 0
    until = time.monotonic() + 1.0  # three heartbeat timeouts of back-to-back pings
    while time.monotonic() < until:
        assert sup.wait(tts.request("ping"), timeout=5.0).ok
        pings += 1
    assert sup.phase("tts") == "ready" and tts.last_heartbeat > first, pings


def test_asking_for_a_family_that_is_not_there_suggests_one(make):
    sup = make(families=("loco",))
    with pytest.raises(KeyError, match="no 'lcoo' daemon \\(did you mean 'loco'\\?\\)"):
        sup.client("lcoo")


def test_a_killed_tree_process_leaves_no_daemon_running(tmp_path):
    tree = subprocess.Popen([sys.executable, "-c", (
        "import sys, time\n"
        "from stuart_bt.core.clock import ScaledClock\n"
        "from stuart_bt.core.events import EventStream\n"
        "from stuart_bt.daemon.supervisor import Supervisor\n"
        "sup = Supervisor('dry', ScaledClock(20), EventStream(ScaledClock(20)), families=('loco',),\n"
        f"                 run_dir={str(tmp_path)!r})\n"
        "sup.start()\n"
        "sup.client('loco').request('navigate', {'pose': {'x': 40.0, 'y': 0.0}})\n"
        "print(sup.pid('loco'), flush=True)\n"
        "time.sleep(60)\n")], stdout=subprocess.PIPE, text=True)
    daemon_pid = int(tree.stdout.readline())
    tree.kill()
    tree.wait()
    deadline = time.monotonic() + 1.0
    while Path(f"/proc/{daemon_pid}").exists() and Path(f"/proc/{daemon_pid}/stat").read_text().split()[2] != "Z":
        assert time.monotonic() < deadline, "the daemon outlived its tree process"
        time.sleep(0.02)
    log = (tmp_path / "loco.stderr.log").read_text()
    assert "Traceback" not in log


def test_bad_line_warnings_are_a_few_in_full_then_one_summary_a_second():
    from stuart_bt.daemon.limits import FAULTY_LINES, FULL_WARNINGS, BadLineLimiter

    published: list[tuple[str, dict]] = []
    limiter = BadLineLimiter("loco", lambda message, fields: published.append((message, fields)))
    for i in range(FULL_WARNINGS + 20):  # 25 bad lines in 2.5 s: chatty, not faulty
        limiter.report(f"bad line {i}", 100.0 + i * 0.1)
    assert [m for m, _ in published[:FULL_WARNINGS]] == [f"bad line {i}" for i in range(FULL_WARNINGS)]
    summaries = published[FULL_WARNINGS:]
    assert 2 <= len(summaries) <= 3  # one a second, each with its count
    assert all(f["suppressed"] >= 1 for _, f in summaries) and "last: bad line" in summaries[0][0]
    limiter.tick(110.0)  # whatever was still held comes out with the next summary
    assert sum(f["suppressed"] for _, f in published[FULL_WARNINGS:]) == 20  # every line accounted for
    assert published[-1][1]["total"] == FULL_WARNINGS + 20
    assert limiter.faulty is None
    for i in range(FAULTY_LINES):  # a flood: faulty, with the reason
        limiter.report("flood", 200.0 + i * 0.001)
    assert limiter.faulty == f"loco daemon sent {FAULTY_LINES} lines that are not protocol within 2 s (limit 200)"
