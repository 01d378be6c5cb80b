"""LinuxCNC through linuxcncrsh, its line protocol on TCP (port 5007 by default).

Source: the linuxcncrsh manual page (LinuxCNC 2.9 and 2.10). A client says ``hello EMC <name> 1.0``
(answered ``HELLO ACK``), ``set echo off`` and ``set verbose on`` (without verbose a ``set`` answers
nothing), ``set enable EMCTOO`` (the enable password), and ``set set_wait done`` (2.9; 2.10 names it
``set wait_mode done``) so that each ``set`` answers once the controller has done it. ``set mdi G1 X10
F600`` then answers ``SET MDI ACK`` once the move has ended, or ``SET MDI NAK`` when LinuxCNC refused it
(past a soft limit, not homed ...; ``get error`` gives the reason). Replies end ``\\r\\n`` or ``\\n\\r``.

A run asks, and never commands, the machine's state: it must be out of e-stop, on, and homed (``run``
never homes; after a restart the machine is homed again). A second connection asks ``get abs_act_pos``
every 0.2 s while a move runs: it is the heartbeat (a LinuxCNC that stops answering ends the run within
2 s) and the live position. Soft limits come from the INI file where it is readable (``[AXIS_<L>]
MIN_LIMIT`` / ``MAX_LIMIT`` in ``[TRAJ] LINEAR_UNITS``); else LinuxCNC's own refusal ends the run at
the step it refuses.
"""

from __future__ import annotations

import configparser
import errno
import socket
import threading
import time
from pathlib import Path

from axiscal.devices.controller import SILENCE_S, Controller, Heartbeat, move_words
from axiscal.devices.links import close_now, recv_before
from axiscal.errors import AxiscalError

__all__ = ["LINUXCNCRSH_PORT", "LinuxcncController", "RshConnection", "ini_limits"]

#: linuxcncrsh's default port
LINUXCNCRSH_PORT = 5007
_AXES = "XYZABCUVW"


class RshConnection:
    """One linuxcncrsh session: commands sent, one reply line each.

    Parameters
    ----------
    host, port : str, int
    name : str
        The client's name in ``hello``.
    connect_password : str
        The connect password (``EMC``).
    enable_password : str or None
        The enable password (``EMCTOO``); None for a session that only asks.
    timeout_s : float
        Longest wait for a reply to a query.
    """

    def __init__(self, host: str, port: int, *, name: str = "axiscal", connect_password: str = "EMC",
                 enable_password: str | None = "EMCTOO", timeout_s: float = 1.0):
        self.where = f"linuxcncrsh at {host}:{port}"
        self.timeout_s = timeout_s
        try:
            self.sock = socket.create_connection((host, port), timeout=timeout_s + 1)
        except OSError as exc:
            raise AxiscalError(f"cannot reach {self.where}: {exc.strerror or exc} (is LinuxCNC running with"
                               " DISPLAY = linuxcncrsh?)") from None
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self._buffer = b""
        self._lock = threading.Lock()
        reply = self.ask(f"hello {connect_password} {name} 1.0")
        if not reply.upper().startswith("HELLO ACK"):
            raise AxiscalError(f"{self.where} refused the connection ({reply!r}): check the connect password")
        self.send("set echo off")
        self._read_line(self.timeout_s)  # the echo of "set echo off" itself
        self._expect("set verbose on", "SET VERBOSE ACK")
        self.enable_password = enable_password
        if enable_password is not None:  # one session at a time may command: the last enabled
            self._expect(f"set enable {enable_password}", "SET ENABLE ACK")
        self.version = "2.9"
        if enable_password is None:
            return  # a watching session only asks
        if self.ask("set set_wait done").upper() != "SET SET_WAIT ACK":
            self._expect("set wait_mode done", "SET WAIT_MODE ACK")
            self.version = "2.10"

    def _expect(self, command: str, answer: str) -> None:
        reply = self.ask(command)
        if reply.upper() != answer:
            raise AxiscalError(f"{self.where} answered {command!r} with {reply!r}, not {answer}")

    def send(self, command: str) -> None:
        try:
            self.sock.sendall(command.encode("ascii") + b"\r\n")
        except OSError as exc:
            raise OSError(exc.errno or errno.EIO, f"{self.where}: {exc.strerror or exc}") from None

    def _read_line(self, timeout_s: float | None) -> str:
        deadline = None if timeout_s is None else time.monotonic() + timeout_s
        while True:
            if b"\n" in self._buffer:
                line, self._buffer = self._buffer.split(b"\n", 1)
                text = line.strip(b"\r\n ").decode("ascii", "replace")
                if text:
                    return text
                continue  # the \r of a \n\r ending
            self._buffer += recv_before(self.sock, deadline, self.where)

    def ask(self, command: str, *, timeout_s: float | None = -1.0) -> str:
        """Send a command and return its reply line (``timeout_s=None``: wait as long as it takes)."""
        with self._lock:
            self.send(command)
            return self._read_line(self.timeout_s if timeout_s == -1.0 else timeout_s)

    def close(self) -> None:
        """Close the session; a reply awaited on another thread ends at once (shutdown wakes it)."""
        close_now(self.sock)


