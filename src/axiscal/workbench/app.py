"""The workbench's web application: the page, its JSON routes and the live stream, on Starlette.

The page (``axiscal/workbench/web``: plain HTML, JavaScript and SVG, nothing fetched from
elsewhere) calls one route per step; each route calls one method of
:class:`~axiscal.workbench.visit.Workbench` in a worker thread and answers JSON: the result, or
``{"error": ...}`` (400) for a mistake, or ``{"fields": {...}}`` (422) naming each field of a form
that cannot be used. ``/ws`` streams the run ``update_hz`` times a second: its state (progress,
stops, lights, reading and position) and every sample of the trace since the last message, so the
page draws the reading without a gap however fast the instrument samples.

Guards, as the live dashboard's: the loopback interface by default; every request's ``Host``
must be an allowed name and its ``Origin`` (when sent) the page's own; bound to another
address, every request must also carry the session's token (``?token=`` once, then a cookie);
request bodies are capped at :data:`MAX_BODY` (an instrument's file sent to ``/api/upload`` at
:data:`~axiscal.workbench.added.MAX_UPLOAD`); files are served only from the data folder.
"""

from __future__ import annotations

import asyncio
import contextlib
import hmac
import json
import math
import secrets
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.middleware import Middleware
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.websockets import WebSocket, WebSocketDisconnect

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_number
from axiscal.live.server import LOOPBACK_HOSTS, request_allowed
from axiscal.workbench.added import MAX_UPLOAD
from axiscal.workbench.budget import budget_defaults
from axiscal.workbench.forms import FormErrors
from axiscal.workbench.tabs import OpenElsewhere
from axiscal.workbench.visit import Workbench

__all__ = ["WEB", "MAX_BODY", "TOKEN_COOKIE", "TAB_HEADER", "create_workbench_app", "new_token"]

WEB = Path(__file__).parent / "web"
#: largest request body taken, bytes
MAX_BODY = 64 * 1024
TOKEN_COOKIE = "axiscal_workbench"


class _Guard:
    """ASGI middleware: Host and Origin checked; the token when one is set; bodies capped."""

    def __init__(self, app, allowed_hosts: tuple[str, ...] | None, token: str | None):
        self.app = app
        self.allowed_hosts = allowed_hosts
        self.token = token

    def _token_given(self, scope) -> bool:
        if self.token is None:
            return True
        from http.cookies import SimpleCookie
        from urllib.parse import parse_qs

        query = parse_qs(scope.get("query_string", b"").decode("latin-1")).get("token", [""])[0]
        cookie = SimpleCookie()
        for name, value in scope["headers"]:
            if name.lower() == b"cookie":
                with contextlib.suppress(Exception):
                    cookie.load(value.decode("latin-1"))
        given = cookie[TOKEN_COOKIE].value if TOKEN_COOKIE in cookie else query
        return hmac.compare_digest(given.encode(), self.token.encode())

    async def _refuse(self, scope, send, status: int, text: bytes) -> None:
        if scope["type"] == "websocket":
            await send({"type": "websocket.close", "code": 1008})
            return
        await send({"type": "http.response.start", "status": status, "headers": [(b"content-type", b"text/plain")]})
        await send({"type": "http.response.body", "body": text})

    async def __call__(self, scope, receive, send) -> None:
        if scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        headers = {name.decode("latin-1").lower(): value.decode("latin-1") for name, value in scope["headers"]}
        hosts = self.allowed_hosts
        if hosts is None:  # bound to every interface: any name, the token decides
            hosts = (headers.get("host", "").rsplit(":", 1)[0].lower(),) if headers.get("host") else ()
        if not request_allowed(headers, hosts) or not self._token_given(scope):
            await self._refuse(scope, send, 403, b"forbidden: host, origin or token not allowed\n")
            return
        length = headers.get("content-length")
        cap = MAX_UPLOAD if scope.get("path") == "/api/upload" else MAX_BODY  # an instrument's file may be larger
        if length is not None and (not length.isdigit() or int(length) > cap):
            await self._refuse(scope, send, 413, b"request too large\n")
            return
        received = 0

        async def capped():
            nonlocal received
            message = await receive()
            if message["type"] == "http.request":
                received += len(message.get("body", b""))
                if received > cap:
                    raise _TooLarge
            return message

        try:
            await self.app(scope, capped if scope["type"] == "http" else receive, send)
        except _TooLarge:
            await self._refuse(scope, send, 413, b"request too large\n")


class _TooLarge(Exception):
    pass


