"""The calibrations of the 6-DOF measurement system from files: what ``axiscal calibrate`` does
(paper 000 section 4): the sensitivity of each channel against a reference instrument, and the
mirror's flatness and the roll from autocollimation (eqs 11-12), written as the calibration file
the measurement applies."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.instruments.calibration import (
    Calibration,
    fit_mirror,
    fit_sensitivity,
    load_calibration,
    save_calibration,
    transfer_reference,
)
from axiscal.instruments.reports import render_report
from axiscal.instruments.sensors import roll_from_autocollimation
from axiscal.io.arguments import check_array, check_count, check_mapping, check_path
from axiscal.io.tabular import CsvTable, read_csv
from axiscal.measurement.system import load_system
from axiscal.measurement.pipeline import MeasurementSystem
from axiscal.units import ARCSEC, MM, UM, angle_factor, length_factor, split_unit

__all__ = ["calibrate_sensitivity", "calibrate_mirror", "calibration_text"]


def _channel_role(system: MeasurementSystem, channel: str):
    if not isinstance(channel, str):
        raise AxiscalError(f"channel must be a channel name, not {channel!r}")
    for letter, head in system.heads.items():
        for role, name in head.channels.items():
            if name == channel:
                return letter, head, role
    raise AxiscalError(f"unknown channel '{channel}'; channels are: {', '.join(system.channels)}")


def _reference_column(table: CsvTable, kinds: tuple[str, ...]) -> tuple[str, str]:
    for column in table.header:
        if column.startswith("reference_"):
            _, unit = split_unit(column)
            if unit not in kinds:
                raise AxiscalError(f"column '{column}': reference unit must be one of {', '.join(kinds)}", path=table.path, line=table.header_line)
            return column, unit
    raise AxiscalError(f"missing column 'reference_<unit>' (unit one of {', '.join(kinds)})", path=table.path, line=table.header_line)


def _angle_column(table: CsvTable, stem: str) -> np.ndarray:
    for unit in ("urad", "arcsec"):
        if table.has(f"{stem}_{unit}"):
            return table.numeric(f"{stem}_{unit}") * angle_factor(unit)
    raise AxiscalError(f"missing column '{stem}_urad' (or _arcsec), needed to transfer the reference", path=table.path, line=table.header_line)


def _save(calibration: Calibration, output: str | Path | None, report: dict[str, Any]) -> dict[str, Any]:
    """Merge ``calibration`` into the file ``output`` (created when missing) and note it in the report."""
    if output is not None:
        merged = load_calibration(output).merged(calibration) if Path(output).exists() else calibration
        save_calibration(merged, output)
        report["output"] = str(output)
    return report


def _line_fit_uncertainty(x: np.ndarray, residual_rms: float) -> tuple[float, float]:
    """Standard uncertainties of gain and offset of a least-squares line ``y = gain * x + offset``.

    The ordinary least-squares standard errors (those ``scipy.stats.linregress`` gives): with ``s``
    the residual standard deviation on n - 2 degrees of freedom, u(gain) = s / sqrt(Sxx) and
    u(offset) = s * sqrt(1/n + mean(x)^2 / Sxx).
    """
    x = np.asarray(x, dtype=float)
    n = len(x)
    if n <= 2:
        return math.inf, math.inf
    s = residual_rms * math.sqrt(n / (n - 2))
    sxx = float(np.sum((x - x.mean()) ** 2))
    if sxx == 0:
        return math.inf, math.inf
    return s / math.sqrt(sxx), s * math.sqrt(1.0 / n + float(x.mean()) ** 2 / sxx)


def _significant_place(scale: float, digits: int = 2) -> int:
    """Decimals that show ``digits`` significant digits of ``scale`` (0 for a zero or non-finite scale)."""
    if not (math.isfinite(scale) and scale > 0):
        return 6
    return max(0, digits - 1 - math.floor(math.log10(scale)))


def calibration_text(report: Mapping[str, Any]) -> str:
    """A calibration report (:func:`calibrate_sensitivity`, :func:`calibrate_mirror`) as text, to the digits that mean something.

    A value with a standard uncertainty (``gain`` and ``gain_u``, ``offset_<unit>`` and
    ``offset_u_<unit>``) is rounded to the second significant digit of its uncertainty; an
    uncertainty, a residual, a range and the cross-validation values are given to two significant
    digits; counts and names as they are. Full precision is in the report itself (``--json``).

    Parameters
    ----------
    report : mapping
        The report dict.

    Returns
    -------
    str
        One ``name: value`` line per entry.

    Examples
    --------
    >>> print(calibration_text({"channel": "x_psd_y_um", "gain": 0.9549890195972108, "gain_u": 0.000123456, "points": 21}), end="")
    channel: x_psd_y_um
    gain: 0.95499
    gain_u: 0.00012
    points: 21
    """
    check_mapping("report", report, what="a calibration report (calibrate_sensitivity, calibrate_mirror)")
    if not report:
        raise AxiscalError("report holds nothing to show")
    lines = []
    for key, value in report.items():
        if isinstance(value, (list, tuple)):
            shown = " ".join(f"{v:.{_significant_place(max(abs(x) for x in value))}f}" for v in value) if value else ""
        elif isinstance(value, bool) or isinstance(value, (int, str)) or value is None:
            shown = str(value)
        else:
            if key == "gain":
                u = report.get("gain_u")
            elif key.startswith("offset_") and not key.startswith("offset_u_"):
                u = report.get("offset_u_" + key.removeprefix("offset_"))
            else:
                u = None
            scale = u if isinstance(u, float) else abs(value)
            shown = f"{value:.{_significant_place(scale)}f}"
        lines.append((key, shown))
    return render_report("measurement/calibration.txt.j2", lines=lines)


def calibrate_sensitivity(
    run_path: str | Path,
    channel: str,
    *,
    machine: str | Path | None = None,
    reference_offset_m: Sequence[float] | None = None,
    output: str | Path | None = None,
) -> dict[str, Any]:
    """Gain and offset of one channel by least squares against a reference instrument (paper 000 section 4.1).

    Parameters
    ----------
    run_path : str or Path
        CSV with the raw channel column and a reference column: ``reference_um`` / ``_mm`` /
        ``_nm`` for scale and PSD channels, ``reference_arcsec`` / ``_urad`` for the quadrant and
        roll detectors.
    channel : str
        The raw channel calibrated, e.g. ``"x_psd_y_um"``.
    machine : str or Path, optional
        Machine TOML with the sensor geometry (default: the virtual module).
    reference_offset_m : sequence of 3 floats, optional
        Sensor point minus reference point, m: the reference of a translation is first moved to
        the sensor's point (section 4.2) with the run's angle columns ``E<A,B,C><axis>_urad`` or
        ``_arcsec``.
    output : str or Path, optional
        Calibration file (JSON) to create or update.

    Returns
    -------
    dict
        ``channel``, ``gain``, ``gain_u`` and ``offset_<unit>``, ``offset_u_<unit>`` (each with
        its standard uncertainty from the fit's residuals), ``residual_max_<unit>``,
        ``residual_rms_<unit>`` (the channel's unit), ``points``; for angle channels also
        ``residual_max_arcsec``; ``output`` when written.

    Raises
    ------
    AxiscalError
        For an unknown channel, missing or wrong columns, an offset on an angle channel, or an
        output that cannot be written.
    """
    run_path = check_path("run_path", run_path)
    system = load_system(machine)
    letter, head, role = _channel_role(system, channel)
    table = read_csv(run_path, min_rows=3)
    raw = table.numeric(channel)
    kind = role.split("_")[0]
    angular = kind in ("qd", "roll")
    column, unit = _reference_column(table, ("arcsec", "urad") if angular else ("nm", "um", "mm"))
    reference = table.numeric(column)
    channel_unit = MM if kind == "scale" else UM
    if angular:
        component = {"qd_u": head.qd_u, "qd_v": head.qd_v, "roll": head.roll}[role]
        focal = head.qd_focal_m if kind == "qd" else 2.0 * head.roll_focal_m
        reference = component.sign * reference * angle_factor(unit) * focal / channel_unit
        if reference_offset_m is not None:
            raise AxiscalError("reference_offset_m applies to translation channels (scale, PSD), not to angles")
    else:
        reference = reference * length_factor(unit, allowed=("nm", "um", "mm")) / channel_unit
        if reference_offset_m is not None:
            offset = check_array("reference_offset_m", reference_offset_m, ndim=1, last=3)
            eps = np.column_stack([_angle_column(table, f"E{r}{letter}") for r in "ABC"])
            component = head.index if kind == "scale" else "xyz".index(role.split("_")[1])
            reference = transfer_reference(reference * channel_unit, eps, offset, component) / channel_unit
    fit = fit_sensitivity(channel, raw, reference)
    unit_name = "mm" if kind == "scale" else "um"
    u_gain, u_offset = _line_fit_uncertainty(raw, fit.residual_rms)
    report: dict[str, Any] = {
        "channel": channel,
        "gain": fit.gain,
        "gain_u": u_gain,
        "offset_" + unit_name: fit.offset,
        "offset_u_" + unit_name: u_offset,
        "residual_max_" + unit_name: fit.residual_max,
        "residual_rms_" + unit_name: fit.residual_rms,
        "points": fit.points,
    }
    if angular:
        report["residual_max_arcsec"] = fit.residual_max * channel_unit / focal / ARCSEC
    return _save(Calibration({channel: fit}), output, report)


def calibrate_mirror(
    run_path: str | Path,
    letter: str,
    *,
    machine: str | Path | None = None,
    max_order: int = 12,
    output: str | Path | None = None,
) -> dict[str, Any]:
    """Map the roll detector's plane mirror against a level (paper 000 eqs 11-12).

    The roll channel's sensitivity calibration (from the machine's calibration file, then from
    ``output`` if it exists) is applied first; the form error module - level is fitted by a
    Legendre polynomial whose order leave-one-out cross-validation picks.

    Parameters
    ----------
    run_path : str or Path
        CSV with ``position_mm``, the raw roll channel (e.g. ``x_roll_um``) and ``level_arcsec``
        or ``level_urad``.
    letter : str
        The axis whose mirror was mapped.
    machine : str or Path, optional
        Machine TOML with the sensor geometry (default: the virtual module).
    max_order : int
        Highest polynomial order tried.
    output : str or Path, optional
        Calibration file (JSON) to create or update.

    Returns
    -------
    dict
        ``axis``, ``order``, ``residual_max_arcsec``, ``residual_rms_arcsec``,
        ``form_error_range_arcsec``, ``cv_rms_arcsec`` (list, one per order tried), ``points``;
        ``output`` when written.

    Raises
    ------
    AxiscalError
        For an axis without sensors, missing columns or an output that cannot be written.
    """
    run_path = check_path("run_path", run_path)
    if not isinstance(letter, str):
        raise AxiscalError(f"letter must be an axis letter, not {letter!r}")
    max_order = check_count("max_order", max_order, minimum=0)
    letter = letter.upper()
    system = load_system(machine)
    if output is not None and Path(output).exists():
        system = system.with_calibration(load_calibration(output))
    if letter not in system.heads:
        raise AxiscalError(f"letter: axis {letter} has no sensors in this machine (axes: {', '.join(system.axes)})")
    head = system.heads[letter]
    channel = head.channels["roll"]
    table = read_csv(run_path, min_rows=4)
    position = table.numeric("position_mm") * MM
    shift = system.calibration.channel(channel).apply(table.numeric(channel)) * UM
    module_roll = head.roll.sign * roll_from_autocollimation(shift, head.roll_focal_m)
    level = _angle_column(table, "level")
    mirror = fit_mirror(letter, position, module_roll, level, max_order=max_order)
    report: dict[str, Any] = {
        "axis": letter,
        "order": mirror.order,
        "residual_max_arcsec": mirror.residual_max_rad / ARCSEC,
        "residual_rms_arcsec": mirror.residual_rms_rad / ARCSEC,
        "form_error_range_arcsec": float(np.ptp(mirror.evaluate(np.linspace(mirror.start_m, mirror.end_m, 200)))) / ARCSEC,
        "cv_rms_arcsec": [v / ARCSEC for v in mirror.cv_rms_rad],
        "points": mirror.points,
    }
    return _save(Calibration({}, {letter: mirror}), output, report)
