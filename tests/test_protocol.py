"""The wire protocol, byte for byte: what a daemon prints for what it is sent (docs/protocol.md)."""

from __future__ import annotations

import contextlib
import json
import os
import select
import subprocess
import sys
import time
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from stuart_bt.core.catalogue import FAMILIES
from stuart_bt.core.clock import ScaledClock
from stuart_bt.daemon import protocol as p

FAMILY_COMMANDS = {"loco": ["navigate", "turn"], "tts": ["say"], "gesture": ["play"],
                   "pick": ["pick", "release"], "vision": ["find", "look", "memory"]}


class Wire:
    """One dry daemon on raw pipes: we write lines, we read every line it prints."""

    def __init__(self, family: str, factor: float = 20.0) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, "-m", f"stuart_bt.skills.{family}", "--backend", "dry",
             "--clock", ScaledClock(factor).spec(), "--heartbeat", "0.05"],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self._buffer = b""
        self.seen: list[dict[str, Any]] = []
        self.ready = self.next(lambda m: m.get("type") == "ready")

    def send(self, line: bytes | dict[str, Any]) -> None:
        self.proc.stdin.write(line if isinstance(line, bytes) else p.encode(line))
        self.proc.stdin.flush()

    def next(self, match: Any, timeout: float = 3.0) -> dict[str, Any]:
        """The next message (heartbeats included) that ``match`` accepts; earlier ones land in ``seen``."""
        deadline = time.monotonic() + timeout
        while True:
            while b"\n" in self._buffer:
                raw, self._buffer = self._buffer.split(b"\n", 1)
                message = json.loads(raw)
                self.seen.append(message)
                if match(message):
                    return message
            remaining = deadline - time.monotonic()
            assert remaining > 0, f"no matching line within {timeout} s; saw {self.seen[-5:]}"
            if select.select([self.proc.stdout], [], [], remaining)[0]:
                chunk = os.read(self.proc.stdout.fileno(), 1 << 20)
                assert chunk, f"daemon closed its output; saw {self.seen[-5:]}"
                self._buffer += chunk

    def reply(self, request_id: str | None, *types: str, timeout: float = 3.0) -> dict[str, Any]:
        types = types or ("done", "error")
        return self.next(lambda m: m.get("id") == request_id and m.get("type") in types, timeout)

    def replies_to(self, request_id: str) -> list[str]:
        return [m["type"] for m in self.seen if m.get("id") == request_id]

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait(5)
        self.proc.stdout.close()
        self.proc.stderr.close()


@pytest.fixture
def wire(request: pytest.FixtureRequest):
    daemons: list[Wire] = []

    def start(family: str) -> Wire:
        daemons.append(Wire(family))
        return daemons[-1]

    yield start
    for daemon in daemons:
        daemon.close()


@pytest.mark.parametrize("family", FAMILIES)
def test_ready_line_names_family_backend_pid_protocol_and_commands(wire, family):
    daemon = wire(family)
    assert daemon.ready == {
        "type": "ready", "family": family, "backend": "dry", "pid": daemon.proc.pid, "protocol": 1,
        "commands": ["ping", "stop", "cancel", "state", "shutdown", *FAMILY_COMMANDS[family]],
    }


def test_ping_is_done_at_once_with_the_clock_time(wire):
    daemon = wire("tts")
    daemon.send({"id": "r1", "cmd": "ping"})
    done = daemon.reply("r1")
    assert done["type"] == "done" and isinstance(done["result"]["t"], float)
    assert daemon.replies_to("r1") == ["done"]


def test_a_walk_is_accepted_then_reports_progress_then_is_done(wire):
    loco = wire("loco")
    loco.send({"id": "r7", "cmd": "navigate", "args": {"pose": {"x": 2.0, "y": 0.0, "yaw": None}}})
    done = loco.reply("r7")
    trace = loco.replies_to("r7")
    assert trace[0] == "accepted" and trace[-1] == "done" and set(trace[1:-1]) == {"progress"}
    assert len(trace) >= 4  # 4 s of clock time: a progress line about every 0.5 s
    first = next(m for m in loco.seen if m.get("id") == "r7")
    assert first["data"] == {"duration": 4.0}
    progress = [m["data"] for m in loco.seen if m.get("id") == "r7" and m["type"] == "progress"]
    assert all(0.0 <= d["pose"]["x"] <= 2.0 for d in progress)
    assert done["result"] == {"pose": {"x": 2.0, "y": 0.0, "yaw": 0.0}, "marker": None, "distance": 2.0}


