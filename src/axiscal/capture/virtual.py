"""The virtual machine: a positioning program run on one axis of a machine model, read by a laser over time.

The program's moves and dwells (:func:`axiscal.io.gcode.program_motions`) are executed on the
axis as a controller would: each move a trapezoidal velocity profile at the programmed feed (rapid
moves at the rapid rate) with a constant acceleration, the axis at rest between moves (exact
stop), each dwell held for its time. Where the axis is:

``position = m + e(m) + reversal + settle + creep``, with ``m = c + correction(c, direction)``

- ``c`` the commanded position, ``correction`` the controller's pitch compensation read back from
  its file (:func:`axiscal.compensation.readback.read_compensation`; none by default), applied
  for the direction of travel as that controller documents;
- ``e`` the machine model's error along the axis at the functional point (the other axes at
  zero; beyond the error table's travel its end value), :meth:`axiscal.model.Machine.volumetric_error`;
- ``reversal`` half the reversal error against the direction of travel (an axis approached from
  below stops short);
- ``settle`` a decaying oscillation after each arrival (``A exp(-t/tau) sin(2 pi f t)``) and
  ``creep`` a slow exponential approach to the final position.

The laser reads ``position * n_air(t)`` (a raw reading computed with the vacuum wavelength) plus
white noise, with the air temperature, pressure and humidity drifting slowly over the run and
recorded beside the reading, so that the air compensation explains the drift. The noise-free
reading is kept, so that a test can compare what is captured with the truth.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.capture.recording import Recording
from axiscal.compensation.readback import ControllerCompensation
from axiscal.errors import AxiscalError
from axiscal.instruments.air import refractive_index
from axiscal.instruments.interferometer import HENE_WAVELENGTH_NM
from axiscal.io.arguments import check_count, check_instance, check_number
from axiscal.io.atomic import atomic_write
from axiscal.io.jsonio import named_from, write_sidecar
from axiscal.model.machine import Machine
from axiscal.units import MM, UM

__all__ = ["VirtualAxis", "SimulatedRecording", "simulate_motions", "simulate_capture", "write_recording"]


@dataclass(frozen=True)
class VirtualAxis:
    """How the virtual axis moves, settles and is read (SI units).

    Attributes
    ----------
    acceleration_m_s2 : float
        Acceleration and deceleration of every move (default 1 m/s^2).
    rapid_m_s : float
        Speed of rapid moves (default 0.1 m/s, 6 m/min).
    reversal_m : float
        Reversal error of the axis (default 4 um).
    repeatability_m : float
        Standard deviation of where the axis stops from one arrival to the next (default 0.2 um).
    settle_m : float
        Amplitude of the oscillation after each arrival (default 2 um).
    settle_hz, settle_s : float
        Its frequency (25 Hz) and decay time constant (0.06 s).
    creep_m, creep_s : float
        Creep after arrival (0.3 um, time constant 0.25 s).
    noise_m : float
        Standard deviation of the laser's white noise (default 20 nm).
    air_drift_c : float
        Rise of the air temperature over the run (default 0.4 degC, from 20.2 degC).
    periodic_m, pitch_m : float
        A periodic error of the screw, ``periodic_m sin(2 pi m / pitch_m)`` at motor position
        ``m`` (default none; pitch 5 mm).
    """

    acceleration_m_s2: float = 1.0
    rapid_m_s: float = 0.1
    reversal_m: float = 4e-6
    repeatability_m: float = 0.2e-6
    settle_m: float = 2e-6
    settle_hz: float = 25.0
    settle_s: float = 0.06
    creep_m: float = 0.3e-6
    creep_s: float = 0.25
    noise_m: float = 20e-9
    air_drift_c: float = 0.4
    periodic_m: float = 0.0
    pitch_m: float = 5e-3

    def __post_init__(self) -> None:
        for name in ("acceleration_m_s2", "rapid_m_s", "settle_hz", "settle_s", "creep_s", "pitch_m"):
            check_number(name, getattr(self, name), positive=True)
        for name in ("reversal_m", "repeatability_m", "settle_m", "creep_m", "noise_m", "air_drift_c", "periodic_m"):
            check_number(name, getattr(self, name), nonnegative=True)


@dataclass(frozen=True)
class SimulatedRecording:
    """What the laser read while the virtual machine ran the program.

    Attributes
    ----------
    recording : Recording
        Time, raw reading (metres) and the air sensors.
    clean_m : ndarray, shape (n,), metres
        The reading without its noise (the truth a capture is compared with).
    dwells : ndarray, shape (k, 3)
        Each dwell of the program: arrival time (s), departure time (s), commanded position (m).
    directions : ndarray of str, shape (k,)
        The direction of the move that ended at each dwell.
    settings : dict
        What was simulated (axis, rate, seed, compensation ...), for the sidecar.
    position_m : ndarray, shape (n,), metres, or None
        The controller's position stream at each sample time, stamped late by the delay asked
        for (None when none was recorded).
    """

    recording: Recording
    clean_m: np.ndarray
    dwells: np.ndarray
    directions: np.ndarray
    settings: Mapping[str, Any] = field(default_factory=dict)
    position_m: np.ndarray | None = None

    def true_stop_means(self, window_s: float) -> np.ndarray:
        """Mean noise-free reading over the last ``window_s`` of each dwell, metres, shape (k,)."""
        t = self.recording.time_s
        out = np.empty(len(self.dwells))
        for k, (_, leave, _) in enumerate(self.dwells):
            a, b = np.searchsorted(t, [leave - window_s, leave], side="left")
            out[k] = self.clean_m[a:b].mean()
        return out


def _segments(motions: Sequence[Any], axis: str, spec: VirtualAxis, start_m: float, continuous: bool = False):
    """Moves and dwells on ``axis`` as arrays: start time, duration, from, to, top speed, kind (0 move, 1 dwell).

    ``continuous``: consecutive moves in the same direction at the same feed, with no dwell
    between, are one move (the controller blends them, as in path mode): the axis passes their
    ends without stopping.
    """
    x = start_m
    items: list[list[float]] = []  # [kind, from, to, speed, dwell]
    for motion in motions:
        kind = motion.kind
        if kind == "dwell":
            if motion.dwell_s > 0:
                items.append([1, x, x, 0.0, float(motion.dwell_s)])
            continue
        if kind not in ("rapid", "feed"):
            raise AxiscalError(f"line {motion.line}: the virtual machine runs straight moves and dwells, not {kind!r} motions")
        target = float(motion.end_m.get(axis, x))
        if target == x:
            continue
        speed = spec.rapid_m_s if kind == "rapid" or not motion.feed_m_per_s else float(motion.feed_m_per_s)
        last = items[-1] if items else None
        if (continuous and last is not None and last[0] == 0 and last[3] == speed
                and np.sign(target - last[2]) == np.sign(last[2] - last[1])):
            last[2] = target
        else:
            items.append([0, x, target, speed, 0.0])
        x = target
    if not items:
        raise AxiscalError(f"the program never moves axis {axis}")
    t = 0.0
    rows = []
    for kind, a, b, speed, dwell in items:
        if kind == 1:
            rows.append((t, dwell, a, b, 0.0, 1))
            t += dwell
            continue
        distance = abs(b - a)
        top = min(speed, np.sqrt(distance * spec.acceleration_m_s2))
        ramp = top / spec.acceleration_m_s2
        duration = 2 * ramp + (distance - top * ramp) / top
        rows.append((t, duration, a, b, top, 0))
        t += duration
    if not any(row[5] == 0 for row in rows):  # nothing but dwells (or nothing at all): no stop to read
        raise AxiscalError(f"the program never moves {axis}")
    return np.array(rows)


def _moves(motions: Sequence[Any], axis: str) -> bool:
    """Whether a straight move of the program takes ``axis`` anywhere (from 0, where the virtual axis starts)."""
    x = 0.0
    for motion in motions:
        if motion.kind in ("rapid", "feed"):
            target = float(motion.end_m.get(axis, x))
            if target != x:
                return True
            x = target
    return False


def _commanded(time_s: np.ndarray, seg: np.ndarray, acceleration: float) -> tuple[np.ndarray, np.ndarray]:
    """Commanded position and segment index at each time (the trapezoidal profiles evaluated)."""
    k = np.clip(np.searchsorted(seg[:, 0], time_s, side="right") - 1, 0, len(seg) - 1)
    start, duration, a, b, top = seg[k, 0], seg[k, 1], seg[k, 2], seg[k, 3], seg[k, 4]
    tau = np.clip(time_s - start, 0.0, duration)
    ramp = np.divide(top, acceleration)
    distance = np.abs(b - a)
    travelled = np.where(
        tau < ramp, 0.5 * acceleration * tau**2,
        np.where(tau <= duration - ramp, 0.5 * top * ramp + top * (tau - ramp),
                 distance - 0.5 * acceleration * (duration - tau) ** 2),
    )
    travelled = np.where(seg[k, 5] == 1, 0.0, np.clip(travelled, 0.0, distance))
    return a + np.sign(b - a) * travelled, k


def simulate_motions(
    motions: Sequence[Any],
    machine: Machine,
    *,
    axis: str,
    compensation: ControllerCompensation | None = None,
    rate_hz: float = 1000.0,
    seed: int = 0,
    spec: VirtualAxis | None = None,
    lead_s: float = 1.0,
    wavelength_nm: float = HENE_WAVELENGTH_NM,
    continuous: bool = False,
    position_delay_s: float | None = None,
) -> SimulatedRecording:
    """Run a program's motions on one axis of the machine model and record what a laser reads.

    Parameters
    ----------
    motions : sequence of Motion
        The program's blocks (:func:`axiscal.io.gcode.program_motions`): rapid and feed moves,
        dwells; positions in metres, feeds in m/s.
    machine : Machine
        The machine model whose axis runs the program.
    axis : str, keyword-only
        The axis letter the laser is aligned with (a linear axis of the chain).
    compensation : ControllerCompensation, optional, keyword-only
        The pitch compensation loaded in the virtual controller (none by default).
    rate_hz : float, keyword-only
        Samples per second of the laser (default 1000).
    seed : int, keyword-only
        Seed of the noise (default 0).
    spec : VirtualAxis, optional, keyword-only
        Acceleration, reversal, settling, noise and air drift (defaults of :class:`VirtualAxis`).
    lead_s : float, keyword-only
        Time the axis stands at its start before the program runs (default 1 s).
    wavelength_nm : float, keyword-only
        The laser's vacuum wavelength (default He-Ne, 632.991 nm).
    continuous : bool, keyword-only
        Blend consecutive moves in one direction at one feed into one move (path mode): the axis
        passes the targets without stopping, as an on-the-fly capture needs (default False:
        exact stop at the end of every move). The settling after a turnaround ends when the next
        move begins.
    position_delay_s : float, seconds, optional, keyword-only
        Record the controller's position stream beside the reading (``position_m``): the
        commanded position, each sample stamped this late (the controller's position at time
        ``t - delay`` carries the stamp ``t``). None (default) records none.

    Returns
    -------
    SimulatedRecording

    Raises
    ------
    AxiscalError
        For an axis that is not a linear axis of the machine, an arc motion, a program that never
        moves the axis, or a rate, seed or delay out of range.
    """
    check_instance("machine", machine, Machine)
    if not isinstance(axis, str) or axis not in machine.letters or axis in machine.rotary:
        raise AxiscalError(f"axis {axis!r} is not a linear axis of the machine ({', '.join(machine.letters)})")
    if compensation is not None:
        check_instance("compensation", compensation, ControllerCompensation)
    rate_hz = check_number("rate_hz", rate_hz, positive=True, high=1e6, unit="Hz")
    seed = check_count("seed", seed, minimum=0)
    spec = VirtualAxis() if spec is None else check_instance("spec", spec, VirtualAxis)
    lead_s = check_number("lead_s", lead_s, nonnegative=True, unit="s")
    check_instance("continuous", continuous, bool)
    if position_delay_s is not None:
        position_delay_s = check_number("position_delay_s", position_delay_s, low=-1.0, high=1.0, unit="s")
    seg = _segments(motions, axis, spec, 0.0, continuous)
    seg[:, 0] += lead_s
    total = float(seg[-1, 0] + seg[-1, 1]) + lead_s
    if total * rate_hz > 5e7:
        raise AxiscalError(f"the program runs {total:.6g} s: {total * rate_hz:.3g} samples at {rate_hz:g} Hz is more than"
                           " the virtual machine records (5e7)")
    time_s = np.arange(int(np.ceil(total * rate_hz))) / rate_hz
    commanded, k = _commanded(time_s, seg, spec.acceleration_m_s2)
    moves = seg[:, 5] == 0
    move_sign = np.where(moves, np.sign(seg[:, 3] - seg[:, 2]), 0.0)
    # direction of travel: that of the segment's move, or of the last move before a dwell
    last_move = np.maximum.accumulate(np.where(moves, np.arange(len(seg)), -1))
    sign_of_seg = np.where(last_move >= 0, move_sign[np.maximum(last_move, 0)], 1.0)
    direction = sign_of_seg[k]
    motor = commanded.copy()
    if compensation is not None:
        up = direction > 0
        motor[up] += compensation.correction(commanded[up], "+")
        motor[~up] += compensation.correction(commanded[~up], "-")
    start, end = machine.travel_m(axis)
    positions = {letter: np.zeros_like(motor) for letter in machine.letters}
    positions[axis] = np.clip(motor, start, end)
    index = "XYZ".index(axis) if axis in "XYZ" else None
    if index is None:
        raise AxiscalError(f"axis {axis!r}: the laser reads X, Y or Z")
    error = machine.volumetric_error(positions)[:, index]
    rng = np.random.default_rng([seed, 20])
    scatter = rng.normal(0.0, spec.repeatability_m, len(seg))  # where each move ends, arrival to arrival
    position = motor + error - direction * spec.reversal_m / 2 + scatter[np.maximum(last_move, 0)][k]
    if spec.periodic_m:
        position += spec.periodic_m * np.sin(2 * np.pi * motor / spec.pitch_m)
    # settling and creep after each arrival (the end of every move), the last two arrivals summed
    arrive = seg[moves, 0] + seg[moves, 1]
    arrive_sign = move_sign[moves]
    j = np.searchsorted(arrive, time_s, side="right") - 1
    for back in (0, 1):
        i = j - back
        ok = i >= 0
        dt = np.where(ok, time_s - arrive[np.maximum(i, 0)], np.inf)
        sgn = arrive_sign[np.maximum(i, 0)]
        live = ok & (dt < 12 * max(spec.settle_s, spec.creep_s))
        if continuous:  # the axis leaves a turnaround at once: its settling ends with the next move's start
            nxt = np.searchsorted(seg[:, 0], arrive[np.maximum(i, 0)] - 1e-9)
            leave = np.where(nxt < len(seg), seg[np.minimum(nxt, len(seg) - 1), 0], np.inf)
            live &= ~((seg[np.minimum(nxt, len(seg) - 1), 5] == 0) & (time_s >= leave))
        ring = spec.settle_m * np.exp(-dt[live] / spec.settle_s) * np.sin(2 * np.pi * spec.settle_hz * dt[live])
        creep = -sgn[live] * spec.creep_m * np.exp(-dt[live] / spec.creep_s)
        position[live] += sgn[live] * ring + creep
    fraction = time_s / max(total, 1e-9)
    air_c = 20.2 + spec.air_drift_c * fraction + 0.02 * np.sin(2 * np.pi * time_s / 120.0)
    pressure = 101200.0 - 30.0 * fraction
    humidity = 45.0 + 2.0 * fraction
    sensors = {"air_temperature_c": np.round(air_c, 4), "pressure_pa": np.round(pressure, 2), "humidity_pct": np.round(humidity, 2)}
    n_air = refractive_index(sensors["air_temperature_c"], sensors["pressure_pa"], sensors["humidity_pct"], wavelength_nm)
    clean = position * n_air
    reading = clean + rng.normal(0.0, spec.noise_m, clean.size)
    dwell_rows = seg[seg[:, 5] == 1]
    dwell_dir = np.where(sign_of_seg[seg[:, 5] == 1] > 0, "+", "-")
    dwells = np.column_stack([dwell_rows[:, 0], dwell_rows[:, 0] + dwell_rows[:, 1], dwell_rows[:, 3]])
    settings = {"axis": axis, "rate_hz": rate_hz, "seed": seed, "duration_s": total,
                "compensation": None if compensation is None else compensation.controller,
                "virtual_axis": {"acceleration_m_s2": spec.acceleration_m_s2, "rapid_mm_min": spec.rapid_m_s / MM * 60,
                                 "reversal_um": spec.reversal_m / UM,
                                 "repeatability_um": spec.repeatability_m / UM, "settle_um": spec.settle_m / UM,
                                 "settle_hz": spec.settle_hz, "settle_s": spec.settle_s, "creep_um": spec.creep_m / UM,
                                 "creep_s": spec.creep_s, "noise_um": spec.noise_m / UM, "air_drift_c": spec.air_drift_c},
                "wavelength_nm": wavelength_nm}
    if spec.periodic_m:
        settings["virtual_axis"].update(periodic_um=spec.periodic_m / UM, pitch_mm=spec.pitch_m / MM)
    if continuous:
        settings["continuous"] = True
    position = None
    if position_delay_s is not None:
        position = _commanded(time_s - position_delay_s, seg, spec.acceleration_m_s2)[0]
        settings["position_delay_ms"] = position_delay_s * 1e3
    recording = Recording(time_s, reading, sensors, "<virtual machine>", {})
    return SimulatedRecording(recording, clean, dwells, dwell_dir, settings, position)


def write_recording(simulated: SimulatedRecording, path: str | Path, *, program: str | None = None) -> Path:
    """Write a simulated recording as the CSV ``capture --from`` reads, with its JSON sidecar (atomically).

    Columns ``time_s, reading_mm, air_temperature_c, pressure_pa, humidity_pct``; the reading is
    raw (computed with the vacuum wavelength), to 1e-9 mm. A recording with the controller's
    position stream has ``position_mm`` after the reading (to 1e-7 mm).

    Parameters
    ----------
    simulated : SimulatedRecording
    path : str or Path
        The CSV to write.
    program : str, optional, keyword-only
        The program file run, named in the sidecar.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    AxiscalError
        If the file cannot be written.
    """
    import pandas as pd

    check_instance("simulated", simulated, SimulatedRecording)
    rec = simulated.recording
    position = {} if simulated.position_m is None else {"position_mm": simulated.position_m / MM}
    frame = pd.DataFrame({"time_s": rec.time_s, "reading_mm": rec.reading_m / MM, **position, **rec.channels})
    formats = {"time_s": "%.6f", "reading_mm": "%.9f", "position_mm": "%.7f", "air_temperature_c": "%.4f",
               "pressure_pa": "%.2f", "humidity_pct": "%.2f"}
    formats = {k: v for k, v in formats.items() if k in frame}
    for name, fmt in formats.items():
        frame[name] = frame[name].map(fmt.__mod__) if len(frame) < 2000 else np.char.mod(fmt, frame[name].to_numpy())
    atomic_write(path, lambda target: frame.to_csv(target, index=False, lineterminator="\n"))
    settings = dict(simulated.settings)
    for key in ("program", "compensation_file"):
        if settings.get(key):
            settings[key] = named_from(settings[key], path)
    units = {"reading_mm": "mm, raw reading computed with the vacuum wavelength"}
    if position:
        units["position_mm"] = "mm, the controller's position stream, stamped late by position_delay_ms"
    write_sidecar(path, kind="laser recording (virtual machine)", units=units, sources=[named_from(program, path)] if program else [], **settings)
    return Path(path)


def _dialect_of(path: Path, dialect: str | None) -> str:
    from axiscal.io.gcode import DIALECTS

    if dialect is not None:
        return dialect
    by_extension = {d.extension: name for name, d in DIALECTS.items() if d.extension in (".ngc", ".mpf", ".h")}
    return by_extension.get(path.suffix.lower(), "linuxcnc")


def simulate_capture(
    program: str | Path,
    machine: Machine | str | Path,
    output: str | Path | None = None,
    *,
    axis: str,
    dialect: str | None = None,
    compensation: str | Path | None = None,
    controller: str | None = None,
    comp_type: int = 1,
    reference_position_m: float = 0.0,
    rate_hz: float = 1000.0,
    seed: int = 0,
    spec: VirtualAxis | None = None,
    wavelength_nm: float = HENE_WAVELENGTH_NM,
    continuous: bool = False,
    position_delay_s: float | None = None,
) -> SimulatedRecording:
    """Run a program file on the virtual machine, with a controller's compensation loaded, and record the laser.

    Parameters
    ----------
    program : str or Path
        The program file, in ``dialect``.
    machine : Machine, str or Path
        The machine model (or its machine.toml).
    output : str or Path, optional
        Where to write the recording (:func:`write_recording`); None writes nothing.
    axis : str, keyword-only
        The axis the laser reads.
    dialect : str, optional, keyword-only
        The program's dialect (default: ``heidenhain`` for ``.h``, ``sinumerik`` for ``.mpf``,
        else ``linuxcnc``).
    compensation : str or Path, optional, keyword-only
        A compensation file to load into the virtual controller.
    controller : {"linuxcnc", "fanuc", "siemens", "heidenhain"}, optional, keyword-only
        Whose file ``compensation`` is (needed with it).
    comp_type, reference_position_m : keyword-only
        As :func:`axiscal.compensation.readback.read_compensation` takes them (LinuxCNC's file
        type; FANUC's reference position, metres).
    rate_hz, seed, spec, wavelength_nm, continuous, position_delay_s : keyword-only
        As :func:`simulate_motions` takes them.

    Returns
    -------
    SimulatedRecording

    Raises
    ------
    AxiscalError
        Naming the file and line: a program the dialect's reader refuses, a compensation file
        the controller would refuse; a compensation without its controller; as
        :func:`simulate_motions`.

    Examples
    --------
    >>> rec = simulate_capture("x.ngc", "examples/xfyz_machine/machine.toml", "x.csv", axis="X")  # doctest: +SKIP
    """
    from axiscal.compensation.readback import read_compensation
    from axiscal.io.gcode import program_motions
    from axiscal.io.tabular import read_text
    from axiscal.model.machine import as_machine

    program = Path(program) if isinstance(program, (str, Path)) else program
    text = read_text(program)
    motions = program_motions(text, dialect=_dialect_of(Path(program), dialect), source=str(program))
    model = as_machine(machine)
    loaded = None
    if compensation is not None:
        if controller is None:
            raise AxiscalError("a compensation file needs its controller (linuxcnc, fanuc, siemens or heidenhain)")
        try:
            loaded = read_compensation(read_text(compensation), controller, comp_type=comp_type,
                                       reference_position_m=reference_position_m)
        except AxiscalError as exc:
            raise exc.located(path=compensation) from None
    elif controller is not None:
        raise AxiscalError("a controller is given without its compensation file")
    if isinstance(axis, str) and axis in model.letters and not _moves(motions, axis):
        raise AxiscalError(f"the program never moves {axis}", path=program)
    simulated = simulate_motions(motions, model, axis=axis, compensation=loaded, rate_hz=rate_hz, seed=seed, spec=spec,
                                 wavelength_nm=wavelength_nm, continuous=continuous, position_delay_s=position_delay_s)
    simulated = SimulatedRecording(simulated.recording, simulated.clean_m, simulated.dwells, simulated.directions,
                                   {**simulated.settings, "program": str(program),
                                    "compensation_file": None if compensation is None else str(compensation)},
                                   simulated.position_m)
    if output is not None:
        write_recording(simulated, output, program=str(program))
    return simulated
