"""Sources that connect: the line protocol over TCP or a serial port, reconnecting with back-off.

A connection that drops, or is refused, is never an error of the run: the source retries after
an exponentially growing delay (:class:`Backoff`) and the dashboard shows its state. The interface
is the one of :mod:`axiscal.live.sources`.
"""

from __future__ import annotations

import errno
import os
import select
import socket
import time
from abc import ABC, abstractmethod
from collections.abc import Sequence

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, check_number
from axiscal.live.protocol import FrameBatch, LineDecoder, _checked_channels
from axiscal.live.status import SourceStatus

__all__ = ["Backoff", "TcpSource", "SerialSource"]


class Backoff:
    """Exponential back-off between reconnection attempts: initial, initial*factor, ... capped at maximum.

    Parameters
    ----------
    initial_s, factor, maximum_s : float
        First delay (s), growth factor per failed attempt, longest delay (s).

    Raises
    ------
    AxiscalError
        For a delay that is not a positive number of seconds, a factor below 1, or a maximum
        below the first delay.
    """

    def __init__(self, *, initial_s: float = 0.05, factor: float = 2.0, maximum_s: float = 2.0):
        initial_s = check_number("initial_s", initial_s, positive=True)
        factor = check_number("factor", factor, unit="", low=1.0)
        maximum_s = check_number("maximum_s", maximum_s, positive=True)
        if not maximum_s >= initial_s:
            raise AxiscalError("back-off needs initial > 0, factor >= 1 and maximum >= initial (maximum_s below initial_s)")
        self.initial_s = initial_s
        self.factor = factor
        self.maximum_s = maximum_s
        self.delay_s = initial_s

    def failed(self) -> float:
        """Record a failed attempt; return how long to wait before the next one."""
        delay = self.delay_s
        self.delay_s = min(self.delay_s * self.factor, self.maximum_s)
        return delay

    def succeeded(self) -> None:
        self.delay_s = self.initial_s


class _LineStreamSource(ABC):
    """Common part of the TCP and serial sources: connect, read lines, reconnect with back-off."""

    def __init__(self, channels: Sequence[str], description: str, backoff: Backoff | None, clock_offset_s: float | None):
        self.channels = _checked_channels(channels)
        if backoff is not None:
            check_instance("backoff", backoff, Backoff)
        if clock_offset_s is not None:
            clock_offset_s = check_number("clock_offset_s", clock_offset_s)
        self.decoder = LineDecoder(self.channels)
        self.backoff = backoff or Backoff()
        self.status = SourceStatus(description)
        self.finished = False
        self.clock_offset_s = clock_offset_s
        self._next_attempt = 0.0

    @property
    @abstractmethod
    def _connected(self) -> bool:
        """Whether a connection is open."""

    @abstractmethod
    def _connect(self) -> None:
        """Open the connection; raise OSError when that fails."""

    @abstractmethod
    def _disconnect(self) -> None:
        """Close the connection."""

    @abstractmethod
    def _receive(self, timeout_s: float) -> bytes | None:
        """Bytes received within the timeout (b"" if none); None when the peer has gone."""

    def _lost(self, message: str) -> FrameBatch:
        tail = self.decoder.flush()
        self._disconnect()
        self.decoder.reset()
        self.status.state = "retrying"
        self.status.message = message
        self._next_attempt = time.monotonic() + self.backoff.failed()
        return tail

    def read(self, timeout_s: float) -> FrameBatch:
        if not self._connected:
            now = time.monotonic()
            if now < self._next_attempt:
                time.sleep(min(self._next_attempt - now, timeout_s))
                return FrameBatch.empty(len(self.channels))
            self.status.attempt_times.append(time.monotonic())
            try:
                self._connect()
            except OSError as exc:
                self.status.retries += 1
                self.status.state = "retrying"
                self.status.message = f"cannot connect: {exc.strerror or exc}"
                self._next_attempt = time.monotonic() + self.backoff.failed()
                return FrameBatch.empty(len(self.channels))
            self.status.connections += 1
            self.status.state = "streaming"
            self.status.message = ""
        try:
            data = self._receive(timeout_s)
        except OSError as exc:
            self.status.retries += 1
            return self._lost(f"connection lost: {exc.strerror or exc}")
        if data is None:
            self.status.retries += 1
            return self._lost("connection closed by the sender")
        batch = self.decoder.feed(data)
        if len(batch):
            self.backoff.succeeded()
        return batch

    def close(self) -> None:
        if self._connected:
            self._disconnect()
        self.status.state = "finished"


