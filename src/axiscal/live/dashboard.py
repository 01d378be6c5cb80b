"""The live dashboard served by a process of its own, fed the processed batches through a pipe.

In the loop's process the dashboard's server (:mod:`axiscal.live.server`) needs the interpreter lock
to fold the batches, make the state's JSON and send it: while it holds the lock the loop waits, and
its frames are late. :class:`DashboardProcess` runs the same app in another Python process, with a
:class:`~axiscal.live.state.LiveState` of its own laid out as the loop's. The loop's state, once the
process is started, writes each batch it is given to a pipe as raw arrays (one ``os.write`` that
never waits: a full pipe keeps the bytes in a bounded backlog, written with the next batch) and
keeps only the frame and fault counts; the process reads the pipe, folds the batches and serves
the page, the API and the WebSocket exactly as :func:`~axiscal.live.server.create_app` does.

The process runs at normal priority whatever the loop's: at real-time priority it would take from
the loop the real-time time the kernel allows each second (95 %), shared by every real-time thread,
and a page drawn late costs nothing. It ends when the pipe is closed: by :meth:`DashboardProcess.stop`, or
by the end of the loop's process, however it ends.
"""

from __future__ import annotations

import fcntl
import json
import logging
import math
import os
import select
import socket
import struct
import subprocess
import sys
import threading
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, is_real, type_name
from axiscal.live.protocol import FrameBatch
from axiscal.live.state import UPDATE_HZ_RANGE, LiveState

__all__ = ["BACKLOG_BYTES", "DashboardProcess"]

#: bytes of batches the loop keeps for a dashboard process that reads slowly (about 3 s at 10 kHz); batches beyond are left out of the dashboard
BACKLOG_BYTES = 8 << 20
_NAMES, _BATCH, _EXTRA = 1, 2, 3
_HEAD = struct.Struct("<BI")
_COUNT = struct.Struct("<I")
_PIPE_BYTES = 1 << 20
_F_SETPIPE_SZ = 1031


class _Feed:
    """The loop's end of the pipe: messages written without ever waiting, a bounded backlog kept."""

    def __init__(self, fd: int):
        self.fd = fd
        self.backlog = bytearray()
        self.layout: tuple[tuple[str, ...], tuple[np.dtype, ...]] = ((), ())
        self._floats: list[int] = []
        self._others: list[int] = []
        self.left_out = 0
        self.closed = False
        self.gone = False  # the process stopped reading for good
        self._lock = threading.Lock()  # a close from another thread never meets a write (the fd's number could be reused)

    def batch(self, batch: FrameBatch, fault: np.ndarray, results: Mapping[str, np.ndarray]) -> None:
        """Write one batch: its time stamps, readings and float results as one block, the rest after it.

        A dozen calls whatever the number of columns: the loop pays about 0.1 ms a batch for it.
        """
        columns = list(results.values())
        layout = (tuple(results), tuple(column.dtype for column in columns))
        if layout != self.layout:
            self.layout = layout
            self._floats = [i for i, dtype in enumerate(layout[1]) if dtype == np.float64]
            self._others = [i for i, dtype in enumerate(layout[1]) if dtype != np.float64]
            self._put(_NAMES, json.dumps([[name, dtype.str] for name, dtype in zip(*layout)]).encode())
        if len(self.backlog) > BACKLOG_BYTES:
            self.left_out += len(batch)
            self.flush()
            return
        n = len(batch)
        block = np.concatenate((np.reshape(batch.t_s, (1, n)), np.transpose(batch.values),
                                np.reshape([columns[i] for i in self._floats], (len(self._floats), n))), dtype=np.float64)
        parts = [_COUNT.pack(n), block.tobytes(), batch.malformed.astype(bool).tobytes(), fault.astype(np.int64).tobytes()]
        parts.extend(columns[i].tobytes() for i in self._others)
        self._put(_BATCH, b"".join(parts))

    def extra(self, value: dict[str, Any]) -> None:
        self._put(_EXTRA, json.dumps(value).encode())

    def _put(self, kind: int, payload: bytes) -> None:
        with self._lock:
            if self.closed or self.gone:
                return
            self.backlog += _HEAD.pack(kind, len(payload))
            self.backlog += payload
            self._flush()

    def flush(self) -> None:
        with self._lock:
            self._flush()

    def close(self) -> None:
        with self._lock:
            if not self.closed:
                self.closed = True
                os.close(self.fd)
            self.backlog.clear()

    def _flush(self) -> None:
        while self.backlog and not self.closed:
            try:
                written = os.write(self.fd, self.backlog)
            except BlockingIOError:
                return
            except OSError:  # the process is gone: nothing more to show
                self.gone = True
                self.backlog.clear()
                return
            del self.backlog[:written]


