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

The sources live in two modules by what drives them: :mod:`axiscal.live.playback` (played by the
clock: the sim, a replay, an ``.rtx`` capture) and :mod:`axiscal.live.streams` (connections: TCP
and serial, which reconnect with exponential back-off, :class:`Backoff`; a connection that drops
is never an error of the run). This module names them: :func:`parse_source` reads a ``--source``
value and :func:`open_source` builds the source it names; every source's name is importable from
here.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, type_name
from axiscal.live.playback import MAX_RATE_HZ, ReplaySource, RtxSource, SimSource
from axiscal.live.protocol import _checked_channels
from axiscal.live.status import SourceStatus
from axiscal.live.streams import Backoff, SerialSource, TcpSource

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
