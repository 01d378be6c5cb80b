"""Byte links to a device: a serial port (pyserial) or a TCP connection, with one small interface.

Every device module talks through a link: ``write(data)``, ``read(timeout_s) -> bytes`` (``b""`` when
nothing came within the timeout), ``close()``. A link that the device closed raises
:class:`LinkClosed`; an operating-system failure raises ``OSError``: the device module turns both into one
line for the user. Serial ports are opened with the device's framing (``7E2`` for a Sylvac Opto RS,
``8N1`` otherwise) and with DTR and RTS asserted where the port has modem lines (a USB CDC device such
as the µMD streams only once DTR is set; a pseudo-terminal has no modem lines, which is not an error).
"""

from __future__ import annotations

import errno
import os
import select
import socket
import time
from dataclasses import dataclass

from axiscal.errors import AxiscalError

__all__ = ["LinkClosed", "SerialFraming", "SerialLink", "TcpLink", "parse_port", "recv_before", "close_now"]


def close_now(sock: socket.socket) -> None:
    """Close a socket so that a reply awaited on another thread ends at once (shutdown wakes it; close alone does not).

    Parameters
    ----------
    sock : socket.socket

    Returns
    -------
    None
    """
    for step in (lambda: sock.shutdown(socket.SHUT_RDWR), sock.close):
        try:
            step()
        except OSError:
            pass


def recv_before(sock: socket.socket, deadline: float | None, where: str) -> bytes:
    """What a blocking socket receives before a moment of the monotonic clock (None: an hour at most).

    Parameters
    ----------
    sock : socket.socket
    deadline : float or None
        ``time.monotonic()`` by which something must have come.
    where : str
        The device, named in errors.

    Returns
    -------
    bytes
        Never empty.

    Raises
    ------
    OSError
        ``ETIMEDOUT`` when nothing came in time, ``ECONNRESET`` when the device closed the connection.
    """
    remaining = 3600.0 if deadline is None else deadline - time.monotonic()
    if remaining <= 0:
        raise OSError(errno.ETIMEDOUT, f"{where} did not answer in time")
    sock.settimeout(remaining)
    try:
        data = sock.recv(65536)
    except socket.timeout:
        raise OSError(errno.ETIMEDOUT, f"{where} did not answer in time") from None
    if not data:
        raise OSError(errno.ECONNRESET, f"{where} closed the connection")
    return data


class LinkClosed(OSError):
    """The device closed the link (end of file on the port or the socket).

    Parameters
    ----------
    errno, strerror :
        As ``OSError`` takes them.
    """


@dataclass(frozen=True)
class SerialFraming:
    """Baud rate and character framing of a serial port.

    Attributes
    ----------
    baud : int
        Bits per second.
    bytesize : int
        Data bits (7 or 8).
    parity : str
        ``"N"``, ``"E"`` or ``"O"``.
    stopbits : int
        1 or 2.
    """

    baud: int = 115200
    bytesize: int = 8
    parity: str = "N"
    stopbits: int = 1

    def describe(self) -> str:
        """The framing as people write it: ``115200 8N1``."""
        return f"{self.baud} {self.bytesize}{self.parity}{self.stopbits}"


def parse_port(argument: str, *, what: str, default_baud: int) -> tuple[str, int]:
    """Split ``PORT[@BAUD]`` into the port and the baud rate.

    Parameters
    ----------
    argument : str
        ``/dev/ttyUSB0`` or ``/dev/ttyUSB0@115200``.
    what : str, keyword-only
        The spec, named in errors (``"umd:/dev/ttyACM0"``).
    default_baud : int, keyword-only
        The device's own rate when none is given.

    Returns
    -------
    tuple of (str, int)

    Raises
    ------
    AxiscalError
        For an empty port or a baud rate that is not a positive whole number.
    """
    port, sep, baud = argument.rpartition("@")
    if not sep:
        port, baud = argument, str(default_baud)
    port = port.strip()
    if not port:
        raise AxiscalError(f"source '{what}': name the serial port, e.g. /dev/ttyUSB0 or /dev/ttyACM0@115200")
    if not baud.strip().isdigit() or not 0 < int(baud) <= 10_000_000:
        raise AxiscalError(f"source '{what}': the baud rate after @ must be a whole number of bits per second, not {baud!r}")
    return port, int(baud)


