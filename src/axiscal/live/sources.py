"""Where live frames come from: the virtual instrument, a recorded file, a Renishaw .rtx capture, TCP, a serial port.

Every source has the same small interface, used by :class:`axiscal.live.pipeline.Pipeline` from
one thread:

- ``read(timeout_s) -> FrameBatch`` -- the frames that arrived (possibly none), waiting at most
  ``timeout_s``;
- ``finished`` -- True once a finite source (a replay) has delivered its last frame;
- ``status`` -- a :class:`SourceStatus` for the dashboard (state, reconnections, last message);
- ``clock_offset_s`` -- monotonic clock minus frame time stamp when the source knows it (the sim
  and a paced replay do), else None; the pipeline measures latency with it;
- ``close()``.

Sources that can lose their connection (TCP, serial) reconnect with exponential back-off
(:class:`Backoff`); a connection that drops is never an error of the run.
"""

from __future__ import annotations

import errno
import os
import select
import socket
import time
from abc import ABC, abstractmethod
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.importers.rtx import read_rtx
from axiscal.io.arguments import check_choice, check_count, check_number, check_path, is_real
from axiscal.io.arguments import check_instance, type_name
from axiscal.live.protocol import FrameBatch, LineDecoder, _checked_channels
from axiscal.live.recorder import read_record
from axiscal.measurement.virtual import PATHS
from axiscal.units import length_factor, split_unit

__all__ = [
    "MAX_RATE_HZ",
    "SourceStatus",
    "Backoff",
    "SimSource",
    "ReplaySource",
    "RtxSource",
    "TcpSource",
    "SerialSource",
    "parse_source",
    "rtx_parts",
    "open_source",
]

#: highest frame rate of the sim source, Hz (ten times the rate the benchmark keeps up with)
MAX_RATE_HZ = 100_000.0


@dataclass
class SourceStatus:
    """What a source is doing, for the dashboard and the progress line.

    Attributes
    ----------
    description : str
        What the source is (``"sim (1000 Hz, diagonal)"``, a file, an address).
    state : str
        One of ``"connecting"``, ``"streaming"``, ``"retrying"``, ``"finished"``.
    connections, retries : int
        Connections made and retries after a failure.
    message : str
        The last problem, if any.
    attempt_times : list of float
        Monotonic times of the connection attempts.
    """

    description: str
    state: str = "connecting"
    connections: int = 0
    retries: int = 0
    message: str = ""
    attempt_times: list[float] = field(default_factory=list)


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


def _empty(width: int) -> FrameBatch:
    return FrameBatch.concatenate([], width)


class SimSource:
    """The virtual instrument streamed in real time: ``VirtualModule.frames(t)`` at ``rate_hz``.

    Frame k has time stamp k / rate_hz and is delivered once that time has passed on the monotonic
    clock (so its delay to the record is measurable); at most ``max_batch_s`` of frames per read.

    Parameters
    ----------
    module : VirtualModule
        The instrument (:mod:`axiscal.measurement.virtual`).
    channels : sequence of str
        Channel order of the measurement system.
    rate_hz : float
        Frames per second, at most :data:`MAX_RATE_HZ`.
    path : str
        Motion of the module (``"diagonal"``, ``"raster"``, ``"back-and-forth"``).
    max_batch_s : float
        Most stream time delivered by one read, s (at most 1).

    Raises
    ------
    AxiscalError
        For a rate that is not finite, not positive or above :data:`MAX_RATE_HZ`.
    """

    def __init__(self, module, channels: Sequence[str], *, rate_hz: float = 1000.0, path: str = "diagonal", max_batch_s: float = 0.05):
        if not (is_real(rate_hz) and np.isfinite(rate_hz) and 0 < rate_hz <= MAX_RATE_HZ):
            raise AxiscalError(f"rate_hz: the frame rate must be a positive number of frames per second up to {MAX_RATE_HZ:g}, not {rate_hz!r}")
        if not (is_real(max_batch_s) and np.isfinite(max_batch_s) and 0 < max_batch_s <= 1.0):
            raise AxiscalError(f"max_batch_s (the longest batch) must be 0 to 1 s, not {max_batch_s!r}")
        if not callable(getattr(module, "frames", None)):
            raise AxiscalError(f"module must be a VirtualModule, not {type_name(module)}")
        check_choice("path", path, PATHS)
        self.module = module
        self.channels = _checked_channels(channels)
        self.rate_hz = float(rate_hz)
        self.path = path
        self.max_batch = max(1, int(round(max_batch_s * rate_hz)))
        self.status = SourceStatus(f"sim ({rate_hz:g} Hz, {path})", state="streaming", connections=1)
        self.finished = False
        self.clock_offset_s: float | None = None
        self._next = 0

    def read(self, timeout_s: float) -> FrameBatch:
        now = time.monotonic()
        if self.clock_offset_s is None:
            self.clock_offset_s = now
        due = int(np.floor((now - self.clock_offset_s) * self.rate_hz)) + 1 - self._next
        if due <= 0:
            wait = (self._next / self.rate_hz + self.clock_offset_s) - now
            if wait > timeout_s:
                time.sleep(max(timeout_s, 0.0))
                return _empty(len(self.channels))
            time.sleep(max(wait, 0.0))
            due = 1
        due = min(due, self.max_batch)
        t = (self._next + np.arange(due)) / self.rate_hz
        self._next += due
        frames, _truth = self.module.frames(t, path=self.path)
        return FrameBatch.from_frames(frames, self.channels)

    def close(self) -> None:
        self.status.state = "finished"


