"""The web app: pages, the event socket and a small JSON API, on Starlette.

Routes (every answer is JSON; a refused request gets ``{"error": "one sentence"}`` and 400, 403,
404 or 409):

| route | what |
|---|---|
| ``GET /`` and ``/static/*`` | the page (HTML, JS, CSS shipped in the package) |
| ``WS /ws`` | ``hello`` (info, snapshot, history), then ``events`` batches |
| ``GET /api/state`` | busy, running, can_continue |
| ``POST /api/run``, ``/api/stop``, ``/api/continue`` | the served tree (or the mission's stop / continue) |
| ``POST /api/say`` ``{text}`` | an utterance (at most 2000 characters) to the mission executor or the running tree |
| ``WS /ws/audio`` | push-to-talk: PCM frames of one press in, what was heard out (audio.py) |
| ``POST /api/walk`` ``{x, y, yaw}``, ``/api/goto`` ``{marker}`` | walk to a map pose / a marker |
| ``GET /api/map``, ``/api/map.png`` | map numbers and picture |
| ``GET /api/markers``, ``POST /api/markers`` ``{op, name, ...}`` | the marker file (markers.py) |
| ``GET /api/joints``, ``GET/POST /api/pose`` ``{joints}`` | sliders; the sim's arm pose now / to take |
| ``GET /api/gestures``, ``GET/POST /api/gestures/{name}``, ``POST /api/gestures/{name}/play`` | gesture files |
"""

from __future__ import annotations

import asyncio
import json
import logging
from collections.abc import AsyncIterator, Awaitable, Callable
from contextlib import asynccontextmanager
from dataclasses import dataclass
from importlib.resources import files
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.types import ASGIApp, Message, Receive, Scope, Send
from starlette.websockets import WebSocket, WebSocketDisconnect

from ..core.jsonfile import is_finite_number, nesting_depth
from ..maps.markers import load_markers
from ..mission.commands import MAX_UTTERANCE, clean_utterance
from .audio import audio_socket
from .control import ControlError
from .gestures import GestureDeskError, GestureFolder, joint_table
from .hub import EventHub
from .mapfile import MapFile
from .markers import MarkerConflict, MarkerEditError, MarkerStore
from .security import CHANGING, COOKIE, Guard

STATIC = Path(str(files("stuart_bt.web").joinpath("static")))
MAX_BODY = 1 << 20  # bytes of a request body: markers, a gesture, a sentence are a few kilobytes
MAX_NESTING = 16  # levels of objects and arrays in a request body
log = logging.getLogger("stuart_bt.web")
POSE_BLEND = 0.25  # sim seconds the arms take to reach a slider pose


@dataclass
class WebParts:
    """What one server serves; ``control`` is None for a replay."""

    hub: EventHub
    guard: Guard
    control: Any = None
    markers: MarkerStore | None = None
    map: MapFile | None = None
    gestures: GestureFolder | None = None


class BadRequest(Exception):
    """One sentence for the page; becomes a 400 answer."""