def _json_safe(value: Any) -> Any:
    """``value`` with every NaN or infinity as None (JSON has neither: a figure not defined is shown as such)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(v) for v in value]
    return value


#: the header that carries the page's tab id (a call without it, from a script, is no tab's)
TAB_HEADER = "x-axiscal-tab"


def _tab(request: Any) -> str | None:
    tab = request.headers.get(TAB_HEADER) or request.query_params.get("tab")
    return tab[:64] if tab else None


def _answer(call, *args, claim: Any = None, **kwargs):
    """``call`` in a worker thread, answered as JSON; ``claim`` (a request) first asks that its tab may change the visit."""
    async def run() -> Response:
        try:
            if claim is not None:
                claim.app.state.bench.tabs.claim(_tab(claim))
            return JSONResponse(_json_safe(await run_in_threadpool(call, *args, **kwargs)))
        except FormErrors as exc:
            return JSONResponse({"error": str(exc), "fields": exc.fields}, status_code=422)
        except OpenElsewhere as exc:
            return JSONResponse({"error": str(exc), "readonly": True}, status_code=409)
        except AxiscalError as exc:
            return JSONResponse({"error": str(exc)}, status_code=400)
    return run()


async def _body(request: Request) -> Any:
    try:
        return await request.json()
    except (ValueError, UnicodeDecodeError):
        return None


def create_workbench_app(bench: Workbench, *, update_hz: float = 20.0, allowed_hosts: tuple[str, ...] | None = LOOPBACK_HOSTS,
                         token: str | None = None) -> Starlette:
    """The workbench's app for ``bench``.

    Parameters
    ----------
    bench : Workbench
        The visit and the history the page works on.
    update_hz : float, keyword-only
        Messages per second on ``/ws`` (1 to 60; default 20).
    allowed_hosts : tuple of str or None, keyword-only
        Host names a request may name (default the loopback names); None: any, with the token.
    token : str, optional, keyword-only
        The session's token, required of every request when given (the server is bound to
        another address than loopback).

    Returns
    -------
    Starlette
        ``app.state.bench`` is ``bench``.

    Raises
    ------
    AxiscalError
        For a ``bench`` that is not a Workbench, an ``update_hz`` outside 1-60, a token shorter than
        16 characters, no token where any host is allowed.
    """
    check_instance("bench", bench, Workbench)
    update_hz = check_number("update_hz", update_hz, low=1.0, high=60.0, unit="Hz")
    if token is not None and (not isinstance(token, str) or len(token) < 16):
        raise AxiscalError("token must be a str of 16 characters or more")
    if allowed_hosts is None and token is None:
        raise AxiscalError("a workbench that answers any host name needs a token")
    if allowed_hosts is not None and (isinstance(allowed_hosts, str) or not all(isinstance(h, str) for h in allowed_hosts)):
        raise AxiscalError(f"allowed_hosts must be a tuple of host names, not {allowed_hosts!r}")
    interval = 1.0 / update_hz

    async def page(request: Request) -> Response:
        response = FileResponse(WEB / "index.html", media_type="text/html")
        if token is not None:
            response.set_cookie(TOKEN_COOKIE, token, httponly=True, samesite="strict")
        return response

    async def icon(request: Request) -> Response:
        # browsers ask for /favicon.ico whatever the page names: both answer with the page's own icon
        return FileResponse(WEB / "favicon.svg", media_type="image/svg+xml")

    async def machines(request: Request) -> Response:
        return await _answer(bench.machines)

    async def machine(request: Request) -> Response:
        return await _answer(bench.machine, request.query_params.get("name", ""))

    async def trend(request: Request) -> Response:
        try:
            svg = await run_in_threadpool(bench.trend_svg, request.query_params.get("machine", ""),
                                          request.query_params.get("figure", ""))
        except AxiscalError as exc:
            return JSONResponse({"error": str(exc)}, status_code=400)
        return Response(svg, media_type="image/svg+xml")

    async def visit(request: Request) -> Response:
        return await _answer(bench.new_visit, await _body(request), claim=request)

    async def state(request: Request) -> Response:
        return await _answer(bench.state, _tab(request))

    async def visits(request: Request) -> Response:
        return await _answer(bench.unfinished)

    async def certificate(request: Request) -> Response:
        return await _answer(bench.certificate_defaults)

    async def budget(request: Request) -> Response:
        return await _answer(budget_defaults, bench.data, request.query_params.get("instrument", ""),
                             request.query_params.get("serial", ""))

    async def open_visit(request: Request) -> Response:
        body = await _body(request)
        return await _answer(bench.open_visit, body.get("folder") if isinstance(body, dict) else None, claim=request)

    async def step(request: Request) -> Response:
        body = await _body(request)
        if not bench.tabs.may_act(_tab(request)):  # a tab that follows the visit does not move it
            return JSONResponse({"step": None, "readonly": True})
        return await _answer(bench.set_step, body.get("step") if isinstance(body, dict) else None)

    async def ports(request: Request) -> Response:
        return await _answer(bench.ports)

    async def plan(request: Request) -> Response:
        return await _answer(bench.make_plan, await _body(request), claim=request)

    async def connection(request: Request) -> Response:
        return await _answer(bench.connect, await _body(request), claim=request)

    async def run(request: Request) -> Response:
        if request.method == "GET":
            return JSONResponse(_json_safe(bench.run_state()))
        body = await _body(request) or {}
        if not isinstance(body, dict):
            return JSONResponse({"error": "send the run's phase as a JSON object"}, status_code=400)
        return await _answer(bench.start_run, body.get("phase", "as-found"), resume=body.get("resume") is True,
                             test=body.get("test"), repeat=body.get("repeat") is True, claim=request)

    async def control(request: Request) -> Response:
        return await _answer(bench.control, request.path_params["action"], claim=request)

    async def results(request: Request) -> Response:
        return await _answer(bench.results, request.query_params.get("phase", "as-found"), request.query_params.get("test"))

    async def compensate(request: Request) -> Response:
        body = await _body(request)
        return await _answer(bench.compensate, body.get("axis") if isinstance(body, dict) else None, claim=request)

    # the visit's machine and its tests: the machines offered, each test's state, the tests taken from files
    async def machine_choices(request: Request) -> Response:
        return await _answer(bench.machine_choices)

    async def tests(request: Request) -> Response:
        return await _answer(bench.tests)

    async def data_files(request: Request) -> Response:
        return await _answer(bench.data_files)

    async def upload(request: Request) -> Response:
        content = await request.body()
        return await _answer(bench.upload, request.query_params.get("name"), content, claim=request)

    async def add_test(request: Request) -> Response:
        return await _answer(bench.add_file_test, await _body(request), claim=request)

    async def remove_test(request: Request) -> Response:
        body = await _body(request)
        return await _answer(bench.remove_test, body.get("test") if isinstance(body, dict) else None, claim=request)

    async def before_after(request: Request) -> Response:
        return await _answer(bench.before_after)

    async def finish(request: Request) -> Response:
        return await _answer(bench.finish, claim=request)

    async def files(request: Request) -> Response:
        try:
            path = bench.file(request.path_params["path"])
        except AxiscalError as exc:
            return JSONResponse({"error": str(exc)}, status_code=404)
        download = request.query_params.get("download") == "1"
        return FileResponse(path, filename=path.name if download else None,
                            content_disposition_type="attachment" if download else "inline")

    async def stream(websocket: WebSocket) -> None:
        await websocket.accept()
        tab = websocket.query_params.get("tab")
        tab = tab[:64] if tab else None
        if tab is not None:
            bench.tabs.attach(tab)
        try:
            await _stream(websocket)
        finally:
            if tab is not None:
                bench.tabs.detach(tab)

    async def _stream(websocket: WebSocket) -> None:
        current, cursor = None, 0
        loop = asyncio.get_running_loop()
        due = loop.time()
        try:
            while True:
                run_now = bench.run
                reset = run_now is not current
                if reset:
                    current, cursor = run_now, 0
                trace: dict[str, Any] = {"from": cursor, "t_s": [], "reading_mm": []}
                if run_now is not None:
                    t, x, after = run_now.samples_since(cursor)
                    trace = {"from": cursor, "t_s": [round(v, 4) for v in t.tolist()],
                             "reading_mm": [round(v, 7) for v in x.tolist()]}
                    cursor = after
                text = json.dumps(_json_safe({"run": bench.run_state(), "trace": trace, "reset": reset}), allow_nan=False)
                await websocket.send_text(text)
                due = max(due + interval, loop.time())  # on the beat; a late message is not made up for
                await asyncio.sleep(due - loop.time())
        except (WebSocketDisconnect, RuntimeError, OSError):
            return

    app = Starlette(
        routes=[
            Route("/", page),
            Route("/favicon.svg", icon),
            Route("/favicon.ico", icon),
            Route("/api/machines", machines),
            Route("/api/machine", machine),
            Route("/api/trend", trend),
            Route("/api/visit", visit, methods=["POST"]),
            Route("/api/state", state),
            Route("/api/visits", visits),
            Route("/api/certificate", certificate),
            Route("/api/budget", budget),
            Route("/api/visit/open", open_visit, methods=["POST"]),
            Route("/api/step", step, methods=["POST"]),
            Route("/api/plan", plan, methods=["POST"]),
            Route("/api/connect", connection, methods=["POST"]),
            Route("/api/ports", ports),
            Route("/api/run", run, methods=["GET", "POST"]),
            Route("/api/run/{action}", control, methods=["POST"]),
            Route("/api/results", results),
            Route("/api/compensate", compensate, methods=["POST"]),
            Route("/api/before-after", before_after),
            Route("/api/finish", finish, methods=["POST"]),
            Route("/api/machine-choices", machine_choices),
            Route("/api/tests", tests),
            Route("/api/data-files", data_files),
            Route("/api/upload", upload, methods=["POST"]),
            Route("/api/tests/add", add_test, methods=["POST"]),
            Route("/api/tests/remove", remove_test, methods=["POST"]),
            Route("/files/{path:path}", files),
            WebSocketRoute("/ws", stream),
            Mount("/static", StaticFiles(directory=WEB), name="static"),
        ],
        middleware=[Middleware(_Guard, allowed_hosts=None if allowed_hosts is None else tuple(allowed_hosts), token=token)],
    )
    app.state.bench = bench
    return app


def new_token() -> str:
    """A fresh session token for a workbench bound beyond loopback.

    Returns
    -------
    str
        24 URL-safe characters from the operating system's random source.
    """
    return secrets.token_urlsafe(18)