class TcpSource(_LineStreamSource):
    """Frames from a TCP server speaking the line protocol (:mod:`axiscal.live.protocol`).

    axiscal connects as the client (the acquisition box listens); a refused or dropped connection
    is retried with :class:`Backoff` until the run ends.

    Parameters
    ----------
    host, port : str, int
        Where the acquisition box listens.
    channels : sequence of str
        Channel order of the measurement system.
    clock_offset_s : float, optional
        Monotonic clock minus the sender's ``t_s``, when the sender stamps frames from a clock
        this machine shares (used to measure latency; see benchmarks/realtime_live.py).

    Raises
    ------
    AxiscalError
        For an empty ``host``, a ``port`` outside 1-65535, bad ``channels``, a ``backoff``
        that is not a :class:`Backoff`, a non-finite clock offset or a timeout that is not
        positive.
    """

    def __init__(
        self,
        host: str,
        port: int,
        channels: Sequence[str],
        *,
        backoff: Backoff | None = None,
        clock_offset_s: float | None = None,
        connect_timeout_s: float = 1.0,
    ):
        if not isinstance(host, str) or not host.strip():
            raise AxiscalError(f"host must be a host name or address, not {host!r}")
        port = check_count("port", port, minimum=1, maximum=65535)
        connect_timeout_s = check_number("connect_timeout_s", connect_timeout_s, positive=True)
        super().__init__(channels, f"tcp {host}:{port}", backoff, clock_offset_s)
        self.host = host
        self.port = port
        self.connect_timeout_s = connect_timeout_s
        self._socket: socket.socket | None = None

    @property
    def _connected(self) -> bool:
        return self._socket is not None

    def _connect(self) -> None:
        sock = socket.create_connection((self.host, self.port), timeout=self.connect_timeout_s)
        sock.setblocking(False)
        self._socket = sock

    def _disconnect(self) -> None:
        if self._socket is not None:
            self._socket.close()
            self._socket = None

    def _receive(self, timeout_s: float) -> bytes | None:
        assert self._socket is not None
        ready, _, _ = select.select([self._socket], [], [], max(timeout_s, 0.0))
        if not ready:
            return b""
        chunks = []
        for _ in range(64):
            try:
                chunk = self._socket.recv(1 << 16)
            except BlockingIOError:
                break
            if not chunk:
                if chunks:
                    break
                return None
            chunks.append(chunk)
            if len(chunk) < 1 << 16:
                break
        return b"".join(chunks)


class SerialSource(_LineStreamSource):
    """Frames in the line protocol from a serial port (needs the optional ``pyserial`` package).

    Parameters
    ----------
    device : str
        The port, e.g. ``/dev/ttyUSB0``.
    baud : int
        Baud rate (default 115200).

    Raises
    ------
    AxiscalError
        For an empty ``device``, a ``baud`` below 1, bad ``channels``, a missing pyserial or
        device.
    """

    def __init__(self, device: str, channels: Sequence[str], *, baud: int = 115200, backoff: Backoff | None = None):
        if not isinstance(device, str) or not device.strip():
            raise AxiscalError(f"device must be the name of a serial port, not {device!r}")
        baud = check_count("baud", baud)
        _checked_channels(channels)
        try:
            import serial
        except ImportError:
            raise AxiscalError("the serial source needs the optional package pyserial (pip install pyserial)") from None
        if not os.path.exists(device):
            raise AxiscalError(f"serial device {device} does not exist")
        super().__init__(channels, f"serial {device} at {baud} baud", backoff, None)
        self._serial_module = serial
        self.device = device
        self.baud = int(baud)
        self._port = None

    @property
    def _connected(self) -> bool:
        return self._port is not None

    def _connect(self) -> None:
        try:
            self._port = self._serial_module.Serial(self.device, self.baud, timeout=0)
        except self._serial_module.SerialException as exc:
            raise OSError(errno.EIO, str(exc)) from None

    def _disconnect(self) -> None:
        if self._port is not None:
            self._port.close()
            self._port = None

    def _receive(self, timeout_s: float) -> bytes | None:
        assert self._port is not None
        try:
            ready, _, _ = select.select([self._port.fileno()], [], [], max(timeout_s, 0.0))
            if not ready:
                return b""
            return bytes(self._port.read(self._port.in_waiting or 1))
        except self._serial_module.SerialException as exc:
            raise OSError(errno.EIO, str(exc)) from None