class WebApi:
    """The handlers of every route, one method each, sharing the server's parts. A replay has no
    control: a command to it is refused with a 409 and one sentence."""

    def __init__(self, parts: WebParts) -> None:
        self.parts, self.hub, self.control = parts, parts.hub, parts.control

    def need_control(self) -> Any:
        if self.control is None:
            raise ControlError("this is a replay of a saved log: nothing to command")
        return self.control

    async def index(self, request: Request) -> Response:
        response = FileResponse(STATIC / "index.html")
        token = request.query_params.get("token")
        if self.parts.guard.token is not None and token:
            response.set_cookie(COOKIE, token, httponly=True, samesite="strict")
        return response

    async def state(self, request: Request) -> Response:
        return JSONResponse(self.need_control().state() if self.control else {"mode": "replay", "busy": False})

    async def run(self, request: Request) -> Response:
        await _off_loop(self.need_control().run)
        return JSONResponse({"ok": True})

    async def stop(self, request: Request) -> Response:
        await _off_loop(self.need_control().stop)
        return JSONResponse({"ok": True})

    async def resume(self, request: Request) -> Response:
        await _off_loop(self.need_control().resume)
        return JSONResponse({"ok": True})

    async def say(self, request: Request) -> Response:
        body = await _json(request)
        text = body.get("text")
        if isinstance(text, str) and len(text) > MAX_UTTERANCE:
            raise BadRequest(f"an utterance is at most {MAX_UTTERANCE} characters")
        cleaned = clean_utterance(text)  # control characters become spaces
        if cleaned is None:
            raise BadRequest("type something to say")
        result = await _off_loop(self.need_control().say, cleaned)
        return JSONResponse({"ok": True, **(result or {})})

    async def walk(self, request: Request) -> Response:
        body = await _json(request)
        x, y = _number(body, "x"), _number(body, "y")
        yaw = None if body.get("yaw") is None else _number(body, "yaw")
        job = await _off_loop(self.need_control().walk, x, y, yaw)
        return JSONResponse({"ok": True, **job})

    async def goto(self, request: Request) -> Response:
        body = await _json(request)
        marker = body.get("marker")
        if not isinstance(marker, str):
            raise BadRequest("name a marker to go to")
        job = await _off_loop(self.need_control().go_to, marker)
        return JSONResponse({"ok": True, **job})

    async def map_info(self, request: Request) -> Response:
        if self.parts.map is None:
            raise ControlError("no map")
        return JSONResponse(self.parts.map.info())

    async def map_png(self, request: Request) -> Response:
        if self.parts.map is None:
            raise ControlError("no map")
        return FileResponse(self.parts.map.png, media_type="image/png")

    async def markers_get(self, request: Request) -> Response:
        if self.parts.markers is None:
            raise ControlError("no marker file")
        return JSONResponse(await _off_loop(self.parts.markers.load))

    async def markers_edit(self, request: Request) -> Response:
        if self.parts.markers is None:
            raise ControlError("no marker file")
        body = await _json(request)
        try:
            doc = await _off_loop(self.parts.markers.edit, body)
        except MarkerConflict as e:
            return JSONResponse({"error": str(e), "current": e.current}, status_code=409)
        if self.control is not None:
            self.control.set_markers(load_markers(self.parts.markers.path))
        return JSONResponse(doc)

    async def joints(self, request: Request) -> Response:
        return JSONResponse({"joints": await _off_loop(joint_table),
                             "live": bool(self.control is not None and self.control.mode == "tree"
                                          and self.control.session.world is not None)})

    async def pose(self, request: Request) -> Response:
        body = await _json(request)
        joints_in = body.get("joints")
        if not isinstance(joints_in, dict) or not joints_in:
            raise BadRequest("'joints' must map joint names to radians")
        from ..skills.gesture.keyframes import validate_keyframes

        problems = validate_keyframes([{"t": 0.0, "joints": joints_in}])
        if problems:
            raise BadRequest("; ".join(p.removeprefix("keyframe 0: ") for p in problems))
        result = await _off_loop(self.need_control().world_call, "arm_trajectory", id="web pose",
                                 points=[{"t": POSE_BLEND, "joints": joints_in}])
        return JSONResponse({"ok": True, "ends_at": result.get("ends_at")})

    async def pose_now(self, request: Request) -> Response:
        state_now = await _off_loop(self.need_control().world_call, "state")
        names = {row["name"] for row in await _off_loop(joint_table)}
        return JSONResponse({"joints": {k: v for k, v in state_now.get("joints", {}).items() if k in names},
                             "t": state_now.get("t")})

    def folder(self) -> GestureFolder:
        if self.parts.gestures is None:
            raise ControlError("no gesture folder")
        return self.parts.gestures

    async def gestures_list(self, request: Request) -> Response:
        return JSONResponse({"folder": str(self.folder().folder), "gestures": self.folder().names()})

    async def gesture_get(self, request: Request) -> Response:
        return JSONResponse(await _off_loop(self.folder().load, request.path_params["name"]))

    async def gesture_save(self, request: Request) -> Response:
        body = await _json(request)
        path = await _off_loop(self.folder().save, request.path_params["name"], body.get("keyframes"))
        return JSONResponse({"ok": True, "file": str(path)})

    async def gesture_play(self, request: Request) -> Response:
        name = request.path_params["name"]
        await _off_loop(self.folder().load, name)  # refuses a missing or broken file with its problems
        await _off_loop(self.need_control().play_gesture, self.folder().path_for(name))
        return JSONResponse({"ok": True})

    async def socket(self, websocket: WebSocket) -> None:
        if not self.parts.guard.host_ok(websocket.headers) or not self.parts.guard.origin_ok(websocket.headers) or \
                not self.parts.guard.token_ok(websocket.query_params, websocket.headers, websocket.cookies):
            await websocket.close(code=1008)
            return
        await websocket.accept()
        client, hello = self.hub.connect()

        async def until_closed() -> None:  # a closed tab ends its sender at once, not at the next send
            try:
                while (await websocket.receive())["type"] != "websocket.disconnect":
                    pass
            finally:
                client.end()

        watcher = asyncio.create_task(until_closed())
        try:
            await websocket.send_text(hello)
            while True:
                text = await client.queue.get()
                if text is None:
                    break
                await websocket.send_text(text)
        except (WebSocketDisconnect, RuntimeError):
            pass
        finally:
            watcher.cancel()
            self.hub.disconnect(client)


    async def audio(self, websocket: WebSocket) -> None:
        await audio_socket(websocket, self.parts.guard, getattr(self.control, "hear", None))


