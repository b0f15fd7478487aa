"""A hostile page or client against the web view on loopback: DNS rebinding, huge and deeply
nested bodies, names with a trailing newline, and fuzzed bodies. Each is refused with a 4xx and
a one-line JSON reason, never a traceback, and nothing is written."""

from __future__ import annotations

import contextlib
import http.client
import json
import shutil
import socket
from importlib.resources import files
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from web_support import REPO, EventFeed, Served

pytestmark = pytest.mark.slow
LAB_MARKERS = Path(str(files("stuart_bt.sim").joinpath("maps/lab_markers.json")))
ENDPOINTS = ("/api/markers", "/api/say", "/api/walk", "/api/goto", "/api/pose", "/api/gestures/wave2",
             "/api/run", "/api/stop")


def request(served: Served, method: str, path: str, body: bytes | None = None,
            headers: dict[str, str] | None = None) -> tuple[int, str]:
    conn = http.client.HTTPConnection("127.0.0.1", served.port, timeout=30)
    try:
        conn.request(method, path, body=body, headers={"Content-Type": "application/json", **(headers or {})})
        response = conn.getresponse()
        return response.status, response.read().decode("utf-8", "replace")
    finally:
        conn.close()


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    folder = tmp_path_factory.mktemp("hostile")
    markers = folder / "markers.json"
    shutil.copy(LAB_MARKERS, markers)
    with Served("trees/greet.yaml", "--paused", "--markers", str(markers), "--gestures", str(folder / "gestures"),
                cwd=REPO) as made:
        made.markers = markers
        made.gestures = folder / "gestures"
        yield made


def test_a_rebinding_page_that_names_another_host_is_refused_and_changes_nothing(served):
    before = served.markers.read_text()
    evil = {"Host": f"evil.example:{served.port}", "Origin": f"http://evil.example:{served.port}"}
    body = json.dumps({"op": "add", "name": "trap", "x": 1.0, "y": 1.0, "yaw": 0.0}).encode()
    status, text = request(served, "POST", "/api/markers", body, evil)
    assert status == 403 and "Host" in json.loads(text)["error"]
    assert request(served, "GET", "/api/state", headers={"Host": f"evil.example:{served.port}"})[0] == 403
    assert request(served, "POST", "/api/say", b'{"text": "hi"}', evil)[0] == 403
    assert served.markers.read_text() == before
    assert request(served, "GET", "/api/state", headers={"Host": f"localhost:{served.port}"})[0] == 200


def test_a_body_over_the_cap_is_refused_with_413_and_the_server_goes_on(served):
    status, text = request(served, "POST", "/api/say", b'{"text": "' + b"a" * (2 << 20) + b'"}')
    assert status == 413 and "Traceback" not in text
    assert request(served, "GET", "/api/state")[0] == 200


def test_a_deeply_nested_body_is_a_400_with_one_line_and_no_traceback(served):
    status, text = request(served, "POST", "/api/markers", b"[" * 100_000 + b"]" * 100_000)
    assert status == 400 and "nested deeper" in json.loads(text)["error"] and "Traceback" not in text


@pytest.mark.parametrize("path, body", [
    ("/api/markers", {"op": "add", "name": "kitchen2\n", "x": 1.0, "y": 1.0, "yaw": 0.0}),
    ("/api/gestures/wave2%0A", {"keyframes": [{"t": 0.0, "joints": {}}]}),
])
def test_a_name_with_a_trailing_newline_is_refused_and_nothing_is_written(served, path, body):
    before = served.markers.read_text()
    status, _ = request(served, "POST", path, json.dumps(body).encode())
    assert 400 <= status < 500
    assert served.markers.read_text() == before
    assert not any(served.gestures.glob("*\n*")) if served.gestures.exists() else True


@pytest.mark.parametrize("body, status, says", [
    (b'{"text": ""}', 400, "type something to say"),
    (b'{"text": " \\u0000\\u0007\\t "}', 400, "type something to say"),  # control characters only
    (b'{"text": 5}', 400, "type something to say"),
    (json.dumps({"text": "Hey Stuart, " + "la " * 700}).encode(), 400, "at most 2000 characters"),
    (b'{"text": "Hey Stuart, caf\xe9"}', 400, "not JSON"),  # Latin-1, not UTF-8
    (b'{"text": "Hey Stuart, stop"', 400, "not JSON"),
    (b'["Hey Stuart, stop"]', 400, "a JSON object"),
    (b'{"text": "Hey Stuart, stop"}', 409, "nothing is running"),  # the tree waits for Run
], ids=["empty", "control characters", "not a string", "too long", "not UTF-8", "cut JSON", "an array",
        "nothing running"])
def test_an_odd_utterance_to_a_tree_server_is_one_clear_4xx_and_nothing_is_said(served, body, status, says):
    answer, text = request(served, "POST", "/api/say", body)
    with EventFeed(served) as feed:  # its hello holds every event so far
        heard = feed.of("utterance")
    assert answer == status and says in json.loads(text)["error"] and "Traceback" not in text
    assert heard == []


JSON = st.recursive(st.none() | st.booleans() | st.floats(allow_nan=False) | st.integers() | st.text(max_size=12),
                    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner, max_size=4),
                    max_leaves=20)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(path=st.sampled_from(ENDPOINTS),
       body=JSON.map(lambda v: json.dumps(v).encode()) | st.binary(max_size=200))
def test_any_body_to_any_endpoint_is_answered_below_500_without_a_traceback(served, path, body):
    before = served.markers.read_text()
    status, text = request(served, "POST", path, body)
    assert status < 500, (path, body, status, text)
    assert "Traceback" not in text
    if status >= 400:
        assert served.markers.read_text() == before


def raw_exchange(served: Served, data: bytes) -> bytes:
    """Send bytes that need not be HTTP on a fresh connection; the first bytes of the answer."""
    with socket.create_connection(("127.0.0.1", served.port), timeout=30) as conn:
        with contextlib.suppress(OSError):  # the server may close before reading all: what it said is there
            conn.sendall(data)
        try:
            return conn.recv(200)
        except ConnectionResetError:
            return b""


@pytest.mark.parametrize("data", [
    b"\x00\xff\xfe garbage that is no request\r\n\r\n",
    b"GET /" + b"a" * (2 << 20) + b" HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n",
    b"GET /api/state HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Huge: " + b"b" * (2 << 20) + b"\r\n\r\n",
], ids=["garbage", "a 2 MiB request line", "a 2 MiB header"])
def test_bytes_that_are_no_request_get_a_400_and_the_server_goes_on(served, data):
    answer = raw_exchange(served, data)
    assert answer == b"" or answer.startswith(b"HTTP/1.1 400"), answer
    assert request(served, "GET", "/api/state")[0] == 200


def test_clients_that_connect_and_say_nothing_do_not_keep_others_waiting(served):
    silent = [socket.create_connection(("127.0.0.1", served.port), timeout=30) for _ in range(50)]
    try:
        status, text = request(served, "GET", "/api/state")
        assert status == 200 and json.loads(text)["mode"] == "tree"
    finally:
        for conn in silent:
            conn.close()