def _read_exactly(stream, size: int) -> bytes | None:
    data = stream.read(size)
    return data if len(data) == size else None


def _read_feed(stream, state: LiveState) -> None:
    """In the dashboard's process: fold every batch the pipe brings into ``state`` until it is closed."""
    width = len(state.channels)
    names: list[str] = []
    floats: list[int] = []
    others: list[tuple[int, np.dtype]] = []
    while (head := _read_exactly(stream, _HEAD.size)) is not None:
        kind, size = _HEAD.unpack(head)
        payload = _read_exactly(stream, size)
        if payload is None:
            return
        if kind == _NAMES:
            layout = [(name, np.dtype(code)) for name, code in json.loads(payload)]
            names = [name for name, _ in layout]
            floats = [i for i, (_, dtype) in enumerate(layout) if dtype == np.float64]
            others = [(i, dtype) for i, (_, dtype) in enumerate(layout) if dtype != np.float64]
        elif kind == _EXTRA:
            state.extra = json.loads(payload)
        elif kind == _BATCH:
            (n,) = _COUNT.unpack_from(payload)
            rows = 1 + width + len(floats)
            offset = _COUNT.size
            block = np.frombuffer(payload, dtype=np.float64, count=rows * n, offset=offset).reshape(rows, n)
            offset += block.nbytes
            malformed = np.frombuffer(payload, dtype=bool, count=n, offset=offset)
            fault = np.frombuffer(payload, dtype=np.int64, count=n, offset=offset + n)
            offset += 9 * n
            columns: list[np.ndarray] = [np.empty(0)] * len(names)
            for row, i in enumerate(floats):
                columns[i] = block[1 + width + row]
            for i, dtype in others:
                columns[i] = np.frombuffer(payload, dtype=dtype, count=n, offset=offset)
                offset += n * dtype.itemsize
            batch = FrameBatch(block[0], block[1 : 1 + width].T, malformed)
            state.update(batch, fault, dict(zip(names, columns)))


class DashboardProcess:
    """The dashboard of ``state`` served by a process of its own, on 127.0.0.1 unless told otherwise.

    Parameters
    ----------
    state : LiveState
        The loop's state; from :meth:`start` to :meth:`stop` its batches go to the process.
    port : int, keyword-only
        TCP port; 0 picks a free one (see :attr:`port` after :meth:`start`).
    host : str, keyword-only
        Address to listen on (IPv4). Anything but loopback exposes the dashboard to every computer
        that reaches this one (docs/live.md).
    update_hz : float, keyword-only
        Refreshes per second.
    title : str, keyword-only
        The page's title.
    allowed_hosts : sequence of str, keyword-only
        Host names allowed besides the loopback names (see :func:`~axiscal.live.server.create_app`).

    Attributes
    ----------
    port : int
        The port listened on.

    Raises
    ------
    AxiscalError
        For a ``state`` that is not a :class:`LiveState`, a ``port`` outside 0-65535, an empty
        ``host``, an ``update_hz`` outside :data:`~axiscal.live.state.UPDATE_HZ_RANGE`, a bad host
        name; :meth:`start` when the port cannot be listened on or the process does not start.
    """

    def __init__(self, state: LiveState, *, port: int = 8765, host: str = "127.0.0.1", update_hz: float = 10.0,
                 title: str = "axiscal live", allowed_hosts: Sequence[str] = ()):
        from axiscal.live.server import _checked_hosts

        check_instance("state", state, LiveState)
        port = check_count("port", port, minimum=0, maximum=65535)
        if not isinstance(host, str) or not host.strip():
            raise AxiscalError(f"host must be an address to listen on, not {host!r}")
        low, high = UPDATE_HZ_RANGE
        if not (is_real(update_hz) and math.isfinite(update_hz) and low <= update_hz <= high):
            raise AxiscalError(f"update_hz: the update rate must be {low:g} to {high:g} per second, not {update_hz!r}")
        if not isinstance(title, str):
            raise AxiscalError(f"title must be a str, not {type_name(title)}")
        self.state = state
        self.host = host
        self.port = port
        self._settings = {"update_hz": update_hz, "title": title, "allowed_hosts": list(_checked_hosts(allowed_hosts))}
        self._process: subprocess.Popen | None = None
        self._feed: _Feed | None = None

    @property
    def url(self) -> str:
        """The page's address."""
        return f"http://{'127.0.0.1' if self.host == '0.0.0.0' else self.host}:{self.port}/"

    def start(self, *, timeout_s: float = 30.0) -> "DashboardProcess":
        """Start the process; return once it listens (raise AxiscalError if it cannot)."""
        listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            listener.bind((self.host, self.port))
        except (OSError, OverflowError) as exc:
            listener.close()
            reason = getattr(exc, "strerror", None) or exc
            raise AxiscalError(f"the dashboard cannot listen on {self.host}:{self.port} ({reason}); choose another port or host") from None
        self.port = listener.getsockname()[1]
        read_end, write_end = os.pipe()
        try:
            try:
                fcntl.fcntl(write_end, _F_SETPIPE_SZ, _PIPE_BYTES)
            except OSError:  # a system that keeps its pipes smaller: the backlog takes the rest
                pass
            settings = self._settings | {"host": self.host, "port": self.port, "socket_fd": listener.fileno(), "feed_fd": read_end,
                                         "layout": self.state._layout}
            # the process imports this very axiscal, however this one was found
            here = str(Path(__file__).resolve().parents[2])
            env = os.environ | {"PYTHONPATH": os.pathsep.join(filter(None, (here, os.environ.get("PYTHONPATH"))))}
            self._process = subprocess.Popen(
                [sys.executable, "-c", _LAUNCH, json.dumps(settings)],
                env=env,
                pass_fds=(listener.fileno(), read_end),
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                start_new_session=True,  # Ctrl-C is the loop's to handle: it closes the pipe, and the process ends
            )
        except BaseException:
            os.close(write_end)
            raise
        finally:
            os.close(read_end)
            listener.close()
        os.set_blocking(write_end, False)
        self._feed = _Feed(write_end)
        if not self._started(timeout_s):
            self.stop()
            raise AxiscalError(f"the dashboard server on {self.host}:{self.port} did not start")
        self.state._feed = self._feed
        self._feed.extra(self.state.extra)
        return self

    def _started(self, timeout_s: float) -> bool:
        """Whether the process said it listens within ``timeout_s``."""
        ready, _, _ = select.select([self._process.stdout], [], [], timeout_s)
        return bool(ready) and self._process.stdout.readline().strip() == b"listening"

    def stop(self, *, timeout_s: float = 5.0) -> None:
        """Stop feeding and serving (safe to call twice): the pipe is closed, the process ends within ``timeout_s``."""
        if self._feed is None:
            return
        if self.state._feed is self._feed:
            self.state._feed = None
        feed, self._feed = self._feed, None
        feed.close()
        process = self._process
        try:
            process.wait(timeout_s)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
        process.stdout.close()

    def __enter__(self) -> "DashboardProcess":
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()