def ini_limits(ini: str | Path, axis: str) -> tuple[float, float] | None:
    """An axis's soft limits from a LinuxCNC INI file, metres (None where the file does not say).

    Parameters
    ----------
    ini : str or Path
    axis : str

    Returns
    -------
    tuple of float or None

    Raises
    ------
    AxiscalError
        For a file that cannot be read, or limits that are not numbers.
    """
    parser = configparser.ConfigParser(strict=False, interpolation=None, inline_comment_prefixes=("#", ";"))
    try:
        parser.read_string(Path(ini).read_text(encoding="utf-8", errors="replace"))
    except (OSError, configparser.Error) as exc:
        raise AxiscalError(f"cannot read the LinuxCNC INI file: {exc}", path=ini) from None
    section = f"AXIS_{axis.upper()}"
    if not parser.has_section(section):
        return None
    units = parser.get("TRAJ", "LINEAR_UNITS", fallback="mm").strip().lower()
    factor = {"mm": 1e-3, "metric": 1e-3, "inch": 25.4e-3, "imperial": 25.4e-3, "in": 25.4e-3}.get(units)
    if factor is None:
        try:
            factor = 1.0 / float(units)  # units per mm... LinuxCNC also accepts a number of units per mm
            factor *= 1e-3
        except ValueError:
            raise AxiscalError(f"[TRAJ] LINEAR_UNITS = {units!r} is neither mm nor inch", path=ini) from None
    try:
        low = float(parser.get(section, "MIN_LIMIT"))
        high = float(parser.get(section, "MAX_LIMIT"))
    except (configparser.NoOptionError, ValueError):
        return None
    return low * factor, high * factor


