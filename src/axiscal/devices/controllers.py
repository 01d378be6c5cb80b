"""Controller specs (``linuxcnc:HOST[:PORT]``, ``grbl:PORT[@BAUD]`` ...) parsed and opened as drivers.

=============================  ==============================================================
spec                           controller
=============================  ==============================================================
``linuxcnc:HOST[:PORT]``       LinuxCNC through linuxcncrsh (port 5007 by default)
``grbl:PORT[@BAUD]``           grbl 1.1 / grblHAL on a serial port (115200)
``grbl:tcp:HOST:PORT``         grblHAL on TCP
``marlin:PORT[@BAUD]``         Marlin on a serial port (115200)
``klipper:SOCKET_PATH``        Klipper's API socket
``moonraker:URL``              Moonraker (Klipper) over HTTP
``sim``                        the virtual controller (with the compensation it is given)
=============================  ==============================================================
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from axiscal.devices.links import SerialFraming, SerialLink, TcpLink, parse_port
from axiscal.errors import AxiscalError

__all__ = ["CONTROLLER_KINDS", "open_controller"]

#: the controllers axiscal drives
CONTROLLER_KINDS = ("linuxcnc", "grbl", "marlin", "klipper", "moonraker", "sim")


def open_controller(spec: str, *, ini: str | Path | None = None, sim: Callable[[], object] | None = None):
    """Connect to the controller a ``--controller`` value names.

    Parameters
    ----------
    spec : str
        One of the forms in the module's table.
    ini : str or Path, optional, keyword-only
        LinuxCNC: the machine's INI file (soft limits, axis letters).
    sim : callable, optional, keyword-only
        Makes the virtual controller for ``sim`` (the caller gives it its machine and compensation).

    Returns
    -------
    a controller (:class:`~axiscal.devices.controller.Controller`)

    Raises
    ------
    AxiscalError
        For an unknown kind, a bad address, port or baud rate, or a controller that cannot be reached.
    """
    if not isinstance(spec, str):
        raise AxiscalError(f"spec must be a controller such as 'linuxcnc:127.0.0.1', not {type(spec).__name__}")
    kind, sep, argument = spec.partition(":")
    kind = kind.strip().lower()
    argument = argument.strip()
    if kind == "sim" and not argument:
        if sim is None:
            from axiscal.devices.sim import SimController

            return SimController()
        return sim()
    if kind not in CONTROLLER_KINDS or not argument:
        raise AxiscalError(f"unknown controller '{spec}'; use linuxcnc:HOST[:PORT], grbl:PORT[@BAUD], grbl:tcp:HOST:PORT,"
                           " marlin:PORT[@BAUD], klipper:SOCKET_PATH, moonraker:URL or sim")
    if kind == "linuxcnc":
        from axiscal.devices.linuxcnc import LINUXCNCRSH_PORT, LinuxcncController

        host, sep, port = argument.rpartition(":")
        if not sep:
            host, port = argument, str(LINUXCNCRSH_PORT)
        if not host or not port.isdigit() or not 0 < int(port) < 65536:
            raise AxiscalError(f"controller '{spec}': expected linuxcnc:HOST[:PORT] with a port 1-65535")
        return LinuxcncController(host.strip("[]"), int(port), ini=ini)
    if kind == "grbl":
        from axiscal.devices.grbl import GrblController

        if argument.lower().startswith("tcp:"):
            host, sep, port = argument[4:].rpartition(":")
            if not host or not port.isdigit() or not 0 < int(port) < 65536:
                raise AxiscalError(f"controller '{spec}': expected grbl:tcp:HOST:PORT with a port 1-65535")
            return GrblController(TcpLink(host.strip("[]"), int(port)), f"{host}:{port}")
        port, baud = parse_port(argument, what=spec, default_baud=115200)
        return GrblController(SerialLink(port, SerialFraming(baud)), port)
    if kind == "marlin":
        from axiscal.devices.marlin import MarlinController

        port, baud = parse_port(argument, what=spec, default_baud=115200)
        return MarlinController(SerialLink(port, SerialFraming(baud)), port)
    if kind == "klipper":
        from axiscal.devices.klipper import KlipperController

        return KlipperController(argument)
    from axiscal.devices.klipper import MoonrakerController

    return MoonrakerController(argument)