#: the process's first lines: it drops the real-time priority (or the lower nice value) the loop's
#: thread passed on before anything else, so that neither its imports (a second or more of a core) nor
#: its work take a core, or the real-time time the kernel allows, from the loop
_LAUNCH = (
    "import os, sys\n"
    "if os.sched_getscheduler(0) in (os.SCHED_FIFO, os.SCHED_RR):\n"
    "    os.sched_setscheduler(0, os.SCHED_OTHER, os.sched_param(0))\n"
    "if os.getpriority(os.PRIO_PROCESS, 0) < 0:\n"
    "    os.setpriority(os.PRIO_PROCESS, 0, 0)\n"
    "from axiscal.live.dashboard import _serve\n"
    "_serve(sys.argv[1])\n"
)


def _serve(text: str) -> None:
    """The dashboard's process: build its state, read the pipe in a thread, serve until the pipe is closed."""
    from axiscal.live.server import _uvicorn_server, create_app

    settings = json.loads(text)
    state = LiveState._from_layout(settings["layout"])
    app = create_app(state, update_hz=settings["update_hz"], title=settings["title"], allowed_hosts=settings["allowed_hosts"])
    server = _uvicorn_server(app, settings["host"], settings["port"])
    listener = socket.socket(fileno=settings["socket_fd"])

    def feed() -> None:
        with open(settings["feed_fd"], "rb", buffering=_PIPE_BYTES) as stream:
            _read_feed(stream, state)
        logging.getLogger("uvicorn.error").setLevel(logging.CRITICAL)  # a client that stopped reading is dropped quietly
        server.should_exit = True

    def announce() -> None:
        while not server.started and not server.should_exit:
            time.sleep(0.01)
        if server.started:
            sys.stdout.write("listening\n")
            sys.stdout.flush()
            with open(os.devnull, "wb") as nowhere:  # nobody reads the pipe any more: nothing may wait on it
                os.dup2(nowhere.fileno(), sys.stdout.fileno())

    threading.Thread(target=feed, name="axiscal-dashboard-feed", daemon=True).start()
    threading.Thread(target=announce, name="axiscal-dashboard-ready", daemon=True).start()
    server.run(sockets=[listener])

