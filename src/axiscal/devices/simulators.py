"""Simulators of the instruments, written from their documents: what ``--source sim:umd`` (etc.) serves.

Each simulator plays its device's side of the protocol on a real pseudo-terminal (serial devices) or a
TCP socket on 127.0.0.1 (the Attocube), from a ``position`` function of time that says where the axis
is (the virtual machine, a controller's simulated axis, a LinuxCNC joint). The tests read them through
the same readers and links as the real devices; faults (a lost beam, a sequence gap, an error reply, a
device that goes silent) are injected by the tests to check what the readers refuse.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import json
import math
import os
import select
import socket
import threading
import time
import tty
from collections.abc import Callable

import numpy as np

from axiscal.devices.umd import HENE_VACUUM_WAVELENGTH_M, umd_line

__all__ = ["open_pty_pair", "close_pty_pair", "UmdSimulator", "SylvacSimulator", "MahrSimulator", "TouchDroSimulator", "AttocubeSimulator"]


_HELD_SLAVES: dict[int, int] = {}


def open_pty_pair() -> tuple[int, str]:
    """A pseudo-terminal in raw mode: the master's file descriptor (the device's end) and the slave's path.

    The slave is held open here until :func:`close_pty_pair`, as a device's port stays there whether or not
    a program has it open (a master whose slave is closed fails every read and write).

    Returns
    -------
    tuple of (int, str)
    """
    master, slave = os.openpty()
    tty.setraw(slave)
    path = os.ttyname(slave)
    _HELD_SLAVES[master] = slave
    return master, path


def close_pty_pair(master: int) -> None:
    """Close a pair made by :func:`open_pty_pair`.

    Parameters
    ----------
    master : int

    Returns
    -------
    None
    """
    for fd in (_HELD_SLAVES.pop(master, None), master):
        if fd is not None:
            try:
                os.close(fd)
            except OSError:
                pass


class _Simulator(ABC):
    """A device's side running on a thread until ``stop()``."""

    def __init__(self):
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self.silent = False  # a device that stops answering

    def start(self) -> "_Simulator":
        self._thread = threading.Thread(target=self._run, name=type(self).__name__, daemon=True)
        self._thread.start()
        return self

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=5)

    @abstractmethod
    def _run(self) -> None:
        """The device's side, until stopped."""


def _write_all(fd: int, data: bytes, stop: threading.Event) -> bool:
    view = memoryview(data)
    while view and not stop.is_set():
        try:
            _, ready, _ = select.select([], [fd], [], 0.2)
            if not ready:
                continue
            view = view[os.write(fd, view):]
        except (BlockingIOError, InterruptedError):
            continue
        except OSError:
            return False
    return True


def _drain(fd: int) -> None:
    """Read and drop what the reader sent (a pty's buffer would fill otherwise)."""
    try:
        while select.select([fd], [], [], 0)[0]:
            if not os.read(fd, 4096):
                return
    except OSError:
        return


