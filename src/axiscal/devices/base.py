"""What every instrument source hands on: time-stamped samples, the faults it saw, its status.

An instrument source has the interface of the live sources (``read(timeout_s)``, ``channels``,
``status``, ``finished``, ``close()``), so the capture reads a µMD, a gauge or a TCP stream alike. Beside
the samples it keeps the faults it saw on the way (a sequence gap, a line that is not a reading) with the
instrument's time, so a capture can refuse a stop whose window holds one and report the others.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import math
import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from axiscal.devices.links import LinkClosed

__all__ = ["Samples", "Fault", "InstrumentStatus", "InstrumentSource", "PolledSource", "READING_CHANNEL", "AIR_CHANNELS"]

#: the channel holding the instrument's reading, millimetres
READING_CHANNEL = "reading_mm"
#: the air and material channels an instrument may fill (the columns of a positioning run)
AIR_CHANNELS = ("air_temperature_c", "pressure_pa", "humidity_pct", "material_temperature_c")


@dataclass(frozen=True)
class Samples:
    """Samples as they arrive (the shape of :class:`axiscal.live.protocol.FrameBatch`).

    Attributes
    ----------
    t_s : ndarray, shape (n,)
        Time of each sample, seconds, on the instrument's clock where it has one.
    values : ndarray, shape (n, c)
        The channels in ``channels`` order, each in its own unit; NaN = no value.
    malformed : ndarray of bool, shape (n,)
        Samples that are not readings (kept so the time line stays whole).
    """

    t_s: np.ndarray
    values: np.ndarray
    malformed: np.ndarray

    def __len__(self) -> int:
        return len(self.t_s)

    @classmethod
    def empty(cls, width: int) -> "Samples":
        return cls(np.empty(0), np.empty((0, width)), np.zeros(0, dtype=bool))

    @classmethod
    def of(cls, t_s: Sequence[float], rows: Sequence[Sequence[float]], bad: Sequence[bool], width: int) -> "Samples":
        if not len(t_s):
            return cls.empty(width)
        return cls(np.asarray(t_s, dtype=float), np.asarray(rows, dtype=float).reshape(len(t_s), width),
                   np.asarray(bad, dtype=bool))


@dataclass(frozen=True)
class Fault:
    """Something the instrument's stream said that is not a reading.

    Attributes
    ----------
    time_s : float, seconds
        When, on the instrument's clock.
    message : str
        What, in the device's words where it has them.
    """

    time_s: float
    message: str


@dataclass
class InstrumentStatus:
    """What an instrument source is doing (the shape of :class:`axiscal.live.sources.SourceStatus`).

    Attributes
    ----------
    description : str
        The device and its port.
    state : str
        ``"connecting"``, ``"streaming"``, ``"lost"`` or ``"finished"``.
    message : str
        The last problem, if any.
    connections, retries : int
    attempt_times : list of float
    """

    description: str
    state: str = "connecting"
    message: str = ""
    connections: int = 0
    retries: int = 0
    attempt_times: list[float] = field(default_factory=list)


class InstrumentSource(ABC):
    """Base of the instrument sources: a link, a decoder of its bytes, the faults seen.

    Subclasses set ``channels``, ``status`` and implement ``_decode(data) -> Samples`` and, for polled
    instruments, ``_poll()`` (send the next request). The link is read in ``read``; a link the device
    closed ends the source (``finished``) with its status saying so.

    Parameters
    ----------
    link : a link of :mod:`axiscal.devices.links`
    description : str
        The device and its port, for messages and status lights.
    """

    channels: tuple[str, ...] = (READING_CHANNEL,)
    #: smallest step of the reading, metres (a gauge's resolution); the default stop stability follows it
    resolution_m: float = 0.0
    clock_offset_s = None

    def __init__(self, link, description: str):
        self.link = link
        self.status = InstrumentStatus(description, state="streaming", connections=1)
        self.finished = False
        self._faults: list[Fault] = []
        self._lock = threading.Lock()

    # -- faults -------------------------------------------------------------------------------
    def _fault(self, time_s: float, message: str) -> None:
        with self._lock:
            self._faults.append(Fault(float(time_s), message))
            self.status.message = message

    @property
    def faults(self) -> tuple[Fault, ...]:
        """Every fault seen so far, in order."""
        with self._lock:
            return tuple(self._faults)

    def faults_between(self, start_s: float, end_s: float) -> tuple[Fault, ...]:
        """The faults whose time lies in ``[start_s, end_s]`` (a stop's window).

        Parameters
        ----------
        start_s, end_s : float, seconds

        Returns
        -------
        tuple of Fault
        """
        with self._lock:
            return tuple(f for f in self._faults if start_s <= f.time_s <= end_s)

    # -- reading ------------------------------------------------------------------------------
    def _poll(self) -> None:
        """Ask a polled instrument for its next reading (streaming instruments do nothing)."""

    @abstractmethod
    def _decode(self, data: bytes) -> Samples:
        """The samples these bytes hold."""

    def read(self, timeout_s: float) -> Samples:
        """The samples that arrived within ``timeout_s`` seconds (possibly none).

        Parameters
        ----------
        timeout_s : float, seconds

        Returns
        -------
        Samples
        """
        if self.finished:
            time.sleep(min(timeout_s, 0.01))
            return Samples.empty(len(self.channels))
        try:
            self._poll()
            data = self.link.read(timeout_s)
        except LinkClosed as exc:
            self.finished = True
            self.status.state = "lost"
            self.status.message = f"the instrument went away: {exc.strerror or exc}"
            return Samples.empty(len(self.channels))
        except OSError as exc:
            self.finished = True
            self.status.state = "lost"
            self.status.message = f"the instrument's link failed: {exc.strerror or exc}"
            return Samples.empty(len(self.channels))
        if not data:
            return Samples.empty(len(self.channels))
        return self._decode(data)

    def close(self) -> None:
        """Close the link."""
        self.link.close()
        if self.status.state != "lost":
            self.status.state = "finished"


class PolledSource(InstrumentSource):
    """An instrument that answers one request with one reading (a gauge, a JSON-RPC head).

    Subclasses give ``request`` (bytes sent for a reading), ``terminator`` (the end of a reply) and
    ``_parse(reply) -> (metres or None, problem or None)``. The time of a reading is the host's
    monotonic clock when its reply arrived, from the source's start (a gauge has no clock of its own).
    A request unanswered for ``reply_timeout_s`` is asked again and counted as a fault.

    Parameters
    ----------
    link : a link of :mod:`axiscal.devices.links`
    description : str
    """

    request = b"?\r"
    terminator = b"\r"
    reply_timeout_s = 1.0

    def __init__(self, link, description: str):
        super().__init__(link, description)
        self._tail = b""
        self._asked_at: float | None = None
        self._t0 = time.monotonic()
        self.replies = 0

    def _now(self) -> float:
        return time.monotonic() - self._t0

    def _poll(self) -> None:
        now = time.monotonic()
        if self._asked_at is not None and now - self._asked_at < self.reply_timeout_s:
            return
        if self._asked_at is not None:
            self._fault(self._now(), f"no answer to a request within {self.reply_timeout_s:g} s")
        self.link.write(self._next_request())
        self._asked_at = now

    def _next_request(self) -> bytes:
        return self.request

    @abstractmethod
    def _parse(self, reply: bytes) -> tuple[float | None, str | None]:
        """A reply as (metres or None, the problem or None)."""

    def _decode(self, data: bytes) -> Samples:
        parts = (self._tail + data).split(self.terminator)
        self._tail = parts.pop()
        if len(self._tail) > 4096:
            self._tail = b""
        t_out, rows, bad = [], [], []
        for raw in parts:
            reply = raw.strip()
            if not reply:
                continue
            self._asked_at = None
            self.replies += 1
            value, problem = self._parse(reply)
            t = self._now()
            if problem is not None:
                self._fault(t, problem)
            t_out.append(t)
            rows.append([math.nan if value is None else value * 1e3] + [math.nan] * (len(self.channels) - 1))
            bad.append(value is None)
        return Samples.of(t_out, rows, bad, len(self.channels))

    def first_reading(self, timeout_s: float = 2.0) -> float:
        """Ask for one reading and wait for it (the device answers, and its resolution is learned).

        Parameters
        ----------
        timeout_s : float, seconds

        Returns
        -------
        float
            The reading, metres (NaN when the device answered with an error).

        Raises
        ------
        AxiscalError
            When nothing answers within ``timeout_s``.
        """
        from axiscal.errors import AxiscalError

        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            samples = self.read(0.05)
            if self.finished:
                break
            if len(samples):
                return float(samples.values[0, 0]) * 1e-3
        raise AxiscalError(f"{self.status.description}: no answer to {self.request!r} within {timeout_s:g} s"
                           " (check the cable, the port and the device's baud rate and framing)")
