"""The live dashboard's server: a Starlette app on localhost pushing the latest state over a WebSocket.

One broadcaster task turns :meth:`LiveState.snapshot` into JSON ``update_hz`` times a second and
keeps only the newest (a version number and the text). Each WebSocket client has its own task that
waits for a version newer than the one it last sent and sends the newest text: a client that reads
slowly is sent fewer, later states -- the ones in between are skipped, nothing is queued for it,
and the pipeline (which only writes the state) never waits for any client.

Routes: ``/`` the page, ``/static/...`` its script and style (shipped in ``axiscal/live/web``),
``/api/config`` channels and axes, ``/api/state`` the newest state, ``/ws`` the stream.
Only the loopback interface is served.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import math
import socket
import threading
from dataclasses import dataclass
from pathlib import Path

import uvicorn
from starlette.applications import Starlette
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.websockets import WebSocket, WebSocketDisconnect

from axiscal.errors import AxiscalError
from axiscal.live.state import UPDATE_HZ_RANGE, LiveState

__all__ = ["WEB", "HOST", "ClientStats", "Broadcaster", "create_app", "LiveServer"]

WEB = Path(__file__).parent / "web"
HOST = "127.0.0.1"


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
    """

    def __init__(self, state: LiveState, *, update_hz: float = 10.0, title: str = "axiscal live"):
        low, high = UPDATE_HZ_RANGE
        if not (math.isfinite(update_hz) and low <= update_hz <= high):
            raise AxiscalError(f"update rate must be {low:g} to {high:g} per second, got {update_hz}")
        self.state = state
        self.interval_s = 1.0 / update_hz
        self.title = title
        self.version = 0
        self.text = "{}"
        self.clients: list[ClientStats] = []
        self._changed = asyncio.Condition()

    def refresh(self) -> None:
        self.text = json.dumps(self.state.snapshot() | {"version": self.version + 1, "title": self.title}, allow_nan=False)
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


def create_app(state: LiveState, *, update_hz: float = 10.0, title: str = "axiscal live") -> Starlette:
    """The dashboard app for ``state``.

    Parameters
    ----------
    state : LiveState
        What the page shows.
    update_hz : float, keyword-only
        Refreshes per second.
    title : str, keyword-only
        The page's title.

    Returns
    -------
    Starlette
        The app; its broadcaster is ``app.state.broadcaster``.

    Raises
    ------
    AxiscalError
        If ``update_hz`` is not positive.
    """
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
    )
    app.state.broadcaster = broadcaster
    return app


class LiveServer:
    """uvicorn serving an app on 127.0.0.1 from a background thread.

    Parameters
    ----------
    app : Starlette
        From :func:`create_app`.
    port : int
        TCP port; 0 picks a free one (see :attr:`port` after :meth:`start`).
    """

    def __init__(self, app: Starlette, *, port: int = 8765):
        self.app = app
        config = uvicorn.Config(
            app, host=HOST, port=port, log_level="warning", lifespan="on", ws_per_message_deflate=False, timeout_graceful_shutdown=1
        )
        self._server = uvicorn.Server(config)
        self._socket: socket.socket | None = None
        self._thread = threading.Thread(target=self._serve, name="axiscal-live-server", daemon=True)
        self.port = port

    def _serve(self) -> None:
        self._server.run(sockets=[self._socket])

    @property
    def url(self) -> str:
        return f"http://{HOST}:{self.port}/"

    def start(self, *, timeout_s: float = 10.0) -> "LiveServer":
        """Start serving; return once the socket listens (raise AxiscalError if it cannot)."""
        self._socket = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self._socket.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            self._socket.bind((HOST, self.port))
        except OSError as exc:
            self._socket.close()
            raise AxiscalError(f"the dashboard cannot listen on {HOST}:{self.port} ({exc.strerror}); choose another --port") from None
        self.port = self._socket.getsockname()[1]
        self._thread.start()
        waited = 0.0
        while not self._server.started and self._thread.is_alive() and waited < timeout_s:
            self._thread.join(0.01)
            waited += 0.01
        if not self._server.started:
            self.stop()
            raise AxiscalError(f"the dashboard server on {HOST}:{self.port} did not start")
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