class UmdSimulator(_Simulator):
    """A µMD1 or µMD2 streaming lines of ``position(t)`` at its sample rate, paced by the clock.

    Parameters
    ----------
    fd : int
        Where the lines go (a pty's master).
    position : callable
        Metres of optical length at time t (seconds from the start).
    version : int
        1 or 2.
    rate_hz : float
        Sample rate (µMD1: 305.17 / 457.76 / 610.35 / 732.42; µMD2: 1000).
    air : tuple of float or None
        (air temperature degC, pressure Pa, humidity %) sent in codes 3, 5, 6 by a µMD1 (None: -1, absent).
    material_temperature_c : float or None
        Code 4 (µMD1).
    noise_m : float, metres
        Standard deviation of white noise on the length.
    seed : int
    pace : bool
        Follow the clock (a real device) or write as fast as the reader takes.
    start_sequence : int
    wavelength_m, optics_multiplier : as the reader.
    three_axes : bool
        16-field lines.
    """

    def __init__(self, fd: int, position: Callable[[float], float], *, version: int = 2, rate_hz: float = 1000.0,
                 air: tuple[float, float, float] | None = None, material_temperature_c: float | None = None,
                 noise_m: float = 0.0, seed: int = 0, pace: bool = True, start_sequence: int = 1,
                 wavelength_m: float = HENE_VACUUM_WAVELENGTH_M, optics_multiplier: int = 1, three_axes: bool = False,
                 duration_s: float | None = None):
        super().__init__()
        self.fd = fd
        self.position = position
        self.version = version
        self.rate_hz = rate_hz
        self.air = air
        self.material_temperature_c = material_temperature_c
        self.noise_m = noise_m
        self.rng = np.random.default_rng(seed)
        self.pace = pace
        self.sequence = start_sequence
        self.wavelength_m = wavelength_m
        self.optics_multiplier = optics_multiplier
        self.three_axes = three_axes
        self.duration_s = duration_s
        #: faults to inject: sequence -> "gap" (the line is not sent), "beam" (REF 0), "meas" (MEAS 0), "repeat"
        self.faults: dict[int, str] = {}
        self.sent = 0

    def _low_speed(self, n: int) -> tuple[int, int]:
        select_ = n & 0x1F
        if self.version == 2:
            return {1: (10, 261 + (29 << 16)), 2: (8, int(round(self.rate_hz * 100))), 3: (20, 2 * 256), 10: (112, 4)}.get(
                select_, (0, 0))
        codes = {1: (10, 58), 2: (8, int(round(self.rate_hz * 100))), 3: (20, 256)}
        if self.air is not None:
            t, p, h = self.air
            codes.update({4: (3, int(round(t * 100))), 5: (5, int(round(p))), 6: (6, int(round(h * 10)))})
        else:
            codes.update({4: (3, -1), 5: (5, -1), 6: (6, -1)})
        codes[7] = (4, -1 if self.material_temperature_c is None else int(round(self.material_temperature_c * 100)))
        return codes.get(select_, (0, 0))

    def line(self, n: int, t: float) -> bytes:
        """The line of sample sequence ``n`` at time ``t``."""
        length = float(self.position(t)) + (self.rng.normal(0.0, self.noise_m) if self.noise_m else 0.0)
        code, data = self._low_speed(n)
        fault = self.faults.get(n)
        ref, meas = 2_000, None
        if fault == "beam":
            ref = 0
        elif fault == "meas":
            meas = 0
        return umd_line(version=self.version, sequence=n, length_m=length, low_code=code, low_data=data,
                        wavelength_m=self.wavelength_m, optics_multiplier=self.optics_multiplier,
                        counts_per_cycle=2 if self.version == 2 else 1, ref=ref, meas=meas, three_axes=self.three_axes)

    def _run(self) -> None:
        began = time.monotonic()
        first = self.sequence
        while not self._stop.is_set():
            now = time.monotonic() - began
            due = int(now * self.rate_hz) + 1 if self.pace else (self.sent + 200)
            if self.duration_s is not None:
                due = min(due, int(self.duration_s * self.rate_hz))
                if self.sent >= due:
                    return
            chunk = []
            while self.sent < due:
                n = first + self.sent
                t = (n - first) / self.rate_hz
                self.sent += 1
                if self.silent:
                    continue
                kind = self.faults.get(n)
                if kind == "gap":
                    continue
                line = self.line(n, t)
                chunk.append(line)
                if kind == "repeat":
                    chunk.append(line)
            if chunk and not _write_all(self.fd, b"".join(chunk), self._stop):
                return
            _drain(self.fd)
            if self.pace:
                time.sleep(0.002)


class _AnsweringSimulator(_Simulator):
    """A polled serial device: reads requests from the pty's master, answers each."""

    request = b"?\r"

    def __init__(self, fd: int, position: Callable[[float], float], *, seed: int = 0, noise_m: float = 0.0):
        super().__init__()
        self.fd = fd
        self.position = position
        self.rng = np.random.default_rng(seed)
        self.noise_m = noise_m
        self.error: str | None = None  # an error reply to give instead of readings
        self.requests = 0

    @abstractmethod
    def reply(self, value_m: float) -> bytes:
        """The reply to one request for a reading at ``value_m``."""

    def _run(self) -> None:
        began = time.monotonic()
        pending = b""
        while not self._stop.is_set():
            try:
                ready, _, _ = select.select([self.fd], [], [], 0.1)
                if not ready:
                    continue
                data = os.read(self.fd, 4096)
            except OSError:
                return
            if not data:
                return
            pending += data
            while self.request in pending:
                _, pending = pending.split(self.request, 1)
                self.requests += 1
                if self.silent:
                    continue
                if self.error is not None:
                    out = self.error.encode() + b"\r"
                else:
                    value = float(self.position(time.monotonic() - began))
                    if self.noise_m:
                        value += self.rng.normal(0.0, self.noise_m)
                    out = self.reply(value)
                if not _write_all(self.fd, out, self._stop):
                    return


