"""Connect, as a technician does: the computer's serial ports, each spec checked before connecting, and what
the instrument and the controller say about themselves once connected.

Specs are those of ``axiscal run`` (docs/devices.md). :func:`check_spec` reads one without opening
anything: its kind, its port and baud rate (a serial port must be one the computer has), its host
and port, its socket or URL. :func:`serial_ports` is pyserial's list of the computer's ports.
:func:`connect` opens both devices, reads the instrument for half a second, asks the controller
where the axis is, whether it is ready (homed, out of e-stop and alarm) and its soft limits, then
closes them; :class:`Connection` carries what each told (a µMD's firmware, sample rate and counts
per cycle; grbl's banner; LinuxCNC's linuxcncrsh version; the limits) and the line a controller
that is not ready answered.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from urllib.parse import urlparse

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count
from axiscal.units import MM

__all__ = ["INSTRUMENTS", "CONTROLLERS", "SIM_RATE_HZ", "Connection", "check_spec", "connect", "serial_ports",
           "is_virtual"]

#: the instrument and controller kinds the workbench drives (``sim``: the virtual machine; the others: ``axiscal run``'s)
INSTRUMENTS = ("sim", "umd", "sylvac", "mahr", "touchdro", "attocube")
CONTROLLERS = ("sim", "linuxcnc", "grbl", "marlin", "klipper", "moonraker")
#: samples per second of the virtual laser
SIM_RATE_HZ = 1000.0
#: the axis the workbench measures
_AXIS = "X"


def serial_ports() -> list[dict[str, Any]]:
    """The computer's serial ports, as pyserial lists them.

    Parameters
    ----------
    (none)

    Returns
    -------
    list of dict
        ``device``, ``description``, ``hwid``, ``vid`` and ``pid`` (USB ids as 4 hex digits, or None),
        ``serial_number``, ``manufacturer``; sorted by device.
    """
    from serial.tools import list_ports

    out = []
    for port in list_ports.comports():
        out.append({"device": port.device, "description": port.description if port.description != "n/a" else "",
                    "hwid": port.hwid if port.hwid != "n/a" else "",
                    "vid": None if port.vid is None else f"{port.vid:04x}",
                    "pid": None if port.pid is None else f"{port.pid:04x}",
                    "serial_number": port.serial_number, "manufacturer": port.manufacturer})
    return sorted(out, key=lambda p: p["device"])


def _serial_port(spec: str, argument: str, default_baud: int) -> None:
    from axiscal.devices.links import parse_port

    port, _ = parse_port(argument, what=spec, default_baud=default_baud)
    if Path(port).exists():
        return
    known = [p["device"] for p in serial_ports()]
    if port not in known:
        raise AxiscalError(f"'{spec}': this computer has no serial port {port}"
                           f" ({'its ports: ' + ', '.join(known) if known else 'it lists none'})")


def _host_port(spec: str, argument: str, form: str, *, port_needed: bool = False) -> None:
    host, sep, port = argument.rpartition(":")
    if not sep:
        host, port = argument, ""
    if not host.strip("[] ") or (port_needed and not port) or (port and not (port.isdigit() and 0 < int(port) < 65536)):
        raise AxiscalError(f"'{spec}': expected {form} with a port 1-65535")


def check_spec(role: str, spec: Any) -> str:
    """Read an instrument's or a controller's spec without opening anything.

    Parameters
    ----------
    role : {"instrument", "controller"}
    spec : str
        As ``axiscal run`` takes it (``umd:/dev/ttyUSB0``, ``linuxcnc:cnc.local``, ``sim`` ...).

    Returns
    -------
    str
        The spec, stripped.

    Raises
    ------
    AxiscalError
        For a kind the workbench does not drive, a serial port the computer does not have, a baud
        rate that is not a whole number, a host without a name or with a port outside 1-65535, a
        Klipper socket that is not there, a Moonraker address that is not an http(s) URL.
    """
    from axiscal.devices.instruments import INSTRUMENT_KINDS

    if role not in ("instrument", "controller"):
        raise AxiscalError(f"role must be instrument or controller, not {role!r}")
    if not isinstance(spec, str) or not spec.strip():
        raise AxiscalError(f"{role} must be a spec such as 'sim', not {spec!r}")
    spec = spec.strip()
    kind, _, argument = spec.partition(":")
    kind, argument = kind.lower(), argument.strip()
    known = INSTRUMENTS if role == "instrument" else CONTROLLERS
    if kind not in known:
        raise AxiscalError(f"{role} '{spec}': use one of {', '.join(known)} (as `axiscal run` takes them, docs/devices.md)")
    if kind == "sim":
        if role == "instrument" and argument and argument.lower() not in INSTRUMENT_KINDS:
            raise AxiscalError(f"instrument '{spec}': a simulated instrument is sim:{', sim:'.join(INSTRUMENT_KINDS)}")
        if role == "controller" and argument:
            raise AxiscalError(f"controller '{spec}': the virtual controller is 'sim' alone")
        return spec
    if not argument:
        raise AxiscalError(f"{role} '{spec}': name its port, host, socket or address after '{kind}:'")
    if kind in ("umd", "sylvac", "mahr", "touchdro", "marlin") or (kind == "grbl" and not argument.lower().startswith("tcp:")):
        _serial_port(spec, argument, 9600 if kind in ("sylvac", "mahr", "touchdro") else 115200)
    elif kind == "grbl":
        _host_port(spec, argument[4:], "grbl:tcp:HOST:PORT", port_needed=True)
    elif kind in ("attocube", "linuxcnc"):
        _host_port(spec, argument, f"{kind}:HOST[:PORT]")
    elif kind == "klipper":
        if not Path(argument).exists():
            raise AxiscalError(f"'{spec}': no Klipper API socket at {argument} (start klippy with -a {argument})")
    else:  # moonraker
        url = urlparse(argument)
        if url.scheme not in ("http", "https") or not url.hostname or any(c.isspace() for c in argument):
            raise AxiscalError(f"'{spec}': expected moonraker:http://HOST[:PORT], Moonraker's address")
    return spec


def is_virtual(instrument: str, controller: str) -> bool:
    """Whether the pair is the virtual machine the workbench runs itself (both ``sim``).

    Parameters
    ----------
    instrument, controller : str
        Specs.

    Returns
    -------
    bool
    """
    for name, spec in (("instrument", instrument), ("controller", controller)):
        if not isinstance(spec, str):
            raise AxiscalError(f"{name} must be a device spec (a str), not {type(spec).__name__}")
    return instrument.strip().lower() == "sim" and controller.strip().lower() == "sim"


@dataclass(frozen=True)
class Connection:
    """The instrument and the controller a run uses, and what they say now.

    Attributes
    ----------
    instrument, controller : str
        Their specs.
    instrument_state, controller_state : str
        ``"ok"``, ``"lost"``, ``"refused"`` (the controller is not ready) or ``"off"`` (the status lights).
    description : str
        What is connected, one line.
    reading_m : float, metres
        The instrument's latest reading.
    position_m : float, metres
        The controller's position.
    instrument_told, controller_told : tuple of (str, str)
        What each said about itself (name, value), in the order told.
    refused : str
        The controller's answer when it is not ready (not homed, e-stop, alarm); empty when ready.
    """

    instrument: str
    controller: str
    instrument_state: str
    controller_state: str
    description: str
    reading_m: float
    position_m: float
    instrument_told: tuple[tuple[str, str], ...] = ()
    controller_told: tuple[tuple[str, str], ...] = ()
    refused: str = ""


def connect(instrument: str = "sim", controller: str = "sim", *, seed: int = 0) -> Connection:
    """Check both specs, open the instrument and the controller, read them once, and close them.

    Parameters
    ----------
    instrument, controller : str
        Specs as ``axiscal run`` takes them; ``sim`` is the virtual machine (default).
    seed : int, keyword-only
        Seed of a simulated laser's noise.

    Returns
    -------
    Connection

    Raises
    ------
    AxiscalError
        For a spec :func:`check_spec` refuses, or a device that cannot be opened (in one line).
    """
    instrument = check_spec("instrument", instrument)
    controller = check_spec("controller", controller)
    seed = check_count("seed", seed, minimum=0)
    if not is_virtual(instrument, controller):
        return _connect_devices(instrument, controller, seed)
    noise = float(np.random.default_rng([seed, 30]).normal(0.0, 20e-9))
    return Connection(instrument, controller, "ok", "ok",
                      f"virtual laser ({SIM_RATE_HZ:g} Hz) on the virtual XZ module's X axis", noise, 0.0,
                      (("kind", "virtual laser"), ("sample rate", f"{SIM_RATE_HZ:g} Hz")),
                      (("kind", "virtual controller"), ("ready", "yes")))


def _instrument_told(source: Any) -> tuple[tuple[str, str], ...]:
    """What an instrument's stream said about itself: a µMD's firmware, rate and counts per cycle."""
    told = [("kind", source.status.description)]
    state = getattr(getattr(source, "decoder", None), "state", None)
    if state is not None and hasattr(state, "firmware"):  # a µMD
        if state.version is not None:
            told.append(("µMD", str(state.version)))
        if state.firmware is not None:
            told.append(("firmware", str(state.firmware)))
        if state.rate_hz is not None:
            told.append(("sample rate", f"{state.rate_hz:g} Hz"))
        told.append(("counts per cycle", str(state.counts_per_cycle) if state.counts_told else "not told"))
    if getattr(source.status, "message", ""):
        told.append(("says", source.status.message))
    return tuple(told)


def _controller_told(made: Any) -> tuple[tuple[tuple[str, str], ...], str]:
    """What a controller said about itself, and its refusal when it is not ready."""
    told = [("kind", made.description)]
    if getattr(made, "banner", ""):
        told.append(("version", made.banner))
    if getattr(made.status, "message", ""):
        told.append(("version", made.status.message))
    refused = ""
    try:
        made.check_ready(_AXIS)
        told.append(("ready", "yes (homed, out of e-stop and alarm)"))
    except AxiscalError as exc:
        refused = str(exc)
    if not refused:
        told += _grbl_settings_told(made)
        try:
            limits = made.limits(_AXIS)
        except (AxiscalError, OSError) as exc:
            limits, told = None, told + [("soft limits", f"not read: {exc}")]
        if limits is not None:
            told.append((f"soft limits {_AXIS}", f"{limits[0] / MM:g} to {limits[1] / MM:g} mm"))
        elif not any(name == "soft limits" or name.startswith("$20") for name, _ in told):
            told.append(("soft limits", "not told (the controller refuses a move beyond its own)"))
    return tuple(told), refused


def _grbl_settings_told(made: Any) -> list[tuple[str, str]]:
    """grbl's ``$`` settings that bound a run on the axis: soft limits ($20), homing ($22), the axis's travel ($130...)."""
    from axiscal.devices.grbl import GrblController

    if not isinstance(made, GrblController):
        return []
    try:
        settings = made.settings()
    except (AxiscalError, OSError) as exc:
        return [("$ settings", f"not read: {exc}")]
    told = []
    if 20 in settings:
        told.append(("$20 soft limits", "on" if settings[20] == 1 else "off: grbl refuses no move beyond its travel"))
    if 22 in settings:
        told.append(("$22 homing cycle", "on" if settings[22] == 1 else "off: machine positions count from where grbl was switched on"))
    travel = 130 + "XYZABC".index(_AXIS)
    if travel in settings:
        told.append((f"${travel} {_AXIS} max travel", f"{settings[travel]:g} mm"))
    return told


def _connect_devices(instrument: str, controller: str, seed: int) -> Connection:
    """Open the devices of ``axiscal run``, read the instrument for half a second and the controller once, close."""
    from axiscal.capture.connected import open_run_devices

    made, source = open_run_devices(controller, instrument, seed=seed)
    try:
        end = time.monotonic() + 0.5
        reading = math.nan
        while time.monotonic() < end:
            batch = source.read(0.05)
            good = np.asarray(batch.values[:, 0])[~np.asarray(batch.malformed)] if len(batch) else np.empty(0)
            good = good[np.isfinite(good)]
            if good.size:
                reading = float(good[-1]) * MM
        try:
            position = float(made.position(_AXIS))
            controller_state = "ok"
        except (AxiscalError, OSError):
            position, controller_state = math.nan, "lost"
        controller_told, refused = _controller_told(made) if controller_state == "ok" else ((), "")
        instrument_state = "ok" if math.isfinite(reading) else "lost"
        return Connection(instrument, controller, instrument_state, "refused" if refused else controller_state,
                          f"{source.status.description}; {made.description}", reading, position,
                          _instrument_told(source), controller_told, refused)
    finally:
        source.close()
        made.close()