def test_an_error_reply_carries_code_reason_and_vendor_code(wire):
    gesture = wire("gesture")
    gesture.send({"id": "g1", "cmd": "play", "args": {"name": "hig five"}})
    assert gesture.reply("g1") == {"id": "g1", "type": "error", "code": "unknown_gesture",
                                   "reason": "no gesture 'hig five' (did you mean 'high five'?)", "vendor_code": 7402}
    assert gesture.replies_to("g1") == ["error"]  # rejected before anything moved: no accepted


def test_heartbeats_count_up_and_carry_the_backend_state(wire):
    loco = wire("loco")
    beats = [loco.next(lambda m: m.get("type") == "heartbeat") for _ in range(3)]
    assert [b["seq"] for b in beats] == [beats[0]["seq"], beats[0]["seq"] + 1, beats[0]["seq"] + 2]
    assert beats[-1]["state"] == {"pose": {"x": 0.0, "y": 0.0, "yaw": 0.0}, "moving": False}


def test_an_utterance_cannot_smuggle_in_a_second_command(wire):
    tts = wire("tts")
    text = 'Hello\n{"id":"x","cmd":"stop"}\n'
    line = p.encode(p.request("s1", "say", {"text": text}))
    assert line.count(b"\n") == 1  # the newlines travel escaped inside the string
    tts.send(line)
    done = tts.reply("s1")
    assert done["type"] == "done" and done["result"]["text"] == text
    assert tts.replies_to("x") == []  # nobody saw a command "x"
    tts.send({"id": "st", "cmd": "state"})
    assert tts.reply("st")["result"]["spoken"] == [text]


@pytest.mark.parametrize("line, request_id, reason", [
    (b"hello daemon\n", None, "not JSON"),
    (b"[1, 2]\n", None, "expected a JSON object, got list"),
    (b'{"cmd": "ping"}\n', None, "request needs a non-empty string 'id'"),
    (b'{"id": "b4"}\n', "b4", "request needs a string 'cmd'"),
    (b'{"id": "b5", "cmd": "ping", "args": [1]}\n', "b5", "'args' must be an object, got list"),
    (b"\xff\xfe\n", None, "not JSON"),
])
def test_a_garbage_line_gets_bad_request_and_the_daemon_carries_on(wire, line, request_id, reason):
    loco = wire("loco")
    loco.send(line)
    error = loco.reply(request_id)
    assert error["code"] == "bad_request" and reason in error["reason"]
    loco.send({"id": "after", "cmd": "ping"})
    assert loco.reply("after")["type"] == "done"


def test_bad_arguments_are_rejected_with_what_is_wrong(wire):
    loco = wire("loco")
    loco.send({"id": "n1", "cmd": "navigate", "args": {"pose": {"x": "far", "y": 0}}})
    assert loco.reply("n1")["reason"] == "navigate pose: 'x' must be a finite number, got 'far'"
    loco.send({"id": "n2", "cmd": "navigate", "args": {"pose": {"x": 1, "y": 0}, "tolerence": 0.2}})
    assert "unknown argument 'tolerence' (did you mean 'tolerance'?)" in loco.reply("n2")["reason"]
    loco.send({"id": "n3", "cmd": "navigate", "args": {}})
    assert loco.reply("n3")["reason"] == "navigate: give exactly one of pose, relative, approach, view (got none)"


def test_an_unknown_command_is_answered_with_a_suggestion(wire):
    loco = wire("loco")
    loco.send({"id": "u1", "cmd": "navgate", "args": {}})
    assert loco.reply("u1") == {"id": "u1", "type": "error", "code": "unknown_command",
                                "reason": "loco daemon has no command 'navgate' (did you mean 'navigate'?)"}


def test_a_line_over_one_mebibyte_is_rejected_unread(wire):
    tts = wire("tts")
    huge = json.dumps({"id": "big", "cmd": "say", "args": {"text": "a" * p.MAX_LINE}}).encode() + b"\n"
    tts.send(huge)
    error = tts.reply(None)
    assert error["code"] == "bad_request" and "exceeds the 1048576-byte limit" in error["reason"]
    tts.send({"id": "after", "cmd": "ping"})
    assert tts.reply("after")["type"] == "done"
    assert tts.replies_to("big") == []