class LinuxcncController(Controller):
    """A LinuxCNC machine driven through linuxcncrsh.

    Parameters
    ----------
    host : str
    port : int
    ini : str or Path, optional
        The machine's INI file, for its soft limits and its axis letters.
    """

    def __init__(self, host: str = "127.0.0.1", port: int = LINUXCNCRSH_PORT, *, ini: str | Path | None = None):
        self.description = f"LinuxCNC at {host}:{port}"
        super().__init__()
        self.host, self.port, self.ini = host, port, ini
        self.main = RshConnection(host, port, name="axiscal")
        self.watch = RshConnection(host, port, name="axiscal-watch", enable_password=None)
        self.status.message = f"linuxcncrsh {self.main.version}"

    def _index(self, axis: str) -> int:
        axis = axis.upper()
        if axis not in _AXES:
            raise AxiscalError(f"axis must be one of {', '.join(_AXES)}, not {axis!r}")
        return _AXES.index(axis)

    def _joint(self, axis: str) -> int:
        coordinates = "XYZ"
        if self.ini is not None:
            parser = configparser.ConfigParser(strict=False, interpolation=None, inline_comment_prefixes=("#", ";"))
            try:
                parser.read_string(Path(self.ini).read_text(encoding="utf-8", errors="replace"))
                coordinates = parser.get("TRAJ", "COORDINATES", fallback=parser.get("KINS", "COORDINATES", fallback="XYZ"))
            except (OSError, configparser.Error):
                pass
        letters = coordinates.replace(" ", "").upper()
        return letters.index(axis.upper()) if axis.upper() in letters else self._index(axis)

    def check_ready(self, axis: str) -> None:
        self._index(axis)
        try:
            estop = self.main.ask("get estop")
            machine = self.main.ask("get machine")
            homed = self.main.ask("get joint_homed")
        except OSError as exc:
            raise self.lost(str(exc)) from None
        if "ON" in estop.upper().split()[1:]:
            raise AxiscalError(f"{self.description} is in e-stop: release it and switch the machine on (axiscal run never does)")
        if "OFF" in machine.upper().split()[1:]:
            raise AxiscalError(f"{self.description}: the machine is off: switch it on (axiscal run never does)")
        flags = homed.upper().split()[1:]
        joint = self._joint(axis)
        if joint >= len(flags) or flags[joint] != "YES":
            raise AxiscalError(f"{self.description}: axis {axis.upper()} (joint {joint}) is not homed: home the machine first"
                               " (axiscal run never homes; after a restart, home again)")
        for command, answer in (("set mode mdi", "SET MODE ACK"), ("set linear_unit_conversion mm", "SET LINEAR_UNIT_CONVERSION ACK")):
            try:
                reply = self.main.ask(command, timeout_s=5.0)
            except OSError as exc:
                raise self.lost(str(exc)) from None
            if reply.upper() != answer:
                raise AxiscalError(f"{self.description} answered {command!r} with {reply!r}: {self._error()}")
        self.status.position_m = self.position(axis)

    def _error(self) -> str:
        try:
            reply = self.main.ask("get error")
        except OSError:
            return "no reason given"
        text = reply[len("ERROR"):].strip() if reply.upper().startswith("ERROR") else reply
        return text or "no reason given"

    def limits(self, axis: str) -> tuple[float, float] | None:
        if self.ini is None or not Path(self.ini).is_file():
            return None
        return ini_limits(self.ini, axis)

    def position(self, axis: str) -> float:
        reply = self.watch.ask("get abs_act_pos", timeout_s=0.3)
        values = reply.split()[1:]
        return float(values[self._index(axis)]) * 1e-3

    def move_to(self, axis: str, position_m: float, feed_m_per_s: float) -> None:
        axis = axis.upper()
        command = f"set mdi G21 G90 G1 {move_words(axis, position_m, feed_m_per_s, places=6, feed_places=3)}"
        self.status.state = "moving"

        def fail(reason: str) -> None:
            self.main.close()

        with Heartbeat(lambda: self.position(axis), fail, period_s=0.2) as beat:
            try:
                reply = self.main.ask(command, timeout_s=None)
            except OSError as exc:
                raise self.lost(beat.failed or str(exc)) from None
        if beat.failed:
            raise self.lost(beat.failed)
        self.status.position_m = beat.position_m
        if reply.upper() != "SET MDI ACK":
            raise AxiscalError(f"{self.description} refused the move to {axis} {position_m * 1e3:.4f} mm: {self._error()}")
        self.status.state = "idle"

    def stop(self) -> None:
        try:
            self.watch.ask(f"set enable {self.main.enable_password}", timeout_s=SILENCE_S)
            self.watch.ask("set abort", timeout_s=SILENCE_S)
        except OSError:
            pass

    def close(self) -> None:
        self.main.close()
        self.watch.close()
        super().close()