class ReplaySource:
    """A recorded CSV (a live record, or any file with ``t_s`` and every channel) played back.

    Parameters
    ----------
    path : str or Path
        The file; read with :func:`axiscal.live.recorder.read_record` (a cut last line is dropped).
    channels : sequence of str
        Channel order of the measurement system; each must be a column of the file.
    pace : bool
        True: frames are delivered when their ``t_s`` (relative to the first) has passed;
        False: as fast as the pipeline takes them.

    Raises
    ------
    AxiscalError
        For a bad ``path`` or ``channels``, a ``pace`` that is not a bool, a ``max_batch``
        below 1, a file that lacks a channel column.
    """

    def __init__(self, path: str | Path, channels: Sequence[str], *, pace: bool = True, max_batch: int = 2000):
        channels = _checked_channels(channels)
        _check_playback(pace, max_batch)
        record = read_record(path)
        missing = [name for name in channels if name not in record.columns]
        if missing:
            raise AxiscalError(f"replay file lacks channel column(s) {', '.join(missing)}", path=path)
        t = record.columns["t_s"]
        values = np.column_stack([record.columns[name] for name in channels]) if channels else np.empty((len(t), 0))
        self._play(f"replay {path}", channels, t, values, pace=pace, max_batch=max_batch)

    def _play(self, description: str, channels: Sequence[str], t: np.ndarray, values: np.ndarray, *, pace: bool, max_batch: int) -> None:
        """Set up the playback of frames ``t`` (N,) and ``values`` (N, C)."""
        self.channels = tuple(channels)
        self._t = t
        self._values = values
        self.pace = pace
        self.max_batch = max_batch
        self.status = SourceStatus(description + ("" if pace else " (as fast as possible)"), state="streaming", connections=1)
        self.finished = len(self._t) == 0
        self.clock_offset_s: float | None = None
        self._start: float | None = None
        self._next = 0
        self._t0 = float(self._t[np.isfinite(self._t)][0]) if np.isfinite(self._t).any() else 0.0

    def read(self, timeout_s: float) -> FrameBatch:
        if self.finished:
            return _empty(len(self.channels))
        stop = min(self._next + self.max_batch, len(self._t))
        if self.pace:
            now = time.monotonic()
            if self._start is None:
                self._start = now
                self.clock_offset_s = now - self._t0
            elapsed = now - self._start
            times = self._t[self._next : stop] - self._t0
            # a row is due when its t_s and every t_s before it has passed (NaN times never hold a row back)
            due_at = np.maximum.accumulate(np.where(np.isfinite(times), times, -np.inf))
            ready = int(np.searchsorted(due_at, elapsed, side="right"))
            if ready == 0:
                wait = min(float(due_at[0]) - elapsed, timeout_s)
                time.sleep(max(wait, 0.0))
                return _empty(len(self.channels))
            stop = self._next + ready
        t = self._t[self._next : stop]
        batch = FrameBatch(t.copy(), self._values[self._next : stop].copy(), ~np.isfinite(t))
        self._next = stop
        if self._next >= len(self._t):
            self.finished = True
            self.status.state = "finished"
        return batch

    def close(self) -> None:
        self.status.state = "finished"