def create_app(parts: WebParts) -> Starlette:
    """The web view's ASGI app: the routes of :class:`WebApi`, the static page, and the guard
    (Host, Origin, token, body limits) in front of everything."""
    api = WebApi(parts)
    routes = [
        Route("/", api.index),
        Route("/api/state", api.state),
        Route("/api/run", api.run, methods=["POST"]),
        Route("/api/stop", api.stop, methods=["POST"]),
        Route("/api/continue", api.resume, methods=["POST"]),
        Route("/api/say", api.say, methods=["POST"]),
        Route("/api/walk", api.walk, methods=["POST"]),
        Route("/api/goto", api.goto, methods=["POST"]),
        Route("/api/map", api.map_info),
        Route("/api/map.png", api.map_png),
        Route("/api/markers", api.markers_get, methods=["GET"]),
        Route("/api/markers", api.markers_edit, methods=["POST"]),
        Route("/api/joints", api.joints),
        Route("/api/pose", api.pose_now, methods=["GET"]),
        Route("/api/pose", api.pose, methods=["POST"]),
        Route("/api/gestures", api.gestures_list),
        Route("/api/gestures/{name}", api.gesture_get, methods=["GET"]),
        Route("/api/gestures/{name}", api.gesture_save, methods=["POST"]),
        Route("/api/gestures/{name}/play", api.gesture_play, methods=["POST"]),
        WebSocketRoute("/ws", api.socket),
        WebSocketRoute("/ws/audio", api.audio),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]

    @asynccontextmanager
    async def lifespan(app: Starlette) -> AsyncIterator[None]:
        parts.hub.attach(asyncio.get_running_loop())
        yield
        parts.hub.close()

    app = Starlette(routes=routes, lifespan=lifespan, exception_handlers=EXCEPTION_HANDLERS)
    return _Checked(app, parts.guard)  # type: ignore[return-value]


class BodyTooLarge(Exception):
    """A request body over MAX_BODY bytes: refused while it streams in, never held whole."""


