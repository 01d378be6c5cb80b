"""Connect, as a technician does: the computer's serial ports, each spec checked before connecting, and what
the instrument and the controller say about themselves once connected, for every axis the visit moves.

Specs are those of ``axiscal run`` (docs/devices.md). :func:`check_spec` reads one without opening
anything: its kind, its port and baud rate (a serial port must be one the computer has), its host
and port, its socket or URL. :func:`serial_ports` is pyserial's list of the computer's ports.
:func:`connect` opens both devices, reads the instrument for half a second, asks the controller
where the first axis is, whether each axis is ready (homed, out of e-stop and alarm) and each one's soft
limits (LinuxCNC's from the machine's INI file, :func:`check_ini`), then closes them; :class:`Connection`
carries what each told (a µMD's firmware, sample rate and counts per cycle; grbl's banner; LinuxCNC's
linuxcncrsh version; the limits of each axis) and the line a controller that is not ready answered.
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
from axiscal.io.arguments import check_count, check_path
from axiscal.units import MM

__all__ = ["INSTRUMENTS", "CONTROLLERS", "SIM_RATE_HZ", "Connection", "check_spec", "check_ini", "connect",
           "serial_ports", "is_virtual"]

#: the instrument and controller kinds the workbench drives (``sim``: the virtual machine; the others: ``axiscal run``'s)
INSTRUMENTS = ("sim", "umd", "sylvac", "mahr", "touchdro", "attocube")
CONTROLLERS = ("sim", "linuxcnc", "grbl", "marlin", "klipper", "moonraker")
#: samples per second of the virtual laser
SIM_RATE_HZ = 1000.0
#: the linear axes a controller is asked about
_LINEAR = "XYZ"


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


def check_ini(ini: Any) -> Path:
    """A LinuxCNC INI file named on the computer running the workbench, read once to check it.

    Parameters
    ----------
    ini : str or Path
        Its path (``~`` is the user's home; a relative path is taken from the workbench's folder).

    Returns
    -------
    Path
        The file, absolute.

    Raises
    ------
    AxiscalError
        In one line, for a file that is not there or cannot be read as an INI file.
    """
    from axiscal.devices.linuxcnc import ini_limits

    if not isinstance(ini, (str, Path)) or not str(ini).strip():
        raise AxiscalError(f"the INI file must be a path, not {ini!r}")
    path = Path(str(ini).strip()).expanduser().resolve()
    if not path.is_file():
        raise AxiscalError(f"no INI file at {path}")
    try:
        for axis in _LINEAR:
            ini_limits(path, axis)  # reads it: a file that cannot be read as an INI file is said now, not at the run
    except AxiscalError as exc:  # configparser's reason runs over lines: said in one
        raise AxiscalError(" ".join(str(exc).split())) from None
    return path


def _checked_axes(axes: Any) -> tuple[str, ...]:
    if isinstance(axes, str) or not isinstance(axes, (list, tuple)) or not axes or any(
            not isinstance(a, str) or a not in _LINEAR for a in axes):
        raise AxiscalError(f"axes must be linear axis letters such as ('X', 'Z'), not {axes!r}")
    return tuple(dict.fromkeys(axes))


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
    limits : tuple of (str, float, float)
        Each axis whose soft limits the controller told: its letter and its limits, metres.
    ini : str
        LinuxCNC's INI file the limits were read from (empty without one).
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
    limits: tuple[tuple[str, float, float], ...] = ()
    ini: str = ""

    def limits_of(self, axis: str) -> tuple[float, float] | None:
        """The soft limits of ``axis`` the controller told, metres (None where it told none)."""
        return next(((low, high) for letter, low, high in self.limits if letter == axis), None)


def connect(instrument: str = "sim", controller: str = "sim", *, seed: int = 0, axes: tuple[str, ...] = ("X",),
            ini: str | Path | None = None, machine: str | Path | None = None) -> Connection:
    """Check both specs, open the instrument and the controller, read them once, and close them.

    Parameters
    ----------
    instrument, controller : str
        Specs as ``axiscal run`` takes them; ``sim`` is the virtual machine (default).
    seed : int, keyword-only
        Seed of a simulated laser's noise.
    axes : tuple of str, keyword-only
        The linear axes the visit moves: each is checked ready and its soft limits asked (default X).
    ini : str or Path, optional, keyword-only
        LinuxCNC's INI file (:func:`check_ini`): the soft limits of each axis (a ``linuxcnc`` controller only).
    machine : str or Path, optional, keyword-only
        The machine description the virtual controller (``sim``) moves, default the built-in XZ module. It
        moves one axis, as each run makes its own: it is asked about the first of ``axes``.

    Returns
    -------
    Connection

    Raises
    ------
    AxiscalError
        For a spec :func:`check_spec` refuses, an INI file :func:`check_ini` refuses or given to
        another controller than LinuxCNC, or a device that cannot be opened (in one line).
    """
    instrument = check_spec("instrument", instrument)
    controller = check_spec("controller", controller)
    seed = check_count("seed", seed, minimum=0)
    axes = _checked_axes(axes)
    if machine is not None:
        machine = check_path("machine", machine)
    if ini is not None:
        if not controller.lower().startswith("linuxcnc:"):
            raise AxiscalError(f"an INI file is LinuxCNC's: the controller '{controller}' takes none")
        ini = check_ini(ini)
    if not is_virtual(instrument, controller):
        return _connect_devices(instrument, controller, seed, axes, ini, machine)
    noise = float(np.random.default_rng([seed, 30]).normal(0.0, 20e-9))
    return Connection(instrument, controller, "ok", "ok",
                      f"virtual laser ({SIM_RATE_HZ:g} Hz) on the virtual machine's {', '.join(axes)}", noise, 0.0,
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


def _controller_told(made: Any, axes: tuple[str, ...],
                     ini: Path | None) -> tuple[tuple[tuple[str, str], ...], str, tuple[tuple[str, float, float], ...]]:
    """What a controller said about itself and each axis's soft limits, and its refusal when an axis is not ready."""
    told = [("kind", made.description)]
    if getattr(made, "banner", ""):
        told.append(("version", made.banner))
    if getattr(made.status, "message", ""):
        told.append(("version", made.status.message))
    refused = ""
    for axis in axes:
        try:
            made.check_ready(axis)
        except AxiscalError as exc:
            refused = str(exc)
            break
    if refused:
        return tuple(told), refused, ()
    told.append(("ready", "yes (homed, out of e-stop and alarm)"))
    told += _grbl_settings_told(made, axes)
    if ini is not None:
        told.append(("INI file", str(ini)))
    limits, grbl_said = [], any(name.startswith("$20") for name, _ in told)
    for axis in axes:
        try:
            told_limits = made.limits(axis)
        except (AxiscalError, OSError) as exc:
            told.append((f"soft limits {axis}", f"not read: {exc}"))
            continue
        if told_limits is not None:
            limits.append((axis, float(told_limits[0]), float(told_limits[1])))
            told.append((f"soft limits {axis}", f"{told_limits[0] / MM:g} to {told_limits[1] / MM:g} mm"
                         + (" (INI file)" if ini is not None else "")))
        elif ini is not None:
            told.append((f"soft limits {axis}", "not in the INI file (LinuxCNC refuses a move beyond its own)"))
    if not limits and ini is None and not grbl_said:
        told.append(("soft limits", "not told (the controller refuses a move beyond its own)"))
    return tuple(told), refused, tuple(limits)


