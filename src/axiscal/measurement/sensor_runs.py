"""Calibration runs of the 6-DOF sensors, every channel at once: gain, offset and residual band per channel.

Paper 000 section 4.1: each PSD is displaced against an inductive probe, each quadrant and roll
detector tilted against an autocollimator, and ``reference = gain * raw + offset`` is fitted by
least squares (:func:`axiscal.instruments.calibration.fit_sensitivity`); the paper's sensors stay
within +-1 um (PSD) and +-1 arcsec (angle detectors) of the reference. The runs of a campaign are
one table, ``channel, raw, reference``, the reference in the channel's unit (um for spot shifts,
mm for a scale); an angle channel's residual is also given as the angle it stands for: the spot
shift over the focal length (quadrant detector, paper 000 eq 2) or over twice the focal length
(roll by autocollimation, eq 3).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.instruments.calibration import ChannelCalibration, fit_sensitivity
from axiscal.io.arguments import check_path
from axiscal.io.tabular import read_csv
from axiscal.measurement.pipeline import MeasurementSystem
from axiscal.units import ARCSEC, MM, UM

__all__ = ["SENSOR_RUN_COLUMNS", "SensorRuns", "calibrate_sensor_runs"]

#: the columns of a calibration runs table
SENSOR_RUN_COLUMNS = ("channel", "raw", "reference")


@dataclass(frozen=True)
class SensorRuns:
    """The fits of every channel of a calibration runs table.

    Attributes
    ----------
    fits : dict of str to ChannelCalibration
        Per channel, in the order the table first names them: gain, offset, residual band (the
        channel's unit).
    units : dict of str to str
        Per channel, its unit (``"um"``, or ``"mm"`` for a scale).
    angle_m : dict of str to float
        Per angle channel, the spot shift that one radian gives, m (focal length, or twice it for
        a roll detector).
    source : str
        The table read.
    """

    fits: dict[str, ChannelCalibration]
    units: dict[str, str]
    angle_m: dict[str, float]
    source: str

    def residual_arcsec(self, channel: str) -> float | None:
        """Largest residual of an angle channel as an angle, arcsec (None for a translation channel)."""
        if channel not in self.angle_m:
            return None
        return self.fits[channel].residual_max * UM / self.angle_m[channel] / ARCSEC

    def figures(self) -> dict[str, Any]:
        """``calibration_um``: the largest residual of the translation channels in um (None when there
        are none); ``calibration_arcsec``: that of the angle channels in arcsec; ``channels``."""
        lengths = [f.residual_max * (MM / UM if self.units[c] == "mm" else 1.0) for c, f in self.fits.items()
                   if c not in self.angle_m]
        angles = [self.residual_arcsec(c) for c in self.angle_m]
        return {
            "calibration_um": max(lengths) if lengths else None,
            "calibration_arcsec": max(angles) if angles else None,
            "channels": len(self.fits),
        }

    def rows(self) -> list[dict[str, Any]]:
        """One row per channel: ``channel``, ``gain``, ``offset``, ``residual_max``, ``residual_rms``,
        ``unit``, ``residual_max_arcsec`` (angle channels) and ``points``."""
        return [
            {"channel": c, "gain": f.gain, "offset": f.offset, "residual_max": f.residual_max, "residual_rms": f.residual_rms,
             "unit": self.units[c], "residual_max_arcsec": self.residual_arcsec(c), "points": f.points}
            for c, f in self.fits.items()
        ]


def calibrate_sensor_runs(path: str | Path, *, machine: str | Path | None = None) -> SensorRuns:
    """Fit every channel of a calibration runs table (paper 000 section 4.1).

    Parameters
    ----------
    path : str or Path
        CSV with ``channel`` (a raw channel of the machine's sensors, e.g. ``x_psd_y_um``),
        ``raw`` and ``reference`` (what the reference instrument read, in the channel's unit), one
        row per calibration point; 3 points or more per channel.
    machine : str or Path, optional, keyword-only
        Machine TOML with the sensor geometry (default: the virtual module of paper 000).

    Returns
    -------
    SensorRuns

    Raises
    ------
    AxiscalError
        Naming the file (and the line): missing columns, a channel the machine does not have,
        a channel with fewer than 3 points or raw readings that do not vary, a value that is not
        a number.

    Examples
    --------
    >>> runs = calibrate_sensor_runs("examples/campaign/sensor_calibration_runs.csv")  # doctest: +SKIP
    >>> runs.figures()["calibration_arcsec"] < 1.0  # doctest: +SKIP
    True
    """
    from axiscal.measurement.system import load_system

    path = check_path("path", path)
    system: MeasurementSystem = load_system(machine)
    table = read_csv(path, min_rows=3)
    table.require(*SENSOR_RUN_COLUMNS)
    names = [name.strip() for name in table.text("channel")]
    raw = table.numeric("raw")
    reference = table.numeric("reference")
    roles = {name: (head, role) for head in system.heads.values() for role, name in head.channels.items()}
    order: list[str] = []
    for row, name in enumerate(names):
        if name not in roles:
            raise AxiscalError(f"unknown channel '{name}'; channels are: {', '.join(system.channels)}", path=path,
                               line=table.line_of(row))
        if name not in order:
            order.append(name)
    fits, units, angle_m = {}, {}, {}
    for name in order:
        rows = np.flatnonzero(np.asarray(names) == name)
        try:
            fits[name] = fit_sensitivity(name, raw[rows], reference[rows])
        except AxiscalError as exc:
            raise AxiscalError(exc.message, path=path, line=table.line_of(int(rows[0]))) from None
        head, role = roles[name]
        units[name] = "mm" if role == "scale" else "um"
        if role in ("qd_u", "qd_v"):
            angle_m[name] = head.qd_focal_m
        elif role == "roll":
            angle_m[name] = 2.0 * head.roll_focal_m
    return SensorRuns(fits, units, angle_m, str(path))