class _Checked:
    """ASGI wrapper: Host and the token on every HTTP request, Origin on changing ones, and a
    body size cap counted as the body arrives."""

    def __init__(self, app: ASGIApp, guard: Guard) -> None:
        self.app = app
        self.guard = guard

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)  # the socket checks its own host, token and origin
            return
        request = Request(scope)
        if not self.guard.host_ok(request.headers):
            await _error("refused: this server is not known by that name (Host)", 403)(scope, receive, send)
            return
        if int(request.headers.get("content-length") or 0) > MAX_BODY:
            await _error(f"the request body is over {MAX_BODY} bytes", 413)(scope, receive, send)
            return
        if not self.guard.token_ok(request.query_params, request.headers, request.cookies):
            await _error("a token is needed: open the address printed when the server started", 403)(
                scope, receive, send)
            return
        if request.method in CHANGING and not self.guard.origin_ok(request.headers):
            await _error("refused: the request did not come from this page (Origin)", 403)(scope, receive, send)
            return
        await self.app(scope, _capped(receive), send)


def _capped(receive: Receive) -> Receive:
    """``receive`` that raises BodyTooLarge once more than MAX_BODY body bytes came in (a chunked
    body has no Content-Length to check first)."""
    seen = 0

    async def counting() -> Message:
        nonlocal seen
        message = await receive()
        if message["type"] == "http.request":
            seen += len(message.get("body", b""))
            if seen > MAX_BODY:
                raise BodyTooLarge(f"the request body is over {MAX_BODY} bytes")
        return message
    return counting


def _error(message: str, status: int) -> Response:
    return JSONResponse({"error": message}, status_code=status)


def _refusal(status: int) -> Callable[[Request, Exception], Awaitable[Response]]:
    async def handler(request: Request, exc: Exception) -> Response:
        return _error(str(exc), status)
    return handler


async def _gesture_refusal(request: Request, exc: Exception) -> Response:
    problems = getattr(exc, "problems", [str(exc)])
    status = 404 if problems and problems[0].startswith("no gesture") else 400
    return JSONResponse({"error": "; ".join(problems), "problems": problems}, status_code=status)


async def _internal_error(request: Request, exc: Exception) -> Response:
    """A bug answered as one line, with no traceback for the client (the server's log has it)."""
    log.error("%s %s failed: %s: %s", request.method, request.url.path, type(exc).__name__, exc, exc_info=exc)
    return _error("internal error; the server's log says more", 500)


EXCEPTION_HANDLERS = {ControlError: _refusal(409), BadRequest: _refusal(400), MarkerEditError: _refusal(400),
                      GestureDeskError: _gesture_refusal, BodyTooLarge: _refusal(413), Exception: _internal_error}


async def _off_loop(fn: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
    """Run a blocking call (file, daemon, world) in a thread; a refusal of the world or the file
    system becomes one sentence for the page."""
    try:
        return await asyncio.to_thread(fn, *args, **kwargs)
    except OSError as e:
        raise BadRequest(f"{e.strerror or e}") from None
    except Exception as e:
        if type(e).__name__ == "WorldError":  # the simulator refused (e.g. a joint limit)
            raise BadRequest(f"the simulator refused: {e}") from None
        raise


async def _json(request: Request) -> dict[str, Any]:
    raw = await request.body() or b"{}"
    if nesting_depth(raw, MAX_NESTING) > MAX_NESTING:
        raise BadRequest(f"the request body is nested deeper than {MAX_NESTING} levels")
    try:
        body = json.loads(raw, parse_constant=_no_constant)
    except (ValueError, RecursionError):  # JSONDecodeError and UnicodeDecodeError are ValueErrors
        raise BadRequest("the request body is not JSON") from None
    if not isinstance(body, dict):
        raise BadRequest("the request body must be a JSON object")
    return body


def _no_constant(name: str) -> float:
    raise ValueError(f"{name} is not JSON")


def _number(body: dict[str, Any], key: str) -> float:
    value = body.get(key)
    if not is_finite_number(value):
        raise BadRequest(f"{key} must be a finite number (metres or radians)")
    return float(value)

