"""From raw sensor frames to the spatial error of the functional point (paper 000, sections 2-3).

The pipeline of one batch of frames, vectorised over the frames:

1. calibration: ``value = gain * raw + offset`` per channel (:mod:`axiscal.instruments.calibration`);
2. sensor equations (eqs 1-3, :mod:`axiscal.instruments.sensors`): scale minus command is the positioning
   error at the read head, the PSD shift the straightness at the PSD, the quadrant detector's shift
   over f1 the pitch and yaw, the roll detector's shift over 2 f2 the roll, minus the plane
   mirror's form error at that position (eq 12);
3. Abbe-Bryan transfer (eqs 4-5): ``delta_P = delta_M + eps x (P - M)`` from the read head and the
   PSD to the point the axis' errors refer to;
4. HTM chain (eqs 6-10) of :mod:`axiscal.model.kinematics` with those per-frame errors: the spatial
   error of the functional point and its actual (corrected) position.

Faults are flagged per frame with the bits of :class:`axiscal.measurement.faults.Fault` and never
raise: a channel is missing (NaN), a channel is outside its valid range, an axis' commanded
position is outside the travel the error model covers (the machine's error table; the scale may
read a little beyond, up to its margin).
A faulty frame keeps its time stamp and fault bits; every other result of it is NaN.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.conventions import component_names
from axiscal.errors import AxiscalError
from axiscal.instruments.abbe import _transfer_components
from axiscal.instruments.calibration import (
    Calibration,
    MirrorCorrection,
    load_calibration,
)
from axiscal.instruments.sensors import SensorHead, sensor_head_from_dict
from axiscal.io.arguments import check_array, check_instance, check_mapping, check_path, check_same_length
from axiscal.io.tabular import read_toml
from axiscal.measurement.faults import Fault, fault_text
from axiscal.model.machine import Machine, machine_from_dict
from axiscal.units import MM, UM

__all__ = [
    "MeasurementSystem",
    "spatial_error",
    "diagonal_errors",
]

#: frames processed at once: big enough to amortise the Python overhead, small enough for the cache
_CHUNK = 16384



@dataclass(frozen=True)
class _AxisPlan:
    """What :meth:`MeasurementSystem.process` does for one axis, worked out once."""

    letter: str
    index: int
    cmd_row: int
    scale_row: int
    error_rows: np.ndarray
    offsets_m: np.ndarray
    roll_index: int
    roll_sign: float
    mirror: MirrorCorrection | None
    start_m: float
    end_m: float
    error_names: tuple[str, ...]
    position_name: str


def _error_names(letter: str) -> tuple[str, ...]:
    names = component_names(letter)
    return tuple(f"{n}_m" for n in names[:3]) + tuple(f"{n}_rad" for n in names[3:])


class MeasurementSystem:
    """Raw sensor frames -> six errors per axis -> Abbe-Bryan -> HTM -> spatial error of the functional point.

    Parameters
    ----------
    machine : Machine
        The HTM model (chain, squareness, tool point); its error tables give the travel of each
        axis (positions outside are faults), their values are not used: the errors are measured.
    heads : mapping of str to SensorHead
        The sensor head of every axis of the machine.
    calibration : Calibration, optional
        Channel gains and offsets and the plane-mirror corrections (default: none, identity).

    Attributes
    ----------
    channels : tuple of str
        Raw channel names in frame order; the same names serve the TCP line protocol, the
        recordings and the dashboard.
    channel_limits : dict of str to (float, float)
        Valid range of each raw channel, in its own unit.
    axes : tuple of str
        Axis letters in chain order.
    """

    def __init__(self, machine: Machine, heads: Mapping[str, SensorHead], calibration: Calibration | None = None):
        check_instance("machine", machine, Machine, what="a Machine (load_machine)")
        check_mapping("heads", heads, what="a mapping of axis letters to SensorHead")
        if not all(isinstance(h, SensorHead) for h in heads.values()):
            raise AxiscalError("heads must map axis letters to SensorHead objects (sensor_head_from_dict)")
        check_instance("calibration", calibration, (Calibration, type(None)), what="a Calibration or None")
        self.machine = machine
        self.calibration = calibration if calibration is not None else Calibration()
        self.axes = tuple(machine.letters)
        missing = [k for k in self.axes if k not in heads]
        if missing:
            raise AxiscalError(f"axis {', '.join(missing)} has no sensors section [axes.{missing[0]}.sensors]")
        self.heads = {k: heads[k] for k in self.axes}
        channels: list[str] = []
        limits: dict[str, tuple[float, float]] = {}
        self._travel: dict[str, tuple[float, float]] = {}
        for letter in self.axes:
            head = self.heads[letter]
            start, end = machine.travel_m(letter)
            self._travel[letter] = (start, end)
            for role, name in head.channels.items():
                if name in limits:
                    raise AxiscalError(f"channel name '{name}' is used twice; give the axes different sensor prefixes")
                channels.append(name)
                if role in ("cmd", "scale"):
                    margin = head.scale_margin_m
                    limits[name] = ((start - margin) / MM, (end + margin) / MM)
                elif role.startswith("psd"):
                    limits[name] = (-head.psd_range_m / UM, head.psd_range_m / UM)
                elif role == "roll":
                    limits[name] = (-head.roll_range_m / UM, head.roll_range_m / UM)
                else:
                    limits[name] = (-head.qd_range_m / UM, head.qd_range_m / UM)
        self.channels = tuple(channels)
        self.channel_limits = limits
        self._prepare()

    def _prepare(self) -> None:
        """Per-channel factors to SI (calibration and sensor equations folded in) and per-axis plans."""
        row = {name: k for k, name in enumerate(self.channels)}
        self._low = np.array([[self.channel_limits[c][0]] for c in self.channels])
        self._high = np.array([[self.channel_limits[c][1]] for c in self.channels])
        factor = np.ones(len(self.channels))
        plans = []
        for letter in self.axes:
            head = self.heads[letter]
            names = head.channels
            factor[row[names["cmd"]]] = factor[row[names["scale"]]] = MM
            error_rows = [0] * 6
            error_rows[head.index] = row[names["scale"]]
            for d in head.cross_directions:
                factor[row[names[f"psd_{d}"]]] = UM
                error_rows["xyz".index(d)] = row[names[f"psd_{d}"]]
            for role, focal in (("qd_u", head.qd_focal_m), ("qd_v", head.qd_focal_m), ("roll", 2.0 * head.roll_focal_m)):
                component = getattr(head, role)
                factor[row[names[role]]] = component.sign * UM / focal
                error_rows[component.index] = row[names[role]]
            start, end = self._travel[letter]
            plans.append(
                _AxisPlan(
                    letter=letter,
                    index=head.index,
                    cmd_row=row[names["cmd"]],
                    scale_row=row[names["scale"]],
                    error_rows=np.array(error_rows),
                    offsets_m=head.offsets_m(),
                    roll_index=head.roll.index,
                    roll_sign=head.roll.sign,
                    mirror=self.calibration.mirrors.get(letter),
                    start_m=start,
                    end_m=end,
                    error_names=_error_names(letter),
                    position_name=f"{letter.lower()}_m",
                )
            )
        calibrations = [self.calibration.channel(c) for c in self.channels]
        self._scale_si = np.array([[c.gain * f] for c, f in zip(calibrations, factor)])
        self._offset_si = np.array([[c.offset * f] for c, f in zip(calibrations, factor)])
        self._plans = tuple(plans)

    @classmethod
    def from_toml(cls, path: str | Path, *, calibration: Calibration | None = None) -> "MeasurementSystem":
        """Read a machine TOML with ``[axes.<L>.sensors]`` sections (docs/formats.md, "Sensor geometry").

        The calibration files named by ``calibration = "..."`` in the sensor sections (relative to
        the TOML file) are loaded and applied; ``calibration`` given here is merged on top.
        """
        path = check_path("path", path)
        check_instance("calibration", calibration, (Calibration, type(None)), what="a Calibration or None")
        data = read_toml(path)
        machine = machine_from_dict(data, base_dir=path.parent, source=str(path))
        heads: dict[str, SensorHead] = {}
        loaded = Calibration()
        seen: set[Path] = set()
        try:
            for letter, section in dict(data.get("axes", {})).items():
                if "sensors" not in section:
                    continue
                heads[letter] = sensor_head_from_dict(letter, section["sensors"])
                name = section["sensors"].get("calibration")
                if name is not None:
                    file = path.parent / str(name)
                    if file not in seen:
                        seen.add(file)
                        loaded = loaded.merged(load_calibration(file))
            system = cls(machine, heads, loaded if calibration is None else loaded.merged(calibration))
        except AxiscalError as exc:
            raise exc.located(path=path) from None
        return system

    def with_calibration(self, calibration: Calibration) -> "MeasurementSystem":
        """The same system with ``calibration`` merged over its own.

        Parameters
        ----------
        calibration : Calibration
            Entries that add to or replace the system's own.

        Returns
        -------
        MeasurementSystem
            A new system; this one is unchanged.
        """
        check_instance("calibration", calibration, Calibration, what="a Calibration")
        return MeasurementSystem(self.machine, self.heads, self.calibration.merged(calibration))

    def fault_text(self, fault: int) -> str:
        """The fault bits of a frame in words.

        Parameters
        ----------
        fault : int
            The frame's fault bits.

        Returns
        -------
        str
            ``"ok"`` for 0; see :func:`axiscal.measurement.faults.fault_text`.
        """
        return fault_text(fault)

    def channel_faults(self, frames: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Fault bits (missing, out of range) of every raw channel separately.

        Parameters
        ----------
        frames : mapping of str to ndarray, shape (N,)
            Raw channels (an absent one counts as missing).

        Returns
        -------
        dict of str to ndarray of int64, shape (N,)
            Per channel ``Fault.MISSING`` and ``Fault.RANGE`` bits.
        """
        n = _batch_size(frames)
        out = {}
        for name in self.channels:
            value = np.asarray(frames[name], dtype=float) if name in frames else np.full(n, np.nan)
            low, high = self.channel_limits[name]
            bits = np.where(np.isnan(value), int(Fault.MISSING), 0).astype(np.int64)
            bits |= np.where((value < low) | (value > high), int(Fault.RANGE), 0)
            out[name] = bits
        return out

    def process(self, frames: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Turn a batch of raw frames into errors, spatial error and corrected position.

        Parameters
        ----------
        frames : mapping of str to ndarray, shape (N,)
            ``"t_s"`` and every channel of :attr:`channels`, each in its own unit (NaN or an
            absent key: missing).

        Returns
        -------
        dict of str to ndarray, shape (N,)
            All SI: ``"t_s"``; per axis the six errors at the axis' functional point
            (``"EXX_m"``, ``"EYX_m"``, ``"EZX_m"``, ``"EAX_rad"``, ``"EBX_rad"``, ``"ECX_rad"``,
            ...); the scale positions ``"x_m"``, ``"z_m"``; the spatial error ``"ex_m"``,
            ``"ey_m"``, ``"ez_m"`` and its length ``"e_m"``; the actual functional point
            ``"px_m"``, ``"py_m"``, ``"pz_m"``; and ``"fault"`` (int64 bits of
            :class:`~axiscal.measurement.faults.Fault`, 0 = good). Results of a faulty frame are
            NaN. :func:`axiscal.measurement.display.to_display` gives the columns files and
            screens show (``"EXX_um"``, ``"x_mm"``, ...).

        Raises
        ------
        AxiscalError
            If the frame columns differ in length or none is given.
        """
        n = _batch_size(frames)
        if n <= _CHUNK:
            return self._process(frames, n)
        pieces = [
            self._process({k: v[start : start + _CHUNK] for k, v in frames.items()}, min(_CHUNK, n - start))
            for start in range(0, n, _CHUNK)
        ]
        return {k: np.concatenate([p[k] for p in pieces]) for k in pieces[0]}

    def _process(self, frames: Mapping[str, np.ndarray], n: int) -> dict[str, np.ndarray]:
        raw = np.empty((len(self.channels), n))
        for row, name in enumerate(self.channels):
            column = frames.get(name)
            raw[row] = np.nan if column is None else column
        fault = np.where(np.any(np.isnan(raw), axis=0), int(Fault.MISSING), 0).astype(np.int64)
        outside = np.any((raw < self._low) | (raw > self._high), axis=0)
        fault |= np.where(outside, int(Fault.RANGE), 0)
        si = raw * self._scale_si
        si += self._offset_si
        if np.any(fault):
            # a missing or out-of-range reading faults its frame, whose results all become NaN below;
            # zero stands in for it meanwhile so that the shared transfer and mirror map, which
            # refuse non-finite input, still see only numbers
            si[:, fault != 0] = np.where(np.isfinite(si[:, fault != 0]), si[:, fault != 0], 0.0)
        out: dict[str, np.ndarray] = {"t_s": np.asarray(frames.get("t_s", np.full(n, np.nan)), dtype=float)}
        command: dict[str, np.ndarray] = {}
        measured: dict[str, np.ndarray] = {}
        for plan in self._plans:
            cmd = si[plan.cmd_row]
            fault |= np.where((cmd < plan.start_m) | (cmd > plan.end_m), int(Fault.POSITION), 0)
            errors = si[plan.error_rows]
            errors[plan.index] -= cmd
            if plan.mirror is not None:
                errors[plan.roll_index] -= plan.roll_sign * plan.mirror._evaluate(cmd)
            # the batch is checked once above: the unchecked paths of the mirror map and the transfer
            errors[:3] = _transfer_components(errors[:3].T.copy(), errors[3:].T, plan.offsets_m).T
            command[plan.letter] = cmd
            measured[plan.letter] = errors
            for name, row in zip(plan.error_names, errors):
                out[name] = row
            out[plan.position_name] = si[plan.scale_row]
        bad = fault != 0
        if np.any(bad):
            command = {k: np.where(bad, self._travel[k][0], q) for k, q in command.items()}
        error = spatial_error(self.machine, command, measured)
        actual = self.machine.nominal_point(command) + error
        error_t = np.ascontiguousarray(error.T)
        actual_t = np.ascontiguousarray(actual.T)
        for k, axis in enumerate("xyz"):
            out[f"e{axis}_m"] = error_t[k]
        # element by element in a fixed order: a reduction (einsum) may round differently with the
        # memory alignment of the batch, and a stream split anywhere must give the same numbers
        out["e_m"] = np.sqrt(error_t[0] * error_t[0] + error_t[1] * error_t[1] + error_t[2] * error_t[2])
        for k, axis in enumerate("xyz"):
            out[f"p{axis}_m"] = actual_t[k]
        if np.any(bad):
            for name, value in out.items():
                if name != "t_s":
                    value[bad] = np.nan
        out["fault"] = fault
        return out


def spatial_error(machine: Machine, positions_m: Mapping[str, np.ndarray], errors: Mapping[str, np.ndarray]) -> np.ndarray:
    """Spatial error of the functional point from error motions known at each point (paper 000 eq 10).

    The HTM chain of ``machine`` (squareness, origins, tool point) with the error tables replaced
    by the given per-point values, e.g. measured live.

    Parameters
    ----------
    machine : Machine
        The model; its tables are not used.
    positions_m : mapping of str to ndarray, shape (N,)
        Nominal (commanded) position of every axis, metres (finite).
    errors : mapping of str to ndarray, shape (6, N)
        Per axis the rows tx, ty, tz (m) and ea, eb, ec (rad) at the axis' reference point.

    Returns
    -------
    ndarray, shape (N, 3)
        Actual minus nominal functional point, in the workpiece frame, metres.
    """
    check_instance("machine", machine, Machine, what="a Machine (load_machine)")
    check_mapping("positions_m", positions_m, machine.letters, what=f"a mapping of every axis ({', '.join(machine.letters)}) to positions in metres")
    check_mapping("errors", errors, machine.letters, what=f"a mapping of every axis ({', '.join(machine.letters)}) to its (6, N) error motions")
    for letter in machine.letters:
        shape = np.shape(errors[letter])
        if len(shape) != 2 or shape[0] != 6:
            raise AxiscalError(f"errors['{letter}'] must have shape (6, N), rows tx, ty, tz, ea, eb, ec; not {shape}")
    return machine.volumetric_error(positions_m, errors=errors, workers=1)


def _batch_size(frames: Mapping[str, np.ndarray]) -> int:
    check_mapping("frames", frames, what="a mapping of channel names to readings")
    for name, value in frames.items():
        kind = np.asarray(value).dtype.kind
        if kind not in "iuf" or np.ndim(value) > 1:
            raise AxiscalError(f"frames['{name}'] must be a one-dimensional array of readings (numbers), not {value!r}"[:200])
    sizes = {np.shape(v)[0] if np.ndim(v) else 1 for v in frames.values()}
    if len(sizes) > 1:
        raise AxiscalError(f"frame columns (frames) have different lengths: {sorted(sizes)}")
    if not sizes:
        raise AxiscalError("no frame columns given")
    return sizes.pop()


def diagonal_errors(
    x_m: np.ndarray, z_m: np.ndarray, error_m: np.ndarray, laser_m: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Paper 000 eq (13): the XZ diagonal's error before and after the error model.

    ``E_BD = sqrt(xm^2 + zm^2) - P_MCV`` and
    ``E_AD = sqrt((xm + xe)^2 + ye^2 + (zm + ze)^2) - P_MCV``.

    Parameters
    ----------
    x_m, z_m : ndarray, shape (n,)
        Nominal axis moves from the diagonal's start, metres.
    error_m : ndarray, shape (n, 3)
        Spatial error (xe, ye, ze) of the functional point relative to its value at the start
        (where the interferometer was zeroed), metres.
    laser_m : ndarray, shape (n,)
        Interferometer reading P_MCV along the diagonal, metres.

    Returns
    -------
    before, after : ndarray, shape (n,)
        E_BD and E_AD, metres.
    """
    x, z, laser = (check_array(n, a, ndim=1) for n, a in (("x_m", x_m), ("z_m", z_m), ("laser_m", laser_m)))
    e = check_array("error_m", error_m, ndim=2, last=3)
    check_same_length(x_m=x, z_m=z, error_m=e, laser_m=laser)
    before = np.hypot(x, z) - laser
    after = np.sqrt((x + e[:, 0]) ** 2 + e[:, 1] ** 2 + (z + e[:, 2]) ** 2) - laser
    return before, after
