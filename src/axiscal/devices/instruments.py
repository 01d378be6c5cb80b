"""Instrument specs (``umd:PORT[@BAUD]``, ``sylvac:PORT``, ...) parsed and opened as sources.

=====================  =====================================================================
spec                   instrument
=====================  =====================================================================
``umd:PORT[@BAUD]``    µMD1 / µMD2 laser readout (USB serial, 115200 8N1)
``sylvac:PORT``        Sylvac / Bowers Opto RS gauge (4800 7E2, asked ``?``)
``mahr:PORT[@BAUD]``   Mahr Millimar (9600 8N1 unless given, asked ``?``)
``touchdro:PORT[@B]``  TouchDRO adapter, one scale (115200 unless given)
``attocube:HOST[:P]``  Attocube IDS3010 over JSON-RPC (TCP port 9090 by default)
``sim:KIND``           the simulator of KIND on a real pseudo-terminal (a socket for attocube),
                       following a position function the caller gives (the virtual machine)
=====================  =====================================================================
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from axiscal.devices.links import SerialFraming, SerialLink, TcpLink, parse_port
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_number

__all__ = ["INSTRUMENT_KINDS", "InstrumentOptions", "is_instrument_spec", "open_instrument", "default_stability_m"]

#: the finest scale read: 1 nm a count
MAX_COUNTS_PER_MM = 1e6
#: a simulator's noise seed: a whole number NumPy's generator takes
MAX_SEED = 2**63 - 1

#: the instruments axiscal reads itself
INSTRUMENT_KINDS = ("umd", "sylvac", "mahr", "touchdro", "attocube")


@dataclass(frozen=True)
class InstrumentOptions:
    """The instrument flags of ``capture``, ``run`` and ``live`` (SI inside).

    Attributes
    ----------
    wavelength_m : float, metres
        µMD: vacuum wavelength (632.991372 nm).
    optics_multiplier : int
        µMD: 1, 2 or 4.
    channel : str or None
        µMD and Attocube ``1|2|3``; TouchDRO ``X|Y|Z|W``.
    rate_hz : float or None, Hz
        µMD: the rate when the stream does not say it.
    umd_version : int or None
        µMD: 1 or 2 (None: from the firmware code).
    material_temperature_code : int or None
        µMD: the LowSpeed code carrying a material temperature (4).
    unit : str
        Sylvac: ``mm`` or ``in``.
    counts_per_mm : float or None
        TouchDRO: the scale's counts per millimetre.
    """

    wavelength_m: float = 632.991372e-9
    optics_multiplier: int = 1
    channel: str | None = None
    rate_hz: float | None = None
    umd_version: int | None = None
    material_temperature_code: int | None = None
    unit: str = "mm"
    counts_per_mm: float | None = None

    def __post_init__(self) -> None:
        # checked here, before a simulator is started on them (a thread that would die on a zero wavelength)
        check_number("wavelength_m", self.wavelength_m, low=100e-9, high=20e-6)
        if self.optics_multiplier not in (1, 2, 4) or isinstance(self.optics_multiplier, bool):
            raise AxiscalError(f"optics_multiplier must be 1, 2 or 4, not {self.optics_multiplier!r}")
        if self.rate_hz is not None:
            check_number("rate_hz", self.rate_hz, positive=True, high=1e6)
        if self.unit not in ("mm", "in"):
            raise AxiscalError(f"unit must be mm or in, not {self.unit!r}")
        if self.counts_per_mm is not None:
            check_number("counts_per_mm", self.counts_per_mm, positive=True, high=MAX_COUNTS_PER_MM, unit="counts per mm")


def is_instrument_spec(spec: str) -> bool:
    """Whether ``spec`` names one of the instruments of this room (or its simulator).

    Parameters
    ----------
    spec : str

    Returns
    -------
    bool
    """
    if not isinstance(spec, str):
        return False
    kind, sep, rest = spec.partition(":")
    kind = kind.strip().lower()
    if kind == "sim":
        return rest.strip().lower() in INSTRUMENT_KINDS
    return kind in INSTRUMENT_KINDS


def _channel(options: InstrumentOptions, allowed: tuple[str, ...], default: str, spec: str) -> str:
    channel = default if options.channel is None else str(options.channel).strip().upper()
    if channel not in allowed:
        raise AxiscalError(f"channel must be one of {', '.join(allowed)} for the source '{spec}', not {options.channel!r}")
    return channel


def _umd_settings(options: InstrumentOptions, spec: str):
    from axiscal.devices.umd import UmdSettings

    return UmdSettings(wavelength_m=float(options.wavelength_m), optics_multiplier=options.optics_multiplier,
                       channel=int(_channel(options, ("1", "2", "3"), "1", spec)), rate_hz=options.rate_hz,
                       version=options.umd_version, material_temperature_code=options.material_temperature_code)


def _open_real(kind: str, argument: str, options: InstrumentOptions, spec: str):
    if kind == "umd":
        from axiscal.devices.umd import UmdSource

        settings = _umd_settings(options, spec)
        port, baud = parse_port(argument, what=spec, default_baud=115200)
        link = SerialLink(port, SerialFraming(baud))
        return UmdSource(link, settings, f"µMD on {port}")
    if kind == "sylvac":
        from axiscal.devices.sylvac import SYLVAC_FRAMING, SylvacSource

        if options.unit not in ("mm", "in"):
            raise AxiscalError(f"unit must be mm or in for a Sylvac gauge ('{spec}'), not {options.unit!r}")
        port, baud = parse_port(argument, what=spec, default_baud=SYLVAC_FRAMING.baud)
        link = SerialLink(port, SerialFraming(baud, 7, "E", 2))
        source = SylvacSource(link, options.unit, f"Sylvac gauge on {port}")
        source.first_reading()
        return source
    if kind == "mahr":
        from axiscal.devices.mahr import MahrSource

        port, baud = parse_port(argument, what=spec, default_baud=9600)
        source = MahrSource(SerialLink(port, SerialFraming(baud)), f"Mahr Millimar on {port}")
        source.first_reading()
        return source
    if kind == "touchdro":
        from axiscal.devices.touchdro import TOUCHDRO_AXES, TouchDroSource

        axis = _channel(options, TOUCHDRO_AXES, "X", spec)
        if options.counts_per_mm is None or not (math.isfinite(options.counts_per_mm) and options.counts_per_mm > 0):
            raise AxiscalError(f"counts_per_mm must give the scale's counts per millimetre for '{spec}' (e.g. 200 for a 5 um scale)")
        port, baud = parse_port(argument, what=spec, default_baud=115200)
        return TouchDroSource(SerialLink(port, SerialFraming(baud)), axis, float(options.counts_per_mm),
                              f"TouchDRO {axis} scale on {port}")
    from axiscal.devices.attocube import ATTOCUBE_PORT, AttocubeSource

    channel = int(_channel(options, ("1", "2", "3"), "1", spec))
    host, sep, port = argument.rpartition(":")
    if not sep or not port.isdigit():
        host, port = argument, str(ATTOCUBE_PORT)
    host = host.strip("[] ")
    if not host or not 0 < int(port) < 65536:
        raise AxiscalError(f"source '{spec}': expected attocube:HOST[:PORT] with a port 1-65535")
    source = AttocubeSource(TcpLink(host, int(port)), channel, f"Attocube IDS at {host}:{port}")
    source.first_reading()
    return source


class _Simulated:
    """A simulator and the source reading it, closed together."""

    def __init__(self, source, simulator, fd: int | None):
        self._source, self._simulator, self._fd = source, simulator, fd

    def __getattr__(self, name):
        return getattr(self._source, name)

    def read(self, timeout_s):
        return self._source.read(timeout_s)

    def close(self) -> None:
        self._source.close()
        self._simulator.stop()
        if self._fd is not None:
            from axiscal.devices.simulators import close_pty_pair

            close_pty_pair(self._fd)


def _open_sim(kind: str, options: InstrumentOptions, spec: str, position: Callable[[float], float] | None, *,
              seed: int = 0, pace: bool = True):
    from axiscal.devices import simulators as sims

    if position is None:
        raise AxiscalError(f"source '{spec}': the simulator follows a machine: run it with the plan (capture) or a controller (run)")
    if kind == "attocube":
        simulator = sims.AttocubeSimulator(position).start()
        return _Simulated(_open_real(kind, f"127.0.0.1:{simulator.port}", options, spec), simulator, None)
    fd, path = sims.open_pty_pair()
    if kind == "umd":
        version = options.umd_version or 2
        simulator = sims.UmdSimulator(fd, position, version=version, rate_hz=1000.0 if version == 2 else 610.35,
                                      air=(20.2, 101_325.0, 45.0) if version == 1 else None, noise_m=2e-9, seed=seed,
                                      pace=pace, wavelength_m=float(options.wavelength_m),
                                      optics_multiplier=options.optics_multiplier)
    elif kind == "sylvac":
        simulator = sims.SylvacSimulator(fd, position, seed=seed)
    elif kind == "mahr":
        simulator = sims.MahrSimulator(fd, position, seed=seed)
    else:
        simulator = sims.TouchDroSimulator(fd, position, counts_per_mm=options.counts_per_mm or 1000.0)
        if options.counts_per_mm is None:
            options = InstrumentOptions(**{**options.__dict__, "counts_per_mm": 1000.0})
    simulator.start()
    try:
        source = _open_real(kind, path, options, spec)
    except Exception:
        simulator.stop()
        sims.close_pty_pair(fd)
        raise
    source.status.description = f"simulated {source.status.description}"
    return _Simulated(source, simulator, fd)


def open_instrument(spec: str, options: InstrumentOptions | None = None, *,
                    position: Callable[[float], float] | None = None, seed: int = 0, pace: bool = True):
    """Open the instrument a ``--source`` value names, as a source the capture reads.

    Parameters
    ----------
    spec : str
        ``umd:PORT[@BAUD]``, ``sylvac:PORT``, ``mahr:PORT[@BAUD]``, ``touchdro:PORT[@BAUD]``,
        ``attocube:HOST[:PORT]`` or ``sim:KIND`` (KIND one of these).
    options : InstrumentOptions, optional
        The instrument flags.
    position : callable, optional, keyword-only
        For ``sim:KIND``: metres along the axis at time t, seconds (the simulated machine).
    seed : int, keyword-only
        Noise seed of a simulator (0 to 2**63 - 1).
    pace : bool, keyword-only
        A simulator follows the clock (default) or streams as fast as read.

    Returns
    -------
    an instrument source
        With ``read(timeout_s)``, ``channels`` (``reading_mm`` first), ``status``, ``finished``,
        ``faults_between(start_s, end_s)`` and ``close()``.

    Raises
    ------
    AxiscalError
        For an unknown kind, a bad port, baud or channel, a port that does not exist or cannot be
        opened, or a polled instrument that does not answer.
    """
    options = InstrumentOptions() if options is None else options
    if not isinstance(options, InstrumentOptions):
        raise AxiscalError(f"options must be InstrumentOptions, not {type(options).__name__}")
    seed = check_count("seed", seed, minimum=0, maximum=MAX_SEED)
    if not isinstance(spec, str):
        raise AxiscalError(f"spec must be an instrument such as 'umd:/dev/ttyACM0', not {type(spec).__name__}")
    kind, sep, argument = spec.partition(":")
    kind = kind.strip().lower()
    if kind == "sim":
        sim_kind = argument.strip().lower()
        if sim_kind not in INSTRUMENT_KINDS:
            raise AxiscalError(f"unknown simulator '{spec}'; use sim:{', sim:'.join(INSTRUMENT_KINDS)}")
        return _open_sim(sim_kind, options, spec, position, seed=seed, pace=pace)
    if kind not in INSTRUMENT_KINDS or not argument.strip():
        raise AxiscalError(f"unknown instrument '{spec}'; use umd:PORT[@BAUD], sylvac:PORT, mahr:PORT, touchdro:PORT or"
                           " attocube:HOST[:PORT]")
    return _open_real(kind, argument.strip(), options, spec)


def default_stability_m(source, given_m: float | None, *, fallback_m: float = 1e-6) -> float:
    """The stop stability to use: the one given, else two counts of a gauge's resolution (at least 1 um).

    Parameters
    ----------
    source : an instrument source
    given_m : float or None, metres
        ``--stability-um`` when the user gave it.
    fallback_m : float, metres, keyword-only
        The default for a laser (1 um).

    Returns
    -------
    float, metres
    """
    if given_m is not None:
        return given_m
    resolution = float(getattr(source, "resolution_m", 0.0) or 0.0)
    return max(fallback_m, 2.0 * resolution)