class SerialLink:
    """A serial port opened with pyserial.

    Parameters
    ----------
    device : str
        The port (``/dev/ttyUSB0``, ``/dev/ttyACM0``, a pseudo-terminal's slave).
    framing : SerialFraming
        Baud rate and framing.

    Raises
    ------
    AxiscalError
        For a port that does not exist, or cannot be opened (permissions: the user must be in the
        ``dialout`` group).
    """

    def __init__(self, device: str, framing: SerialFraming):
        import serial

        self.device = device
        self.framing = framing
        if not os.path.exists(device):
            raise AxiscalError(f"serial port {device} does not exist (is the device plugged in? `ls /dev/tty*` lists the ports)")
        parity = {"N": serial.PARITY_NONE, "E": serial.PARITY_EVEN, "O": serial.PARITY_ODD}[framing.parity]
        stopbits = {1: serial.STOPBITS_ONE, 2: serial.STOPBITS_TWO}[framing.stopbits]
        bytesize = {7: serial.SEVENBITS, 8: serial.EIGHTBITS}[framing.bytesize]
        try:
            self._port = serial.Serial(device, framing.baud, bytesize=bytesize, parity=parity, stopbits=stopbits, timeout=0,
                                       write_timeout=2.0)
        except (serial.SerialException, OSError) as exc:
            hint = " (add the user to the dialout group and log in again)" if "ermission" in str(exc) else ""
            raise AxiscalError(f"cannot open serial port {device}: {exc}{hint}") from None
        for line in ("dtr", "rts"):
            try:
                setattr(self._port, line, True)
            except (serial.SerialException, OSError):
                pass  # a pseudo-terminal has no modem lines
        self._serial = serial

    def write(self, data: bytes) -> None:
        try:
            self._port.write(data)
            self._port.flush()
        except (self._serial.SerialException, OSError) as exc:
            raise OSError(errno.EIO, f"write to {self.device} failed: {exc}") from None

    def read(self, timeout_s: float) -> bytes:
        try:
            ready, _, _ = select.select([self._port.fileno()], [], [], max(timeout_s, 0.0))
            if not ready:
                return b""
            data = os.read(self._port.fileno(), 1 << 16)
        except (self._serial.SerialException, OSError) as exc:
            if isinstance(exc, OSError) and exc.errno == errno.EIO:
                raise LinkClosed(errno.EIO, f"{self.device} closed") from None
            raise OSError(errno.EIO, f"read from {self.device} failed: {exc}") from None
        if not data:
            raise LinkClosed(errno.EIO, f"{self.device} closed")
        return data

    def close(self) -> None:
        try:
            self._port.close()
        except (self._serial.SerialException, OSError):
            pass


class TcpLink:
    """A TCP connection to a device that listens (an Attocube IDS, linuxcncrsh, a grblHAL board).

    Parameters
    ----------
    host : str
    port : int
    connect_timeout_s : float
        How long the connection may take.

    Raises
    ------
    AxiscalError
        For a connection refused or timed out, in one line naming the address.
    """

    def __init__(self, host: str, port: int, *, connect_timeout_s: float = 2.0):
        self.host, self.port = host, port
        try:
            self._socket = socket.create_connection((host, port), timeout=connect_timeout_s)
        except OSError as exc:
            raise AxiscalError(f"cannot connect to {host}:{port}: {exc.strerror or exc}") from None
        self._socket.setblocking(False)
        self._socket.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)

    def write(self, data: bytes) -> None:
        deadline = time.monotonic() + 2.0
        view = memoryview(data)
        while view:
            try:
                sent = self._socket.send(view)
            except BlockingIOError:
                if time.monotonic() > deadline:
                    raise OSError(errno.ETIMEDOUT, f"{self.host}:{self.port} does not take what is sent") from None
                select.select([], [self._socket], [], 0.1)
                continue
            view = view[sent:]

    def read(self, timeout_s: float) -> bytes:
        ready, _, _ = select.select([self._socket], [], [], max(timeout_s, 0.0))
        if not ready:
            return b""
        try:
            data = self._socket.recv(1 << 16)
        except BlockingIOError:
            return b""
        if not data:
            raise LinkClosed(errno.ECONNRESET, f"{self.host}:{self.port} closed the connection")
        return data

    def close(self) -> None:
        try:
            self._socket.close()
        except OSError:
            pass