def _grbl_settings_told(made: Any, axes: tuple[str, ...]) -> list[tuple[str, str]]:
    """grbl's ``$`` settings that bound a run: soft limits ($20), homing ($22), each axis's travel ($130...)."""
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
    for axis in axes:
        travel = 130 + "XYZABC".index(axis)
        if travel in settings:
            told.append((f"${travel} {axis} max travel", f"{settings[travel]:g} mm"))
    return told


def _connect_devices(instrument: str, controller: str, seed: int, axes: tuple[str, ...], ini: Path | None,
                     machine: Path | None) -> Connection:
    """Open the devices of ``axiscal run``, read the instrument for half a second and the controller once, close."""
    from axiscal.capture.connected import open_run_devices, sim_machine

    moved = None
    if controller.lower() == "sim":  # the virtual controller moves one axis of the machine: the first asked about
        axes = axes[:1]
        moved = sim_machine(machine=machine, axis=axes[0])
    made, source = open_run_devices(controller, instrument, seed=seed, ini=ini, machine=moved)
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
            position = float(made.position(axes[0]))
            controller_state = "ok"
        except (AxiscalError, OSError):
            position, controller_state = math.nan, "lost"
        controller_told, refused, limits = _controller_told(made, axes, ini) if controller_state == "ok" else ((), "", ())
        instrument_state = "ok" if math.isfinite(reading) else "lost"
        return Connection(instrument, controller, instrument_state, "refused" if refused else controller_state,
                          f"{source.status.description}; {made.description}", reading, position,
                          _instrument_told(source), controller_told, refused, limits, "" if ini is None else str(ini))
    finally:
        source.close()
        made.close()