def _check_playback(pace: bool, max_batch: int) -> None:
    """Refuse a ``pace`` that is not a bool or a ``max_batch`` that is not a positive whole number."""
    check_instance("pace", pace, bool)
    check_count("max_batch", max_batch)


class RtxSource(ReplaySource):
    """A Renishaw ``.rtx`` dynamic capture played back as the reading of one channel.

    The capture holds one reading at a fixed sample rate (:func:`axiscal.io.importers.rtx.read_rtx`):
    frame k has ``t_s = k / rate`` and carries the sample k in ``channel`` (converted to the unit
    its name ends in); every other channel is missing, so those frames carry the missing-channel
    fault unless the system has no other channel.

    Parameters
    ----------
    path : str or Path
        The ``.rtx`` file.
    unit : str
        Unit the samples were stored in (the file does not say): ``nm``, ``um``, ``mm``, ``m``, ``in``.
    channel : str
        The measurement system's channel the reading feeds (a length channel, e.g. ``x_scale_mm``).
    channels : sequence of str
        Channel order of the measurement system.
    pace : bool
        True: at the capture's sample rate; False: as fast as the pipeline takes them.

    Raises
    ------
    AxiscalError
        For an unreadable capture, an unknown unit, or a channel the system does not have or that
        is not a length.
    """

    def __init__(self, path: str | Path, unit: str, channel: str, channels: Sequence[str], *, pace: bool = True, max_batch: int = 2000):
        channels = _checked_channels(channels)
        _check_playback(pace, max_batch)
        path = check_path("path", path)
        if not isinstance(channel, str) or channel not in channels:
            raise AxiscalError(f"channel '{channel}' is not one of the measurement system's: {', '.join(channels)}")
        factor = length_factor(split_unit(channel)[1], allowed=("nm", "um", "mm"), what=f"channel {channel}")
        capture = read_rtx(path, unit=unit)
        values = np.full((len(capture.samples_m), len(channels)), np.nan)
        values[:, channels.index(channel)] = capture.samples_m / factor
        description = f"rtx {path} ({capture.sample_rate_hz:g} Hz, {unit}) as {channel}"
        self._play(description, channels, capture.time_s, values, pace=pace, max_batch=max_batch)


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
                return _empty(len(self.channels))
            self.status.attempt_times.append(time.monotonic())
            try:
                self._connect()
            except OSError as exc:
                self.status.retries += 1
                self.status.state = "retrying"
                self.status.message = f"cannot connect: {exc.strerror or exc}"
                self._next_attempt = time.monotonic() + self.backoff.failed()
                return _empty(len(self.channels))
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


def parse_source(spec: str) -> tuple[str, str]:
    """Split a ``--source`` value into (kind, argument).

    Parameters
    ----------
    spec : str
        ``sim``, ``replay:FILE``, ``rtx:FILE:UNIT:CHANNEL``, ``tcp:HOST:PORT`` or
        ``serial:DEVICE[:BAUD]``.

    Returns
    -------
    kind : str
        ``"sim"``, ``"replay"``, ``"rtx"``, ``"tcp"`` or ``"serial"``.
    argument : str
        The rest (empty for ``sim``).

    Raises
    ------
    AxiscalError
        For an unknown kind or a TCP address without a valid port.

    Examples
    --------
    >>> parse_source("tcp:127.0.0.1:9000")
    ('tcp', '127.0.0.1:9000')
    """
    if not isinstance(spec, str):
        raise AxiscalError(f"spec must be a source (a str such as 'sim' or 'tcp:HOST:PORT'), not {type_name(spec)}")
    kind, sep, argument = spec.partition(":")
    kind = kind.strip().lower()
    if kind == "sim" and not sep:
        return "sim", ""
    if kind in ("replay", "rtx", "tcp", "serial") and argument:
        if kind == "rtx":
            path, unit, channel = rtx_parts(argument)
            if not (path and unit and channel):
                raise AxiscalError(f"source '{spec}': expected rtx:FILE:UNIT:CHANNEL, e.g. rtx:run.rtx:mm:x_scale_mm")
        if kind == "tcp":
            host, _, port = argument.rpartition(":")
            if not host or not port.isdigit() or not 0 < int(port) < 65536:
                raise AxiscalError(f"source '{spec}': expected tcp:HOST:PORT with a port 1-65535, e.g. tcp:127.0.0.1:9000")
        return kind, argument
    raise AxiscalError(f"unknown source '{spec}'; use sim, replay:FILE, rtx:FILE:UNIT:CHANNEL, tcp:HOST:PORT or serial:DEVICE[:BAUD]")


