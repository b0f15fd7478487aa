"""Who may use the web view: loopback (127.0.0.1) without a token; any other address (here
127.0.0.2, still this machine) only with the token printed at start, on every request and socket;
a changing request from another origin is refused either way. And the CLI's one-line refusals."""

from __future__ import annotations

import json
import socket
import subprocess
import sys
import urllib.error
import urllib.request

import pytest

from web_support import REPO, Served, browser_tests

browser_tests()
websockets_sync = pytest.importorskip("websockets.sync.client", reason="the socket check needs websockets (web extra)")

pytestmark = pytest.mark.slow
OFF_LOOPBACK = "127.0.0.2"  # not 127.0.0.1: the token rule applies (and it never leaves this machine)


def http(url: str, method: str = "GET", headers: dict[str, str] | None = None) -> tuple[int, dict]:
    body = b"{}" if method == "POST" else None
    request = urllib.request.Request(url, method=method, headers=headers or {}, data=body)
    try:
        with urllib.request.urlopen(request, timeout=10) as response:
            return response.status, json.loads(response.read() or b"null")
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read() or b"null")


def socket_opens(url: str, **headers: str) -> bool:
    try:
        with websockets_sync.connect(url, additional_headers=headers, open_timeout=10) as ws:
            return json.loads(ws.recv(timeout=10))["type"] == "hello"
    except Exception:  # noqa: BLE001 - refused at the handshake or closed at once
        return False


def test_off_loopback_every_request_and_socket_needs_the_printed_token(page):
    with Served("trees/greet.yaml", "--paused", host=OFF_LOOPBACK) as served:
        token = served.url.split("?token=")[1]
        assert f"token: {token}" in served.output()
        base = served.url.split("?")[0]
        ws = base.replace("http://", "ws://") + "ws"

        assert http(base + "api/state") == (403, {"error": "a token is needed: open the address printed when the "
                                                           "server started"})
        assert http(base + "api/state?token=wrong")[0] == 403
        assert http(base + "static/main.js")[0] == 403
        assert http(base + "api/state", headers={"Authorization": f"Bearer {token}"})[0] == 200
        assert http(base + f"api/state?token={token}")[0] == 200
        assert not socket_opens(ws)
        assert socket_opens(ws + f"?token={token}")
        # the token is right but the page asking is another site's
        assert http(base + f"api/stop?token={token}", "POST", {"Origin": "http://evil.example"})[0] == 403
        assert not socket_opens(ws + f"?token={token}", Origin="http://evil.example")

        page.goto(base)
        assert "a token is needed" in page.text_content("body")
        page.goto(served.url)  # the printed address: the page keeps the token in a same-site cookie
        page.wait_for_selector("#conn.ok")
        page.wait_for_selector('.node[data-path="greet"]')
        page.goto(base)  # so a reload without it still works
        page.wait_for_selector("#conn.ok")


def test_on_loopback_no_token_is_needed_but_origin_is_still_checked():
    with Served("trees/greet.yaml", "--paused") as served:
        assert "?token=" not in served.url and "token:" not in served.output()
        assert http(served.url + "api/state")[0] == 200
        assert socket_opens(served.url.replace("http://", "ws://") + "ws")
        assert http(served.url + "api/run", "POST", {"Origin": "http://evil.example"})[0] == 403
        assert http(served.url + "api/run", "POST", {"Origin": served.url.rstrip("/")})[0] == 200


def serve(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "stuart_bt.cli", "serve", *args], cwd=REPO, capture_output=True,
                          text=True, timeout=60)


@pytest.mark.parametrize("args, message", [
    ((), "give one of: a TREE file, --mission, or --replay RUN.jsonl"),
    (("trees/greet.yaml", "--mission"), "give one of"),
    (("trees/nope.yaml",), "nope.yaml"),
    (("--replay", "README.md"), "README.md: not an event log"),
    (("trees/greet.yaml", "--port", "70000"), "is not a port number"),
])
def test_bad_input_is_one_line_and_starts_nothing(args, message):
    done = serve(*args)
    assert done.returncode == 1
    assert message in done.stderr and "Traceback" not in done.stderr


def test_a_port_in_use_is_said_before_anything_starts():
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        done = serve("trees/greet.yaml", "--port", str(port))
    assert done.returncode == 1
    assert f"cannot listen on 127.0.0.1:{port}" in done.stderr and "starting" not in done.stderr
