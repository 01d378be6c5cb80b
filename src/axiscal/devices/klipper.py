"""Klipper, through its API socket (``klippy.py printer.cfg -a /tmp/klippy_uds``), and Moonraker over HTTP.

Sources: Klipper's "API server" document (klipper3d.org/API_Server.html) and Moonraker's
"Printer Administration" API (moonraker.readthedocs.io). Klipper takes JSON objects ended by the byte
0x03 on a Unix socket: ``{"id": 1, "method": "gcode/script", "params": {"script": "G90\\nG1 X10 F600\\nM400"}}``
is answered ``{"id": 1, "result": {}}`` once the script has run (M400: the move has ended), or
``{"id": 1, "error": {"message": "Must home axis first: ..."}}``. ``objects/query`` with
``{"objects": {"toolhead": ["position", "homed_axes", "axis_minimum", "axis_maximum"]}}`` answers the
position, the homed axes and the soft limits; ``emergency_stop`` stops at once (Ctrl-C: Klipper has no feed
hold; it then needs a FIRMWARE_RESTART). Moonraker offers the same on HTTP: ``POST
/printer/gcode/script``, ``GET /printer/objects/query``, ``POST /printer/emergency_stop``. In both, a
second connection asks the position every 0.2 s while a move runs (the heartbeat: silence for 2 s ends
the run).
"""

from __future__ import annotations

from abc import abstractmethod

import errno
import http.client
import json
import socket
import time
import urllib.parse

from axiscal.devices.controller import SILENCE_S, Controller, Heartbeat, move_words
from axiscal.devices.links import close_now, recv_before
from axiscal.errors import AxiscalError

__all__ = ["KlipperController", "MoonrakerController", "KlipperSocket"]

_AXES = "XYZ"


class KlipperSocket:
    """One connection to Klipper's API socket.

    Parameters
    ----------
    path : str
        The Unix socket (``/tmp/klippy_uds``).
    """

    def __init__(self, path: str):
        self.path = path
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            self.sock.connect(path)
        except OSError as exc:
            self.sock.close()
            raise AxiscalError(f"cannot reach Klipper's API socket {path}: {exc.strerror or exc} (start klippy with -a {path})") from None
        self._buffer = b""
        self._id = 0

    def call(self, method: str, params: dict, *, timeout_s: float | None) -> dict:
        """Send a request and return its reply object (``result`` or ``error``)."""
        self._id += 1
        ident = self._id
        self.sock.sendall(json.dumps({"id": ident, "method": method, "params": params}).encode() + b"\x03")
        deadline = None if timeout_s is None else time.monotonic() + timeout_s
        while True:
            while b"\x03" in self._buffer:
                raw, self._buffer = self._buffer.split(b"\x03", 1)
                try:
                    message = json.loads(raw.decode("utf-8"))
                except ValueError:
                    continue
                if isinstance(message, dict) and message.get("id") == ident:
                    return message
            self._buffer += recv_before(self.sock, deadline, f"Klipper's API socket ({method})")

    def close(self) -> None:
        """Close the connection; a reply awaited on another thread ends at once (shutdown wakes it)."""
        close_now(self.sock)


class _ToolheadController(Controller):
    """What Klipper and Moonraker share: a script call, a query of the toolhead, an emergency stop."""

    @abstractmethod
    def _script(self, script: str, *, timeout_s: float | None, main: bool) -> dict:
        """Run a G-code script; the reply object."""

    @abstractmethod
    def _query(self, *, timeout_s: float) -> dict:
        """The toolhead's status object."""

    def _toolhead(self) -> dict:
        try:
            return self._query(timeout_s=SILENCE_S)
        except OSError as exc:
            raise self.lost(str(exc)) from None

    def check_ready(self, axis: str) -> None:
        if axis.upper() not in _AXES:
            raise AxiscalError(f"axis must be X, Y or Z, not {axis!r}")
        toolhead = self._toolhead()
        if axis.lower() not in str(toolhead.get("homed_axes", "")):
            raise AxiscalError(f"{self.description}: axis {axis.upper()} is not homed (homed: {toolhead.get('homed_axes') or 'none'}):"
                               " home it first (axiscal run never homes)")
        self.status.position_m = float(toolhead["position"][_AXES.index(axis.upper())]) * 1e-3

    def limits(self, axis: str) -> tuple[float, float] | None:
        toolhead = self._toolhead()
        try:
            i = _AXES.index(axis.upper())
            return float(toolhead["axis_minimum"][i]) * 1e-3, float(toolhead["axis_maximum"][i]) * 1e-3
        except (KeyError, IndexError, TypeError, ValueError):
            return None

    def position(self, axis: str) -> float:
        return float(self._query(timeout_s=0.3)["position"][_AXES.index(axis.upper())]) * 1e-3

    def move_to(self, axis: str, position_m: float, feed_m_per_s: float) -> None:
        axis = axis.upper()
        script = f"G90\nG1 {move_words(axis, position_m, feed_m_per_s)}\nM400"
        self.status.state = "moving"
        with Heartbeat(lambda: self.position(axis), lambda reason: self._abandon(), period_s=0.2) as beat:
            try:
                reply = self._script(script, timeout_s=None, main=True)
            except OSError as exc:
                raise self.lost(beat.failed or str(exc)) from None
        if beat.failed:
            raise self.lost(beat.failed)
        if "error" in reply:
            error = reply["error"]
            message = error.get("message", error) if isinstance(error, dict) else error
            raise AxiscalError(f"{self.description} refused the move to {axis} {position_m * 1e3:.4f} mm: {message}")
        self.status.state = "idle"
        self.status.position_m = position_m

    @abstractmethod
    def _abandon(self) -> None:
        """Unblock a script call awaited on another thread."""