class SylvacSimulator(_AnsweringSimulator):
    """A Sylvac Opto RS gauge: ``?\\r`` -> ``+12.345\\r`` (mm, 0.001 mm resolution unless told).

    Parameters
    ----------
    fd : int
        The pty's master.
    position : callable
        Metres at time t.
    resolution_mm : float
    inch : bool
        Answer in inches.
    """

    def __init__(self, fd, position, *, resolution_mm: float = 0.001, inch: bool = False, **kwargs):
        super().__init__(fd, position, **kwargs)
        self.decimals = max(0, int(round(-math.log10(resolution_mm))))
        self.inch = inch

    def reply(self, value_m: float) -> bytes:
        value = value_m / (25.4e-3 if self.inch else 1e-3)
        text = f"{value:.{self.decimals}f}"
        if not text.startswith("-"):
            text = "+" + text
        return text.encode() + b"\r"


class MahrSimulator(_AnsweringSimulator):
    """A Mahr Millimar: ``?\\r`` -> ``+0012.3450mm\\r\\n``.

    Parameters
    ----------
    fd : int
        The pty's master.
    position : callable
        Metres at time t.
    """

    def reply(self, value_m: float) -> bytes:
        return f"{value_m * 1e3:+010.4f}mm\r\n".encode()


class TouchDroSimulator(_Simulator):
    """A TouchDRO adapter streaming ``X<counts>;Y<counts>;Z<counts>;T0;`` at a rate.

    Parameters
    ----------
    fd : int
    position : callable
        Metres on the X scale at time t (Y and Z stand at 0).
    counts_per_mm : float
    rate_hz : float
    """

    def __init__(self, fd: int, position: Callable[[float], float], *, counts_per_mm: float = 1000.0, rate_hz: float = 50.0):
        super().__init__()
        self.fd = fd
        self.position = position
        self.counts_per_mm = counts_per_mm
        self.rate_hz = rate_hz

    def _run(self) -> None:
        began = time.monotonic()
        while not self._stop.is_set():
            t = time.monotonic() - began
            counts = int(round(float(self.position(t)) * 1e3 * self.counts_per_mm))
            if not self.silent and not _write_all(self.fd, f"x{counts};Y0;Z0;T0;".encode(), self._stop):
                return
            _drain(self.fd)
            time.sleep(1.0 / self.rate_hz)


class AttocubeSimulator(_Simulator):
    """An Attocube IDS3010's JSON-RPC server on 127.0.0.1 (port 0: any free port; see ``port``).

    Parameters
    ----------
    position : callable
        Metres on axis 1 at time t (axes 2 and 3 read 0).
    """

    def __init__(self, position: Callable[[float], float], *, host: str = "127.0.0.1", port: int = 0):
        super().__init__()
        self.position = position
        self.warning = 0
        self._server = socket.create_server((host, port))
        self._server.settimeout(0.2)
        self.host, self.port = self._server.getsockname()[:2]
        self.requests = 0

    def _serve(self, conn: socket.socket, began: float) -> None:
        buffer = b""
        decoder = json.JSONDecoder()
        conn.settimeout(0.2)
        while not self._stop.is_set():
            try:
                data = conn.recv(4096)
            except socket.timeout:
                continue
            except OSError:
                return
            if not data:
                return
            buffer += data
            while buffer:
                text = buffer.decode("utf-8", "replace").lstrip()
                try:
                    request, end = decoder.raw_decode(text)
                except ValueError:
                    break
                buffer = text[end:].encode()
                self.requests += 1
                if self.silent:
                    continue
                if request.get("method") != "com.attocube.ids.displacement.getAxesDisplacement":
                    reply = {"jsonrpc": "2.0", "id": request.get("id"), "error": {"code": -32601, "message": "Method not found"}}
                else:
                    pm = int(round(float(self.position(time.monotonic() - began)) * 1e12))
                    reply = {"jsonrpc": "2.0", "id": request.get("id"), "result": [self.warning, pm, 0, 0]}
                try:
                    conn.sendall(json.dumps(reply).encode() + b"\r\n")
                except OSError:
                    return

    def _run(self) -> None:
        began = time.monotonic()
        while not self._stop.is_set():
            try:
                conn, _ = self._server.accept()
            except socket.timeout:
                continue
            except OSError:
                return
            with conn:
                self._serve(conn, began)

    def stop(self) -> None:
        super().stop()
        self._server.close()
