"""The XZ diagonal against a laser interferometer, explained by the 6-DOF sensors read at the same stops.

Paper 000 section 5, eq (13): the module steps X and Z along the diagonal; at each stop the
interferometer reads the functional point's move P_MCV along it and the 6-DOF sensors give the
spatial error (xe, ye, ze) of the functional point. ``E_BD = sqrt(xm^2 + zm^2) - P_MCV`` is the
diagonal's error before the error model, ``E_AD = sqrt((xm + xe)^2 + ye^2 + (zm + ze)^2) - P_MCV``
what is left once the measured spatial error is added (:func:`axiscal.measurement.pipeline.diagonal_errors`),
both relative to the first stop, where the interferometer is zeroed. The same with the scales'
positions alone shows what the linear scales explain by themselves. Unlike the model-based
diagonal check (ISO 230-6, :mod:`axiscal.model.diagonal`), nothing here comes from error tables
taken earlier, so a load on the slide is measured as it acts.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_mapping, check_path
from axiscal.io.tabular import read_csv
from axiscal.measurement.pipeline import diagonal_errors
from axiscal.units import MM, UM

__all__ = ["STOP_TOLERANCE_M", "SensorDiagonal", "sensor_diagonal"]

#: how far a stop may lie from the diagonal's point at its ``nominal_mm``, metres: far beyond any
#: positioning error, so that readings paired with the wrong stops (a nominal doubled, a stop left
#: out) are refused instead of read as an error of hundreds of millimetres
STOP_TOLERANCE_M = 1.0 * MM


@dataclass(frozen=True)
class SensorDiagonal:
    """E_BD and E_AD at each stop of the diagonal (paper 000 eq 13), from laser readings and 6-DOF frames.

    Attributes
    ----------
    x_m, z_m : ndarray, shape (n,)
        Nominal moves of X and Z from the first stop, m.
    laser_m : ndarray, shape (n,)
        Interferometer readings along the diagonal, m.
    before_m : ndarray, shape (n,)
        E_BD, m.
    after_m : ndarray, shape (n,)
        E_AD with the spatial error the sensors measured, m.
    scales_only_m : ndarray, shape (n,)
        The scales' diagonal (their positions alone) minus the laser, m.
    samples : int
        Frames averaged at each stop.
    """

    x_m: np.ndarray
    z_m: np.ndarray
    laser_m: np.ndarray
    before_m: np.ndarray
    after_m: np.ndarray
    scales_only_m: np.ndarray
    samples: int

    def figures(self) -> dict[str, Any]:
        """``E_BD_max_um``, ``E_AD_max_um`` (largest magnitude), ``E_BD_range_um``, ``E_AD_range_um``,
        ``scales_only_max_um``, ``stops`` and ``samples_per_stop``."""
        return {
            "E_BD_max_um": float(np.max(np.abs(self.before_m))) / UM,
            "E_AD_max_um": float(np.max(np.abs(self.after_m))) / UM,
            "E_BD_range_um": float(np.ptp(self.before_m)) / UM,
            "E_AD_range_um": float(np.ptp(self.after_m)) / UM,
            "scales_only_max_um": float(np.max(np.abs(self.scales_only_m))) / UM,
            "stops": int(self.laser_m.size),
            "samples_per_stop": self.samples,
        }


def _xz_ends(name: str, point: Mapping[str, float]) -> tuple[float, float]:
    check_mapping(name, point, what="axis positions in metres, e.g. {'X': 0.0, 'Z': 0.0}")
    if set(point) - {"X", "Z"}:
        raise AxiscalError(f"{name} names axes {', '.join(sorted(set(point) - {'X', 'Z'}))}: the diagonal is in the XZ plane")
    values = [point.get(axis, 0.0) for axis in ("X", "Z")]
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values):
        raise AxiscalError(f"{name} must hold finite positions in metres, not {dict(point)!r}")
    return float(values[0]), float(values[1])


def _point(x_m: float, z_m: float) -> str:
    return f"X={x_m / MM:.6g} Z={z_m / MM:.6g}"


def sensor_diagonal(
    readings_path: str | Path,
    frames_path: str | Path,
    *,
    start: Mapping[str, float],
    end: Mapping[str, float],
    machine: str | Path | None = None,
) -> SensorDiagonal:
    """Paper 000 eq (13) from a diagonal's laser readings and the 6-DOF frames taken at the same stops.

    Parameters
    ----------
    readings_path : str or Path
        CSV ``nominal_mm, measured_mm``: the nominal displacement along the diagonal from its
        start and the interferometer's reading at each stop, zeroed at the first.
    frames_path : str or Path
        Raw frames of the 6-DOF sensors (``t_s`` and one column per channel), the same number at
        each stop, stop after stop in the order of the readings (a live record works).
    start, end : mapping of str to float, keyword-only
        The diagonal's ends, ``{"X": ..., "Z": ...}`` in metres; the stops lie on the line between
        them at the readings' nominal displacements.
    machine : str or Path, optional, keyword-only
        Machine TOML with the sensor sections (default: the virtual module of paper 000).

    Returns
    -------
    SensorDiagonal

    Raises
    ------
    AxiscalError
        For unreadable files (naming the file and the line), ends that coincide or leave the XZ
        plane, a number of frames that is not a whole number per stop, a stop whose frames
        are all faulty, a ``nominal_mm`` off the diagonal (before its start or beyond its end) or
        more than :data:`STOP_TOLERANCE_M` from where the scales put that stop.
    """
    from axiscal.measurement.offline import measure_file

    readings_path = check_path("readings_path", readings_path)
    frames_path = check_path("frames_path", frames_path)
    x0, z0 = _xz_ends("start", start)
    x1, z1 = _xz_ends("end", end)
    length = math.hypot(x1 - x0, z1 - z0)
    if length == 0.0:
        raise AxiscalError("start and end are the same point: the diagonal has no length")
    table = read_csv(readings_path, min_rows=2)
    table.require("nominal_mm", "measured_mm")
    nominal = table.numeric("nominal_mm") * MM
    laser = table.numeric("measured_mm") * MM
    stops = nominal.size
    measured = measure_file(frames_path, machine=machine)
    results = measured.results
    frames = measured.fault.size
    if frames % stops:
        raise AxiscalError(f"{frames} frames are not the same number at each of the {stops} stops of {readings_path.name}",
                           path=frames_path)
    samples = frames // stops
    good = measured.fault == 0
    means = {}
    for key in ("ex_m", "ey_m", "ez_m", "x_m", "z_m"):
        values = np.where(good, results[key], np.nan).reshape(stops, samples)
        counted = np.isfinite(values).sum(axis=1)
        if (counted == 0).any():
            stop = int(np.flatnonzero(counted == 0)[0])
            raise AxiscalError(f"every frame of stop {stop + 1} (nominal {nominal[stop] / MM:g} mm) is faulty", path=frames_path)
        means[key] = np.nansum(values, axis=1) / counted
    error = np.column_stack([means["ex_m"], means["ey_m"], means["ez_m"]])
    x = (x1 - x0) * nominal / length
    z = (z1 - z0) * nominal / length
    apart = np.hypot(means["x_m"] - (x0 + x), means["z_m"] - (z0 + z))
    if np.any(apart > STOP_TOLERANCE_M):
        k = int(np.argmax(apart > STOP_TOLERANCE_M))
        raise AxiscalError(
            f"nominal_mm {nominal[k] / MM:g} puts stop {k + 1} at {_point(x0 + x[k], z0 + z[k])} mm on the diagonal, but"
            f" the scales of {frames_path.name} put it at {_point(means['x_m'][k], means['z_m'][k])} mm: the readings"
            f" do not match the diagonal's stops", path=readings_path, line=table.lines[k])
    off = (nominal < -STOP_TOLERANCE_M) | (nominal > length + STOP_TOLERANCE_M)
    if off.any():
        k = int(np.argmax(off))
        raise AxiscalError(f"nominal_mm {nominal[k] / MM:g} is off the diagonal from {_point(x0, z0)} to {_point(x1, z1)}"
                           f" mm, which is {length / MM:g} mm long", path=readings_path, line=table.lines[k])
    before, after = diagonal_errors(x, z, error - error[0], laser)
    scales_only = np.hypot(means["x_m"] - means["x_m"][0], means["z_m"] - means["z_m"][0]) - laser
    return SensorDiagonal(x, z, laser, before, after, scales_only, samples)