def rtx_parts(argument: str) -> tuple[str, str, str]:
    """Split the argument of an ``rtx:`` source into (file, unit, channel); the file may hold ':'.

    Parameters
    ----------
    argument : str
        ``FILE:UNIT:CHANNEL``.

    Returns
    -------
    tuple of str
        File, unit, channel (empty strings where missing).

    Raises
    ------
    AxiscalError
        For an ``argument`` that is not a str.

    Examples
    --------
    >>> rtx_parts("runs/x axis.rtx:mm:x_scale_mm")
    ('runs/x axis.rtx', 'mm', 'x_scale_mm')
    """
    if not isinstance(argument, str):
        raise AxiscalError(f"argument must be FILE:UNIT:CHANNEL (a str), not {type_name(argument)}")
    parts = argument.rsplit(":", 2)
    if len(parts) < 3:
        return (parts[0], "", "") if len(parts) == 1 else (parts[0], parts[1], "")
    return parts[0], parts[1].strip(), parts[2].strip()


def open_source(
    spec: str,
    channels: Sequence[str],
    *,
    virtual_module: Callable[[], object] | None = None,
    rate_hz: float = 1000.0,
    path: str = "diagonal",
    pace: bool = True,
):
    """Build the source a ``--source`` value names (see :func:`parse_source`).

    Parameters
    ----------
    spec : str
        The ``--source`` value.
    channels : sequence of str
        The measurement system's channels, in frame order.
    virtual_module : callable, keyword-only
        Makes the :class:`~axiscal.measurement.virtual.VirtualModule` for ``sim`` when called.
    rate_hz : float, keyword-only
        Frames per second of ``sim``, Hz.
    path : str, keyword-only
        Motion of ``sim``.
    pace : bool, keyword-only
        Replay at the file's ``t_s`` pace.

    Returns
    -------
    SimSource, ReplaySource, RtxSource, TcpSource or SerialSource

    Raises
    ------
    AxiscalError
        For a bad spec, or a replay file or capture that does not exist or cannot be read.
    """
    kind, argument = parse_source(spec)
    channels = _checked_channels(channels)
    check_instance("pace", pace, bool)
    if virtual_module is not None and not callable(virtual_module):
        raise AxiscalError(f"virtual_module must be a function that makes the VirtualModule, not {type_name(virtual_module)}")
    if kind == "sim":
        if virtual_module is None:
            raise AxiscalError("the sim source needs the virtual module (virtual_module)")
        return SimSource(virtual_module(), channels, rate_hz=rate_hz, path=path)
    if kind == "replay":
        if not Path(argument).is_file():
            raise AxiscalError("replay file not found", path=argument)
        return ReplaySource(argument, channels, pace=pace)
    if kind == "rtx":
        file, unit, channel = rtx_parts(argument)
        if not Path(file).is_file():
            raise AxiscalError("rtx capture not found", path=file)
        return RtxSource(file, unit, channel, channels, pace=pace)
    if kind == "tcp":
        host, _, port = argument.rpartition(":")
        return TcpSource(host.strip("[]"), int(port), channels)
    device, _, baud = argument.rpartition(":")
    if not (device and baud.isdigit()):
        device, baud = argument, "115200"
    return SerialSource(device, channels, baud=int(baud))