class KlipperController(_ToolheadController):
    """Klipper through its API socket.

    Parameters
    ----------
    path : str
        The API socket.
    """

    def __init__(self, path: str):
        self.description = f"Klipper at {path}"
        super().__init__()
        self.main = KlipperSocket(path)
        self.watch = KlipperSocket(path)

    def _script(self, script, *, timeout_s, main):
        return (self.main if main else self.watch).call("gcode/script", {"script": script}, timeout_s=timeout_s)

    def _query(self, *, timeout_s):
        reply = self.watch.call("objects/query", {"objects": {"toolhead": ["position", "homed_axes", "axis_minimum",
                                                                            "axis_maximum"]}}, timeout_s=timeout_s)
        if "error" in reply:
            raise AxiscalError(f"{self.description} refused a query: {reply['error']}")
        return reply["result"]["status"]["toolhead"]

    def _abandon(self) -> None:
        self.main.close()

    def stop(self) -> None:
        try:
            self.watch.call("emergency_stop", {}, timeout_s=SILENCE_S)
        except OSError:
            pass

    def close(self) -> None:
        self.main.close()
        self.watch.close()
        super().close()


class MoonrakerController(_ToolheadController):
    """Klipper through Moonraker's HTTP API.

    Parameters
    ----------
    url : str
        ``http://HOST[:PORT]`` (Moonraker listens on 7125 by default).
    """

    def __init__(self, url: str):
        try:
            parts = urllib.parse.urlsplit(url if "://" in url else f"http://{url}")
            port = parts.port  # a port that is no number, or beyond 65535, raises here
        except ValueError:
            parts, port = None, None
        host = parts.hostname if parts is not None else None
        if parts is None or parts.scheme not in ("http", "https") or not host or port == 0 \
                or any(not c.isprintable() or c.isspace() or c in "/\\?#@%" for c in host):
            raise AxiscalError(f"moonraker:URL needs an http:// address (http://HOST[:PORT], port 1-65535), not {url!r}")
        self.host, self.port = host, port or 7125
        self.https = parts.scheme == "https"
        self.description = f"Moonraker at {parts.scheme}://{self.host}:{self.port}"
        super().__init__()
        self._main_conn: http.client.HTTPConnection | None = None
        try:
            self._query(timeout_s=SILENCE_S)
        except (OSError, ValueError) as exc:  # ValueError: an address http.client will not send (InvalidURL)
            raise AxiscalError(f"cannot reach {self.description}: {getattr(exc, 'strerror', None) or exc}") from None

    def _connection(self, timeout_s: float | None) -> http.client.HTTPConnection:
        kind = http.client.HTTPSConnection if self.https else http.client.HTTPConnection
        return kind(self.host, self.port, timeout=timeout_s if timeout_s is not None else 3600.0)

    def _request(self, conn, method: str, path: str, body: dict | None) -> dict:
        try:
            conn.request(method, path, body=None if body is None else json.dumps(body),
                         headers={"Content-Type": "application/json"})
            response = conn.getresponse()
            data = response.read()
        except (http.client.HTTPException, socket.timeout) as exc:
            raise OSError(errno.EIO, f"{self.description}: {exc}") from None
        try:
            message = json.loads(data.decode("utf-8"))
        except ValueError:
            raise OSError(errno.EIO, f"{self.description} answered {response.status} with no JSON") from None
        if response.status >= 400 or "error" in message:
            error = message.get("error", {})
            return {"error": error if isinstance(error, dict) else {"message": str(error)}}
        return message

    def _script(self, script, *, timeout_s, main):
        conn = self._connection(timeout_s)
        self._main_conn = conn
        try:
            return self._request(conn, "POST", "/printer/gcode/script", {"script": script})
        finally:
            conn.close()

    def _query(self, *, timeout_s):
        conn = self._connection(timeout_s)
        try:
            reply = self._request(conn, "GET", "/printer/objects/query?toolhead=position,homed_axes,axis_minimum,axis_maximum", None)
        finally:
            conn.close()
        if "error" in reply:
            raise AxiscalError(f"{self.description} refused a query: {reply['error'].get('message', reply['error'])}")
        return reply["result"]["status"]["toolhead"]

    def _abandon(self) -> None:
        if self._main_conn is not None and self._main_conn.sock is not None:
            try:
                self._main_conn.sock.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass

    def stop(self) -> None:
        conn = self._connection(SILENCE_S)
        try:
            self._request(conn, "POST", "/printer/emergency_stop", None)
        except OSError:
            pass
        finally:
            conn.close()