def test_line_buffer_joins_chunks_and_drops_oversize_lines():
    lines = p.LineBuffer(limit=10)
    assert lines.feed(b'{"a"') == []
    assert lines.feed(b':1}\n{"b":2}\n\n') == [b'{"a":1}', b'{"b":2}']
    assert lines.feed(b"x" * 11) == [p.Oversize(11)]
    assert lines.feed(b"yyyy\nok\n") == [b"ok"]  # the rest of the long line is skipped


def test_encode_makes_one_line_and_decode_reads_it_back():
    message = p.request("r1", "say", {"text": "line one\nline two \u2028 end"})
    line = p.encode(message)
    assert line.endswith(b"\n") and line.count(b"\n") == 1
    assert p.decode(line) == message
    with pytest.raises(p.ProtocolError, match="not JSON"):
        p.decode(b"{nope")


# -- the decoder at the boundary: refuses, never crashes (issue 12) ---------------------------


FUZZ = settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=20),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=4),
    max_leaves=30,
)


def _finite_everywhere(value) -> bool:
    stack = [value]
    while stack:
        item = stack.pop()
        if isinstance(item, float) and item != item or item in (float("inf"), float("-inf")):
            return False
        if isinstance(item, dict):
            stack += list(item.values())
        elif isinstance(item, list):
            stack += item
    return True


def _decodes_or_refuses(line) -> None:
    try:
        message = p.decode(line)
    except p.ProtocolError:
        return
    assert isinstance(message, dict) and _finite_everywhere(message)
    with contextlib.suppress(p.ProtocolError):
        p.check_daemon_message(message)


def _lines_of(stream: bytes, limit: int) -> list[bytes | str]:
    """What a line buffer must give for ``stream`` however it is cut into reads: each complete
    line that is not blank, "oversize" for each line over ``limit`` (a long unfinished last line
    included: it is known to be too long before its end arrives)."""
    *complete, unfinished = stream.split(b"\n")
    out: list[bytes | str] = ["oversize" if len(line) > limit else line for line in complete if line.strip()
                              or len(line) > limit]
    return out + (["oversize"] if len(unfinished) > limit else [])


@FUZZ
@given(st.lists(st.sampled_from([b"\n", b" ", b"{}", b'{"a":1}', b"x" * 7, b"\n\n"]), max_size=40),
       st.lists(st.integers(min_value=1, max_value=40), max_size=20))
def test_line_buffer_gives_the_same_lines_however_the_stream_is_cut(pieces, cuts):
    stream = b"".join(pieces)
    lines, out, start = p.LineBuffer(limit=10), [], 0
    for cut in [*cuts, len(stream)]:  # reads of any size, some ending at a newline (the quick path)
        out += lines.feed(stream[start:start + cut])
        start += cut
    out += lines.feed(stream[start:])
    assert ["oversize" if isinstance(line, p.Oversize) else line for line in out] == _lines_of(stream, 10)


@FUZZ
@given(st.binary(max_size=300))
def test_decode_of_arbitrary_bytes_gives_a_message_or_a_protocol_error(data):
    _decodes_or_refuses(data)


@FUZZ
@given(st.text(alphabet=st.sampled_from('{}[]",:0123456789.eE-+ abcNaInfity\\u'), max_size=200))
def test_decode_of_json_like_text_gives_a_message_or_a_protocol_error(text):
    _decodes_or_refuses(text)


@FUZZ
@given(JSON_VALUES)
def test_decode_of_any_json_value_never_lets_a_non_finite_number_through(value):
    line = json.dumps(value, allow_nan=True)  # NaN / Infinity as Python writes them
    _decodes_or_refuses(line)
    _decodes_or_refuses(json.dumps({"type": "done", "id": "r1", "result": {"pose": value}}, allow_nan=True))


