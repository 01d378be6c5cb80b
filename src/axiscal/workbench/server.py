"""The workbench served: the app of :mod:`axiscal.workbench.app` on uvicorn, in a background thread."""

from __future__ import annotations

import contextlib
import threading
from dataclasses import dataclass
from pathlib import Path

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_number
from axiscal.live.server import LOOPBACK_HOSTS, LiveServer
from axiscal.workbench.app import create_workbench_app, new_token
from axiscal.workbench.visit import Workbench

__all__ = ["WorkbenchServer", "serve_workbench"]

_LOOPBACK_ADDRESSES = ("127.0.0.1", "localhost", "::1")


@dataclass
class WorkbenchServer:
    """A running workbench.

    Attributes
    ----------
    server : LiveServer
        uvicorn in its thread.
    bench : Workbench
        The visit and the history the page works on.
    token : str or None
        The token a browser must bring when the server listens beyond loopback.
    """

    server: LiveServer
    bench: Workbench
    token: str | None = None

    @property
    def url(self) -> str:
        """The page's address (with the token when one is needed)."""
        return self.server.url + ("" if self.token is None else f"?token={self.token}")

    def stop(self) -> None:
        """Stop serving (a run going on is aborted; its stops stay in the partial file)."""
        if self.bench.run is not None:
            self.bench.run.abort()
        self.server.stop()


def serve_workbench(
    data: str | Path,
    *,
    db: str | None = None,
    port: int = 8770,
    host: str = "127.0.0.1",
    speed: float = 1.0,
    update_hz: float = 20.0,
) -> WorkbenchServer:
    """Serve the workbench on ``host:port``: what ``axiscal workbench`` does.

    Parameters
    ----------
    data : str or Path
        The data folder (made when missing).
    db : str, optional, keyword-only
        The history database.
    port : int, keyword-only
        TCP port (default 8770; 0 picks a free one).
    host : str, keyword-only
        Address to listen on (default loopback). Any other asks every request for a token,
        given in :attr:`WorkbenchServer.url`.
    speed : float, keyword-only
        How many times faster than real time the virtual machine runs (default 1).
    update_hz : float, keyword-only
        Messages per second of the live stream (default 20).

    Returns
    -------
    WorkbenchServer
        Started.

    Raises
    ------
    AxiscalError
        For a data folder that cannot be made, a port in use, a bad host; for a history database
        that cannot be used (as the ``axiscal history`` commands refuse it: not a database, cut short,
        damaged, of a newer schema, another application's, a folder, an unknown URL or driver, a
        server that does not answer).
    """
    if not isinstance(host, str) or not host.strip():
        raise AxiscalError(f"host must be an address to listen on, not {host!r}")
    port = check_count("port", port, minimum=0, maximum=65535)
    update_hz = check_number("update_hz", update_hz, low=1.0, high=60.0, unit="Hz")
    bench = Workbench(data, db=db, speed=speed)
    bench.check_history()  # a history that cannot be used is refused now, in one line, not on the page later
    loopback = host.strip().lower() in _LOOPBACK_ADDRESSES or host.startswith("127.")
    token = None if loopback else new_token()
    if loopback:
        allowed: tuple[str, ...] | None = LOOPBACK_HOSTS + ((host,) if host not in LOOPBACK_HOSTS else ())
    else:
        allowed = None if host in ("0.0.0.0", "::") else LOOPBACK_HOSTS + (host.lower(),)
    app = create_workbench_app(bench, update_hz=update_hz, allowed_hosts=allowed, token=token)
    server = LiveServer(app, port=port, host=host).start()
    # the history's first reading imports SciPy's statistics for its trends (seconds on a cold machine):
    # done now, beside the server, so that the page's list of machines does not wait for it
    threading.Thread(target=_warm_up, args=(bench,), name="axiscal-workbench-warm-up", daemon=True).start()
    return WorkbenchServer(server, bench, token)


def _warm_up(bench: Workbench) -> None:
    with contextlib.suppress(AxiscalError):
        bench.machines()
