"""The live dashboard's server: a Starlette app on localhost pushing the latest state over a WebSocket.

One broadcaster task turns :meth:`LiveState.snapshot` into JSON ``update_hz`` times a second and
keeps only the newest (a version number and the text). Each WebSocket client has its own task that
waits for a version newer than the one it last sent and sends the newest text: a client that reads
slowly is sent fewer, later states -- the ones in between are skipped, nothing is queued for it,
and the pipeline (which only writes the state) never waits for any client.

Routes: ``/`` the page, ``/static/...`` its script and style (shipped in ``axiscal/live/web``),
``/api/config`` channels and axes, ``/api/state`` the newest state, ``/ws`` the stream.
The loopback interface is served unless another address is given.

A web page the user opens elsewhere must not read the stream: every request (page, API and
WebSocket) is refused with 403 unless its ``Host`` header names an allowed host (the loopback
names :data:`LOOPBACK_HOSTS`, plus those given) -- so a DNS-rebound name pointing at 127.0.0.1 is
refused -- and, when it carries an ``Origin`` (browsers send it on a WebSocket and on cross-site
requests), that origin is the dashboard's own (``http://`` and the same host and port).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import math
import socket
import threading
from collections.abc import Sequence
from typing import Any
from dataclasses import dataclass
from pathlib import Path

import uvicorn
from starlette.applications import Starlette
from starlette.middleware import Middleware
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.websockets import WebSocket, WebSocketDisconnect

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_mapping, is_real
from axiscal.live.priority import below_the_loop
from axiscal.io.arguments import check_instance, type_name
from axiscal.live.state import UPDATE_HZ_RANGE, LiveState

__all__ = ["WEB", "HOST", "LOOPBACK_HOSTS", "ClientStats", "Broadcaster", "request_allowed", "create_app", "create_board_app",
           "LiveServer"]

WEB = Path(__file__).parent / "web"
HOST = "127.0.0.1"
#: host names a request may name by default (without the port)
LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "[::1]")


def _host_name(host: str) -> str:
    """A ``Host`` value without its port, lower case (``[::1]:8765`` -> ``[::1]``)."""
    host = host.strip().lower()
    if host.startswith("["):
        return host[: host.find("]") + 1] if "]" in host else host
    return host.rsplit(":", 1)[0] if host.count(":") == 1 else host


def request_allowed(headers: dict[str, str], allowed_hosts: tuple[str, ...] = LOOPBACK_HOSTS) -> bool:
    """Whether a request to the dashboard may be answered: an allowed Host, and no Origin but its own.

    Parameters
    ----------
    headers : dict of str to str
        The request's headers, names in lower case.
    allowed_hosts : tuple of str
        Host names allowed (lower case, without port; IPv6 in brackets).

    Returns
    -------
    bool
        True when ``Host`` names an allowed host and ``Origin`` is absent or ``http://`` plus
        exactly that ``Host``.

    Raises
    ------
    AxiscalError
        For ``headers`` that is not a mapping or ``allowed_hosts`` that is not a tuple of
        names.

    Examples
    --------
    >>> request_allowed({"host": "127.0.0.1:8765", "origin": "http://127.0.0.1:8765"})
    True
    >>> request_allowed({"host": "evil.example:8765"})
    False
    >>> request_allowed({"host": "localhost:8765", "origin": "http://evil.example"})
    False
    """
    check_mapping("headers", headers, what="the request's headers (a mapping)")
    if isinstance(allowed_hosts, str) or not isinstance(allowed_hosts, (tuple, list, frozenset, set)):
        raise AxiscalError(f"allowed_hosts must be a tuple of host names, not {allowed_hosts!r}")
    host = headers.get("host", "")
    if not isinstance(host, str) or not host or _host_name(host) not in allowed_hosts:
        return False
    origin = headers.get("origin")
    return origin is None or isinstance(origin, str) and origin.strip().lower() == f"http://{host.strip().lower()}"


def _json_in_parts(value: Any) -> str:
    """``json.dumps(value, allow_nan=False)``, the same text, made one list or scalar at a time.

    One ``json.dumps`` of a whole state (19 kB) is one call into C of about 1.3 ms that holds the
    interpreter lock throughout: the live loop, which needs the lock to record its next batch, waited
    for it. Made a dictionary entry at a time, the lock can pass to the loop between two lists.
    """
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(str(key))}: {_json_in_parts(item)}" for key, item in value.items()) + "}"
    return json.dumps(value, allow_nan=False)


class _GuardHosts:
    """ASGI middleware answering 403 to a request :func:`request_allowed` refuses (HTTP and WebSocket)."""

    def __init__(self, app, allowed_hosts: tuple[str, ...]):
        self.app = app
        self.allowed_hosts = allowed_hosts

    async def __call__(self, scope, receive, send) -> None:
        if scope["type"] in ("http", "websocket"):
            headers = {name.decode("latin-1").lower(): value.decode("latin-1") for name, value in scope["headers"]}
            if not request_allowed(headers, self.allowed_hosts):
                if scope["type"] == "websocket":
                    await send({"type": "websocket.close", "code": 1008})  # before accept: the handshake gets 403
                    return
                await send({"type": "http.response.start", "status": 403, "headers": [(b"content-type", b"text/plain")]})
                await send({"type": "http.response.body", "body": b"forbidden: host or origin not allowed\n"})
                return
        await self.app(scope, receive, send)


@dataclass
class ClientStats:
    """Per-client counters of the dashboard's WebSocket.

    Attributes
    ----------
    sent : int
        States sent.
    skipped : int
        States skipped because the client was still busy.
    version : int
        Version of the last state sent (the newest is ``Broadcaster.version``).
    """

    sent: int = 0
    skipped: int = 0
    version: int = 0


class Broadcaster:
    """Holds the newest state as JSON text; clients wait for a newer version than the one they have.

    The state is turned into JSON only while a client is connected (or ``/api/state`` asks), so a
    dashboard nobody watches costs the pipeline nothing.

    Parameters
    ----------
    state : LiveState
        What is shown.
    update_hz : float, keyword-only
        Refreshes per second.
    title : str, keyword-only
        The page's title.

    Raises
    ------
    AxiscalError
        For a ``state`` that is not a :class:`LiveState`, an ``update_hz`` outside
        :data:`~axiscal.live.state.UPDATE_HZ_RANGE`, a ``title`` that is not a str.
    """

    def __init__(self, state: LiveState, *, update_hz: float = 10.0, title: str = "axiscal live"):
        low, high = UPDATE_HZ_RANGE
        if not (is_real(update_hz) and math.isfinite(update_hz) and low <= update_hz <= high):
            raise AxiscalError(f"update_hz: the update rate must be {low:g} to {high:g} per second, not {update_hz!r}")
        check_instance("state", state, LiveState)
        if not isinstance(title, str):
            raise AxiscalError(f"title must be a str, not {type_name(title)}")
        self.state = state
        self.interval_s = 1.0 / update_hz
        self.title = title
        self.version = 0
        self.text = "{}"
        self.clients: list[ClientStats] = []
        self._changed = asyncio.Condition()

    def refresh(self) -> None:
        self.text = _json_in_parts(self.state.snapshot() | {"version": self.version + 1, "title": self.title})
        self.version += 1

    async def run(self) -> None:
        while True:
            if self.clients:
                self.refresh()
                async with self._changed:
                    self._changed.notify_all()
            await asyncio.sleep(self.interval_s)

    async def newer_than(self, version: int) -> tuple[int, str]:
        async with self._changed:
            await self._changed.wait_for(lambda: self.version > version)
        return self.version, self.text


def create_app(
    state: LiveState, *, update_hz: float = 10.0, title: str = "axiscal live", allowed_hosts: Sequence[str] = ()
) -> Starlette:
    """The dashboard app for ``state``.

    Parameters
    ----------
    state : LiveState
        What the page shows.
    update_hz : float, keyword-only
        Refreshes per second.
    title : str, keyword-only
        The page's title.
    allowed_hosts : sequence of str, keyword-only
        Host names allowed besides :data:`LOOPBACK_HOSTS` (as a browser sends them in ``Host``,
        without port), e.g. the machine's name when the server listens on another interface.

    Returns
    -------
    Starlette
        The app; its broadcaster is ``app.state.broadcaster``.

    Raises
    ------
    AxiscalError
        If ``update_hz`` is outside :data:`~axiscal.live.state.UPDATE_HZ_RANGE` or a host name is
        empty or holds a port.
    """
    check_instance("state", state, LiveState)
    extra = _checked_hosts(allowed_hosts)
    broadcaster = Broadcaster(state, update_hz=update_hz, title=title)

    @contextlib.asynccontextmanager
    async def lifespan(app: Starlette):
        task = asyncio.create_task(broadcaster.run())
        try:
            yield
        finally:
            task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await task

    async def page(request) -> Response:
        return FileResponse(WEB / "index.html", media_type="text/html")

    async def config(request) -> Response:
        return JSONResponse({"title": title, "channels": list(state.channels), "axes": list(state.axes), "update_hz": update_hz})

    async def latest(request) -> Response:
        if not broadcaster.clients:
            broadcaster.refresh()
        return Response(broadcaster.text, media_type="application/json")

    async def stream(websocket: WebSocket) -> None:
        await websocket.accept()
        stats = ClientStats()
        broadcaster.clients.append(stats)
        broadcaster.refresh()
        try:
            while True:
                version, text = await broadcaster.newer_than(stats.version)
                if stats.version:
                    stats.skipped += version - stats.version - 1
                await websocket.send_text(text)
                stats.sent += 1
                stats.version = version
        except (WebSocketDisconnect, RuntimeError, OSError):
            return
        finally:
            broadcaster.clients.remove(stats)

    app = Starlette(
        routes=[
            Route("/", page),
            Route("/api/config", config),
            Route("/api/state", latest),
            WebSocketRoute("/ws", stream),
            Mount("/static", StaticFiles(directory=WEB), name="static"),
        ],
        lifespan=lifespan,
        middleware=[Middleware(_GuardHosts, allowed_hosts=LOOPBACK_HOSTS + extra)],
    )
    app.state.broadcaster = broadcaster
    return app


def _checked_hosts(allowed_hosts: Sequence[str]) -> tuple[str, ...]:
    if isinstance(allowed_hosts, str) or not isinstance(allowed_hosts, (tuple, list, frozenset, set)):
        raise AxiscalError(f"allowed_hosts must be a sequence of host names, not {allowed_hosts!r}")
    if not all(isinstance(name, str) for name in allowed_hosts):
        raise AxiscalError(f"allowed_hosts must hold host names (str), not {tuple(allowed_hosts)!r}")
    extra = tuple(name.strip().lower() for name in allowed_hosts)
    for name in extra:
        if not name or "/" in name or (":" in name and not name.startswith("[")):
            raise AxiscalError(f"allowed host '{name}' must be a host name or address without port or scheme")
    return extra


def create_board_app(snapshot, *, page: str, allowed_hosts: Sequence[str] = ()) -> Starlette:
    """A page that polls ``/api/state`` for what ``snapshot()`` returns (the capture's board).

    Parameters
    ----------
    snapshot : callable
        Returns the state as a JSON-able mapping; called from the server's thread, so it must
        return a value the writer replaces whole (never one it changes in place).
    page : str
        The page's file in ``axiscal/live/web`` (``capture.html``).
    allowed_hosts : sequence of str, keyword-only
        Host names allowed besides :data:`LOOPBACK_HOSTS` (see :func:`create_app`).

    Returns
    -------
    Starlette

    Raises
    ------
    AxiscalError
        For a ``snapshot`` that is not callable, a page that is not shipped, or a bad host name.
    """
    if not callable(snapshot):
        raise AxiscalError(f"snapshot must be a function returning the state, not {type_name(snapshot)}")
    if not isinstance(page, str) or not (WEB / page).is_file():
        raise AxiscalError(f"page must name a page of axiscal/live/web, not {page!r}")
    extra = _checked_hosts(allowed_hosts)

    async def index(request) -> Response:
        return FileResponse(WEB / page, media_type="text/html")

    async def latest(request) -> Response:
        return Response(json.dumps(snapshot(), allow_nan=False), media_type="application/json")

    return Starlette(
        routes=[Route("/", index), Route("/api/state", latest), Mount("/static", StaticFiles(directory=WEB), name="static")],
        middleware=[Middleware(_GuardHosts, allowed_hosts=LOOPBACK_HOSTS + extra)],
    )


def _uvicorn_server(app: Starlette, host: str, port: int) -> uvicorn.Server:
    """The uvicorn server of a dashboard: quiet, no compression, 1 s to close its connections politely."""
    config = uvicorn.Config(
        app, host=host, port=port, log_level="warning", lifespan="on", ws_per_message_deflate=False, timeout_graceful_shutdown=1
    )
    return uvicorn.Server(config)


class LiveServer:
    """uvicorn serving an app from a background thread, on 127.0.0.1 unless told otherwise.

    Parameters
    ----------
    app : Starlette
        From :func:`create_app`.
    port : int
        TCP port; 0 picks a free one (see :attr:`port` after :meth:`start`).
    host : str
        Address to listen on (IPv4). Anything but loopback exposes the dashboard and its stream to
        every computer that reaches this one (docs/live.md).

    Raises
    ------
    AxiscalError
        For an ``app`` that is not a Starlette app, a ``port`` outside 0-65535, an empty
        ``host``.
    """

    def __init__(self, app: Starlette, *, port: int = 8765, host: str = HOST):
        check_instance("app", app, Starlette, what="the Starlette app create_app returns")
        port = check_count("port", port, minimum=0, maximum=65535)
        if not isinstance(host, str) or not host.strip():
            raise AxiscalError(f"host must be an address to listen on, not {host!r}")
        self.app = app
        self.host = host
        self._server = _uvicorn_server(app, host, port)
        self._socket: socket.socket | None = None
        self._thread = threading.Thread(target=self._serve, name="axiscal-live-server", daemon=True)
        self.port = port

    def _serve(self) -> None:
        below_the_loop()
        self._server.run(sockets=[self._socket])

    @property
    def url(self) -> str:
        return f"http://{HOST if self.host == '0.0.0.0' else self.host}:{self.port}/"

    def start(self, *, timeout_s: float = 10.0) -> "LiveServer":
        """Start serving; return once the socket listens (raise AxiscalError if it cannot)."""
        self._socket = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self._socket.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            self._socket.bind((self.host, self.port))
        except (OSError, OverflowError) as exc:
            self._socket.close()
            reason = getattr(exc, "strerror", None) or exc
            raise AxiscalError(f"the dashboard cannot listen on {self.host}:{self.port} ({reason}); choose another port or host") from None
        self.port = self._socket.getsockname()[1]
        self._thread.start()
        waited = 0.0
        while not self._server.started and self._thread.is_alive() and waited < timeout_s:
            self._thread.join(0.01)
            waited += 0.01
        if not self._server.started:
            self.stop()
            raise AxiscalError(f"the dashboard server on {self.host}:{self.port} did not start")
        return self

    def stop(self, *, timeout_s: float = 5.0) -> None:
        """Stop serving. A client that stopped reading cannot be closed politely: after the graceful
        period (1 s) its connection is dropped; uvicorn's error lines about that are not shown."""
        logging.getLogger("uvicorn.error").setLevel(logging.CRITICAL)
        self._server.should_exit = True
        if self._thread.is_alive():
            self._thread.join(timeout_s)
        if self._thread.is_alive():
            self._server.force_exit = True
            self._thread.join(timeout_s)
        if self._socket is not None:
            self._socket.close()

    def __enter__(self) -> "LiveServer":
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()