@FUZZ
@given(st.integers(min_value=1, max_value=3000), st.sampled_from("[{"))
def test_deep_nesting_is_refused_before_the_parser_recurses(depth, bracket):
    body = ('{"a":' * depth + "1" + "}" * depth) if bracket == "{" else ("[" * depth + "]" * depth)
    line = '{"id": "r1", "x": ' + body + "}"
    if depth + 1 > p.MAX_DEPTH:
        with pytest.raises(p.ProtocolError, match="nested deeper than"):
            p.decode(line)
    else:
        assert p.decode(line)["id"] == "r1"


@pytest.mark.parametrize("line, says", [
    (b"[" * 300_000, "nested deeper than 32 levels"),
    (b'{"a": ' + b"[" * 100_000 + b"]" * 100_000 + b"}", "nested deeper than 32 levels"),
    (b'{"x": NaN}', "NaN is not a number"),
    (b'{"x": -Infinity}', "-Infinity is not a number"),
    (b'{"x": 1e400}', "too large for a float"),
    (b'{"x": 1E+0400}', "too large for a float"),
    (b'{"x": -2' + b"0" * 400 + b'.5}', "too large for a float"),  # no exponent, a long mantissa
    (b'{"x": 9' + b"0" * 300 + b'e10}', "too large for a float"),
    (b'{"x": ' + b"9" * 5000 + b"}", "not JSON"),
    (b'{"x": "\\ud800"}', "lone surrogate"),
    (b"\xff\xfe{}", "not UTF-8"),
])
def test_decode_refuses_what_would_crash_or_poison_the_framework(line, says):
    with pytest.raises(p.ProtocolError, match=says.replace("[", r"\[")):
        p.decode(line)


def test_brackets_inside_strings_do_not_count_as_nesting():
    text = "[" * 1000 + '"quoted \\" ]' + "{" * 1000
    assert p.decode(json.dumps({"id": "r1", "text": text})) == {"id": "r1", "text": text}


@pytest.mark.parametrize("message, says", [
    ({"type": "heartbeat", "seq": "1", "state": {}}, "heartbeat: 'seq' must be an integer, got str"),
    ({"type": "heartbeat", "seq": 1, "state": []}, "heartbeat: 'state' must be an object, got list"),
    ({"type": "done", "id": "r1", "result": {"pose": {"x": "abc", "y": 0}}}, "pose.x must be a finite number"),
    ({"type": "progress", "id": "r1", "data": {"pose": {"x": True, "y": 0}}}, "pose.x must be a finite number"),
    ({"type": "error", "id": "r1", "code": 7, "reason": "x"}, "'code' must be a string, got int"),
    ({"type": "ready", "family": "loco", "backend": "dry", "pid": True, "protocol": 1, "commands": []},
     "'pid' must be an integer, got bool"),
    ({"type": "log", "level": "shout", "message": "x"}, "level 'shout' is not one of"),
    ({"type": "mystery"}, "unknown type 'mystery'"),
])
def test_the_schema_of_each_daemon_message_type_is_checked(message, says):
    with pytest.raises(p.ProtocolError, match=says.replace("(", r"\(").replace(")", r"\)")) as caught:
        p.check_daemon_message(message)
    assert caught.value.request_id == message.get("id")


def _verdict(read) -> tuple[Any, ...]:
    try:
        return ("read", read())
    except p.ProtocolError as e:
        return ("refused", e.reason, e.request_id)


POSE_KEY_SPELLINGS = ["pose", "robot_pose", "\\u0070ose", "robot_po\\u0073e", "p\\u006Fse", "posed", "x"]


@FUZZ
@given(JSON_VALUES, st.sampled_from(POSE_KEY_SPELLINGS), st.sampled_from(["done", "progress", "error", "heartbeat"]))
def test_reading_a_daemon_line_gives_the_verdict_of_decode_then_the_schema(value, key, kind):
    """The framework's reader skips walks the text shows to be idle (no pose key, no number that
    can overflow); it must refuse exactly what the full check refuses, escaped keys included."""
    body = {"done": "result", "progress": "data", "error": "data", "heartbeat": "state"}[kind]
    extra = {"error": ',"code":"blocked","reason":"x"', "heartbeat": ',"seq":1'}.get(kind, "")
    line = (f'{{"type":"{kind}","id":"r1"{extra},"{body}":{{"{key}":{json.dumps(value, allow_nan=True)}}}}}'
            .encode())
    assert _verdict(lambda: p.decode_daemon_message(line)) == _verdict(lambda: p.check_daemon_message(p.decode(line)))


@pytest.mark.parametrize("line", [
    rb'{"type":"done","id":"r1","result":{"\u0070ose":{"x":"abc","y":0}}}',
    rb'{"type":"progress","id":"r1","data":{"robot_po\u0073e":{"x":1}}}',
])
def test_a_pose_whose_key_is_spelled_with_escapes_is_still_checked(line):
    with pytest.raises(p.ProtocolError, match="pose") as caught:
        p.decode_daemon_message(line)
    assert caught.value.request_id == "r1"


def test_every_message_a_daemon_builds_passes_the_schema():
    for message in (p.ready("loco", "dry", 1, ["ping"]), p.accepted("r1"), p.accepted("r1", {"duration": 1.0}),
                    p.progress("r1", {"pose": {"x": 1, "y": 2, "yaw": 0.5}}), p.done("r1"),
                    p.error(None, "bad_request", "x"), p.error("r1", "stopped", "x", 7, {"pose": {"x": 0, "y": 0}}),
                    p.heartbeat(1, 0.5, {"pose": {"x": 0.0, "y": 0.0, "yaw": 0.0}}), p.log("info", "hi")):
        assert p.check_daemon_message(p.decode(p.encode(message))) == message


def _stdlib_verdict(line: bytes):
    try:
        return ("read", p._decode_stdlib(line)[0])
    except p.ProtocolError as e:
        return ("refused", e.reason, e.request_id)


def _same_values(a, b) -> bool:
    """Equal, and of the same types all the way down (1 and 1.0 are equal but not the same)."""
    if type(a) is not type(b):
        return False
    if isinstance(a, dict):
        return list(a) == list(b) and all(_same_values(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return len(a) == len(b) and all(_same_values(x, y) for x, y in zip(a, b, strict=True))
    return a == b or (a != a and b != b)


NUMBER_TEXT = st.one_of(st.integers().map(str), st.floats(allow_nan=False).map(repr),
                        st.from_regex(r"-?[0-9]{1,30}(\.[0-9]{1,30})?([eE][+-]?[0-9]{1,4})?", fullmatch=True))


@FUZZ
@given(st.one_of(st.binary(max_size=200),
                 JSON_VALUES.map(lambda v: json.dumps({"id": "r1", "v": v}, allow_nan=True).encode()),
                 NUMBER_TEXT.map(lambda n: f'{{"id":"r1","n":{n}}}'.encode()),
                 st.text(alphabet=st.sampled_from('{}[]",:0123456789.eE-+ abcNaInfity\\ud8\xe9'), max_size=120)
                 .map(lambda t: t.encode("utf-8", "surrogatepass"))))
def test_the_fast_reader_reads_every_line_as_the_stdlib_reader_does(line):
    """orjson reads the usual line; what it reads must be what the stdlib path reads, to the
    type of every number, and what it refuses must be refused with the stdlib path's reason."""
    fast = _verdict(lambda: p.decode(line))
    slow = _stdlib_verdict(line)
    assert fast[0] == slow[0] and (fast[1:] == slow[1:] if fast[0] == "refused" else _same_values(fast[1], slow[1]))


@pytest.mark.parametrize("message", [
    {"type": "done", "id": "r1", "result": {"big": 2 ** 70, "small": -(2 ** 64)}},  # past 64 bits
    {"type": "done", "id": "r1", "result": {1: "a", None: "b", 2.5: "c"}},  # keys the stdlib writes as strings
    {"type": "done", "id": "r1", "result": {"nan": float("nan"), "inf": float("-inf")}},  # null, as to_json
    {"type": "log", "level": "info", "message": "line one\nline two \u2028 \x00 é"},
])
def test_encode_writes_what_the_stdlib_encoder_writes_as_one_line(message):
    line = p.encode(message)
    assert line.endswith(b"\n") and line.count(b"\n") == 1
    assert json.loads(line) == json.loads(p._TO_LINE(message))


def test_encode_refuses_what_the_stdlib_encoder_refuses():
    circular: dict = {}
    circular["self"] = circular
    with pytest.raises(ValueError):
        p.encode({"type": "done", "id": "r1", "result": circular})
    with pytest.raises(TypeError):
        p.encode({"type": "done", "id": "r1", "result": {"x": object()}})
