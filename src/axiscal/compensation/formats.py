"""One call from a positioning run to the compensation table of a controller, with what it leaves uncorrected.

Chooses the controller module (LinuxCNC, FANUC, SIEMENS, HEIDENHAIN), fills in the defaults the
command line documents (interval: the mean target spacing in whole millimetres; reference
position: the first target), refuses an option that belongs to another controller instead of
ignoring it, and measures the error the table leaves at the measured targets (the residual
``e(x) - offset + c(x)`` of :func:`axiscal.compensation.curve.residuals`).

A rotary axis (a run read from ``target_deg``) is written in degrees: LinuxCNC and HEIDENHAIN
rows from the first target round to 360 deg, FANUC rotary pitch error compensation over one
revolution (3621 = 3620, the values of one revolution summing to zero), SINUMERIK modulo
compensation from 0 to 360 deg. A one-direction test gives the tables that hold one curve
(FANUC without a - direction table, SINUMERIK, HEIDENHAIN without BACKLASH); the tables that
need both directions refuse it and say why.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.compensation.curve import ErrorCurve, error_curve, residuals
from axiscal.compensation.fanuc import fanuc_table
from axiscal.compensation.heidenhain import heidenhain_table
from axiscal.compensation.linuxcnc import linuxcnc_table
from axiscal.compensation.siemens import siemens_table
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_integer, check_number, check_optional_number
from axiscal.positioning.evaluation import (
    TURN,
    PositioningRun,
    covers_circle,
    require_finite,
    target_statistics,
)
from axiscal.positioning.reader import read_positioning_run
from axiscal.units import ARCSEC, DEG, MM, UM

__all__ = ["FORMATS", "FORMAT_OPTIONS", "ROTARY_OPTIONS", "FANUC_ROTARY_INCREMENT", "MAX_CORRECTION_M", "MAX_CORRECTION_RAD",
           "CompensationResult", "compensation_table"]

#: the largest correction a table is written with unless the user raises the bound: a mean deviation
#: beyond it is a reading that is not the axis's (a unit, a scale or an offset gone wrong), not an error
#: any real axis has; 1 mm for a linear axis, 1 degree for a rotary one
MAX_CORRECTION_M = 1e-3
MAX_CORRECTION_RAD = DEG

#: the options of a linear axis (metres) and their counterparts for a rotary axis (radians)
ROTARY_OPTIONS = {"interval_m": "interval_rad", "detection_unit_m": "detection_unit_rad",
                  "reference_position_m": "reference_position_rad"}

#: input increment and default detection unit of a FANUC rotary axis (IS-B: 0.001 deg), radians
FANUC_ROTARY_INCREMENT = 0.001 * DEG

#: the controller table formats :func:`compensation_table` writes
FORMATS = ("linuxcnc", "fanuc", "siemens", "heidenhain")

#: each option of :func:`compensation_table` and the formats that read it; giving it to another
#: format is an error, not ignored
FORMAT_OPTIONS: dict[str, tuple[str, ...]] = {
    "comp_type": ("linuxcnc",),
    "interval_m": ("fanuc", "siemens"),
    "magnification": ("fanuc",),
    "detection_unit_m": ("fanuc",),
    "reference_position_m": ("fanuc", "siemens"),
    "reference_point": ("fanuc",),
    "bidirectional": ("fanuc",),
    "axis": ("siemens", "heidenhain"),
    "axis_number": ("fanuc",),
    "backlash": ("heidenhain",),
    "interval_rad": ("fanuc", "siemens"),
    "detection_unit_rad": ("fanuc",),
    "reference_position_rad": ("fanuc", "siemens"),
}


@dataclass(frozen=True)
class CompensationResult:
    """A controller compensation table and how well it corrects the measured deviations.

    Attributes
    ----------
    format : str
        One of :data:`FORMATS`.
    table : LinuxcncTable, FanucTable, SiemensTable or HeidenhainTable
        The table object (it can apply itself: ``table.correction(x, direction)``).
    text : str
        The file as the controller reads it.
    description : str
        What the table is, in one phrase (format, points, interval, unit).
    largest_residual_m : float
        Largest error left at the measured targets after the table is applied, over the
        directions the table distinguishes, metres.
    resolution_m : float
        The smallest step of a value in the table, metres.
    reference_offset_m : float
        The deviation at the reference position that a table zeroed there leaves to the
        reference position setting (FANUC; SIEMENS with a reference position), metres; 0 otherwise.
    rotary : bool
        A table of a rotary axis: the three values above are then in radians.
    """

    format: str
    table: Any
    text: str
    description: str
    largest_residual_m: float
    resolution_m: float
    reference_offset_m: float
    rotary: bool = False

    @property
    def note(self) -> str:
        """One line for the user: the table, the largest error left and the reference offset, in um (arcsec)."""
        factor, unit = (ARCSEC, "arcsec") if self.rotary else (UM, "um")
        zero_point = (
            f"; the table is zero at the reference position, whose own deviation {self.reference_offset_m / factor:+.3f}"
            f" {unit} is left to the reference position setting" if self.reference_offset_m else ""
        )
        return (
            f"{self.description}; largest error left at the measured targets {self.largest_residual_m / factor:.3f}"
            f" {unit} (table resolution {self.resolution_m / factor:g} {unit}){zero_point}"
        )


def _refuse_options_of_other_formats(fmt: str, given: dict[str, Any]) -> None:
    for name, value in given.items():
        if name not in FORMAT_OPTIONS:
            raise AxiscalError(f"unknown compensation option '{name}'; use one of {', '.join(FORMAT_OPTIONS)}")
        formats = FORMAT_OPTIONS[name]
        if value is not None and fmt not in formats:
            raise AxiscalError(f"{name} applies to format {' or '.join(formats)}, not {fmt}")


def _default_interval(targets: np.ndarray, unit: float = MM) -> float:
    """The mean target spacing rounded to whole units (mm, or degrees for a rotary axis; at least 1), SI."""
    return max(1.0, round(np.ptp(targets) / (targets.size - 1) / unit)) * unit


def _axis_options(run: PositioningRun, given: dict[str, Any]) -> dict[str, float | None]:
    """interval, detection unit and reference position in SI (m or rad), from the options of the run's kind of axis."""
    for linear, rotary in ROTARY_OPTIONS.items():
        wrong = linear if run.rotary else rotary
        if given[wrong] is not None:
            kind = "a rotary axis (targets in deg)" if run.rotary else "a linear axis"
            form = "angle (radians; degrees on the command line)" if run.rotary else "length"
            raise AxiscalError(f"{wrong} does not apply: {run.source} is a test of {kind}; give the {form} form of this option")
    pick = {linear: given[rotary] if run.rotary else given[linear] for linear, rotary in ROTARY_OPTIONS.items()}
    return {"interval": pick["interval_m"], "detection_unit": pick["detection_unit_m"],
            "reference_position": pick["reference_position_m"]}


def _needs_both_directions(fmt: str, bidirectional: bool | None, backlash: bool | None) -> str | None:
    """What in the table asked for needs a test in both directions (None: one curve will do)."""
    if fmt == "linuxcnc":
        return "a LinuxCNC COMP_FILE holds a forward and a reverse column"
    if fmt == "fanuc" and bidirectional:
        return "a bidirectional FANUC table (3605#0) holds a table for each direction"
    if fmt == "heidenhain" and backlash is not False:
        return "the BACKLASH column of a HEIDENHAIN table is the difference of the two directions (or use backlash=False)"
    return None


def _check_correction(run: PositioningRun, curve: ErrorCurve, bound: float, name: str, unit: float, unit_name: str) -> None:
    """Refuse a mean deviation beyond ``bound``: no real axis is out by that much, a reading gone wrong is."""
    for direction, values in (("+", curve.up), ("-", curve.down)):
        beyond = np.flatnonzero(np.abs(values) > bound)
        if beyond.size:
            k = int(beyond[np.argmax(np.abs(values[beyond]))])
            raise AxiscalError(
                f"the mean deviation at {curve.positions[k] / unit:.4g} {unit_name} ({direction}) is {values[k] / unit:+.6g}"
                f" {unit_name}, beyond the largest correction written ({bound / unit:g} {unit_name}): a reading in the wrong"
                f" unit or from the wrong datum, not an error of the axis; raise {name} only if the axis truly is out"
                " by that much", path=None if run.source.startswith("<") else run.source)


def compensation_table(
    run: PositioningRun | str | Path,
    fmt: str,
    *,
    comp_type: int | None = None,
    interval_m: float | None = None,
    magnification: int | None = None,
    detection_unit_m: float | None = None,
    reference_position_m: float | None = None,
    reference_point: int | None = None,
    bidirectional: bool | None = None,
    axis: str | None = None,
    axis_number: int | None = None,
    backlash: bool | None = None,
    interval_rad: float | None = None,
    detection_unit_rad: float | None = None,
    reference_position_rad: float | None = None,
    max_correction_m: float = MAX_CORRECTION_M,
    max_correction_rad: float = MAX_CORRECTION_RAD,
) -> CompensationResult:
    """The compensation table of controller ``fmt`` from the mean deviations of a positioning run.

    An option left at None takes the format's default; an option given (not None) to a format
    that does not read it (see :data:`FORMAT_OPTIONS`) is an error, and so is a length option
    for a rotary axis or an angle option for a linear one (:data:`ROTARY_OPTIONS`).

    Parameters
    ----------
    run : PositioningRun, or str or Path
        The test, metres (radians for a rotary axis), or a run file read with
        :func:`axiscal.positioning.reader.read_positioning_run`; the table corrects its mean
        deviation per direction. A one-direction test gives only the tables that hold one curve.
    fmt : {"linuxcnc", "fanuc", "siemens", "heidenhain"}
        The controller table format.
    comp_type : {0, 1}, optional, keyword-only
        linuxcnc: ``COMP_FILE_TYPE``, 0 = positions reached, 1 = corrections (default 1).
    interval_m : float, optional, keyword-only
        fanuc/siemens: spacing of the compensation points, metres (default: the mean target
        spacing rounded to whole millimetres, at least 1 mm).
    magnification : int, optional, keyword-only
        fanuc: parameter 3623, 1..100 (default 1).
    detection_unit_m : float, optional, keyword-only
        fanuc: detection unit of the axis, metres (default 1 um).
    reference_position_m : float, optional, keyword-only
        fanuc: machine position of the reference position, metres (default the first target);
        siemens: the table is shifted to be zero here (default: not shifted).
    reference_point : int, optional, keyword-only
        fanuc: compensation point number of the reference position (parameter 3620).
    bidirectional : bool, optional, keyword-only
        fanuc: a second table for travel in the - direction (3605#0 = 1; default False).
    axis : str, optional, keyword-only
        siemens: machine axis name (default "X1"); heidenhain: axis letter (default "X").
    axis_number : int, optional, keyword-only
        fanuc: axis number on the parameter tape (default 1).
    backlash : bool, optional, keyword-only
        heidenhain: write the BACKLASH column (default True); False writes one mean column.
    interval_rad : float, optional, keyword-only
        fanuc/siemens, rotary axis: spacing of the compensation points, radians (default: the
        mean target spacing rounded to whole degrees); it must divide the circle.
    detection_unit_rad : float, optional, keyword-only
        fanuc, rotary axis: detection unit, radians (default 0.001 deg).
    reference_position_rad : float, optional, keyword-only
        fanuc, rotary axis: position of the reference, radians (default the first target);
        siemens: the table is shifted to be zero here.
    max_correction_m : float, metres, keyword-only
        The largest mean deviation of a linear axis a table corrects (default
        :data:`MAX_CORRECTION_M`, 1 mm): one beyond it is refused, naming the target.
    max_correction_rad : float, radians, keyword-only
        The same for a rotary axis (default :data:`MAX_CORRECTION_RAD`, 1 degree).

    Returns
    -------
    CompensationResult
        The table, its text, a description, the largest error it leaves at the targets (m),
        its resolution (m) and the reference offset (m).

    Raises
    ------
    AxiscalError
        For an unknown format, an option of another format or of the other kind of axis, an
        option that is NaN or infinite, a run file the reader refuses (naming its line), a
        one-direction test for a table that needs both directions, a FANUC rotary table from a
        test that does not go round the circle, a mean deviation beyond ``max_correction_m``
        (``max_correction_rad``), or a value the controller's table cannot hold (see the
        controller modules).

    Examples
    --------
    >>> import numpy as np
    >>> run = PositioningRun(np.array([0.0, 0.1, 0.2]), np.full((3, 2), 2e-6), np.full((3, 2), -2e-6))
    >>> result = compensation_table(run, "heidenhain", backlash=False)
    >>> result.largest_residual_m
    0.0
    """
    if not isinstance(fmt, str) or fmt not in FORMATS:
        raise AxiscalError(f"unknown compensation table format {fmt!r}; use one of {', '.join(FORMATS)}")
    for name, value in (("bidirectional", bidirectional), ("backlash", backlash)):
        if value is not None:
            check_instance(name, value, (bool, np.bool_))
    given = dict(comp_type=comp_type, interval_m=interval_m, magnification=magnification,
                 detection_unit_m=detection_unit_m, reference_position_m=reference_position_m,
                 reference_point=reference_point, bidirectional=bidirectional, axis=axis, axis_number=axis_number,
                 backlash=backlash, interval_rad=interval_rad, detection_unit_rad=detection_unit_rad,
                 reference_position_rad=reference_position_rad)
    _refuse_options_of_other_formats(fmt, given)
    require_finite(**given)
    for name in ("interval_m", "detection_unit_m", "reference_position_m", "interval_rad", "detection_unit_rad",
                 "reference_position_rad"):
        check_optional_number(name, given[name])
    for name in ("comp_type", "magnification", "reference_point", "axis_number"):
        if given[name] is not None:
            check_integer(name, given[name])
    if axis is not None:
        check_instance("axis", axis, str, what="an axis name")
    max_correction_m = check_number("max_correction_m", max_correction_m, positive=True, high=1.0)
    max_correction_rad = check_number("max_correction_rad", max_correction_rad, positive=True, high=TURN)
    if not isinstance(run, PositioningRun):
        run = read_positioning_run(run).run
    si = _axis_options(run, given)
    if not run.bidirectional:
        need = _needs_both_directions(fmt, bidirectional, backlash)
        if need:
            raise AxiscalError(
                f"{need}: it needs a test in both directions; {run.source} goes in the {run.directions[0]} direction only"
            )
    targets = run.targets
    rotary = run.rotary
    round_the_circle = rotary and covers_circle(targets)
    curve: ErrorCurve = error_curve(target_statistics(run), period=TURN if round_the_circle else None)
    unit, unit_name = (DEG, "deg") if rotary else (MM, "mm")
    _check_correction(run, curve, max_correction_rad if rotary else max_correction_m, "max_correction_rad" if rotary
                      else "max_correction_m", unit, unit_name)
    interval = _default_interval(targets, unit) if si["interval"] is None else si["interval"]
    reference_position = si["reference_position"]
    detection_unit = si["detection_unit"]
    offset = 0.0
    one_way = "" if run.bidirectional else f", from the {run.directions[0]} direction only (reversal not measured)"
    if fmt == "linuxcnc":
        comp_type = 1 if comp_type is None else comp_type
        table = linuxcnc_table(curve.closed(), comp_type=comp_type, unit_m=unit)
        directions: tuple[str, ...] = ("+", "-")
        what = f"LinuxCNC COMP_FILE_TYPE = {comp_type}, {table.nominal.size} entries" + (", degrees" if rotary else "")
    elif fmt == "fanuc":
        if rotary and not round_the_circle:
            raise AxiscalError(
                f"FANUC rotary pitch error compensation spans one revolution: {run.source} does not go round the circle"
                f" ({targets[0] / DEG:g}..{targets[-1] / DEG:g} deg)"
            )
        rotary_settings = dict(rotary=True, travel_per_revolution=TURN, input_increment_m=FANUC_ROTARY_INCREMENT) if rotary else {}
        table = fanuc_table(
            curve,
            interval_m=interval,
            reference_position_m=targets[0] if reference_position is None else reference_position,
            reference_point=reference_point,
            magnification=1 if magnification is None else magnification,
            detection_unit_m=(FANUC_ROTARY_INCREMENT if rotary else UM) if detection_unit is None else detection_unit,
            bidirectional=bool(bidirectional),
            axis_number=1 if axis_number is None else axis_number,
            **rotary_settings,
        )
        directions = ("+", "-") if bidirectional else ("mean",)
        offset = table.reference_deviation_m
        step = f"{table.resolution / DEG:g} deg" if rotary else f"{table.resolution / UM:g} um"
        what = (f"FANUC {'rotary ' if rotary else ''}pitch error compensation, points {table.points[0]}..{table.points[-1]},"
                f" reference point {table.reference_point}, interval {interval / unit:g} {unit_name}, unit {step}")
    elif fmt == "siemens":
        options = dict(unit_m=DEG, decimals=6) if rotary else {}
        table = siemens_table(curve, step_m=interval, axis=axis or "X1", zero_at_m=reference_position, **options)
        directions = ("mean",)
        offset = 0.0 if reference_position is None else float(curve.at(reference_position, "mean"))
        what = (f"SINUMERIK $AA_ENC_COMP{' modulo' if table.modulo else ''}, {table.values_mm.size} points,"
                f" step {interval / unit:g} {unit_name}")
    else:
        with_backlash = True if backlash is None else backlash
        options = dict(unit_m=DEG, decimals=6) if rotary else {}
        table = heidenhain_table(curve.closed(), axis=axis or "X", backlash=with_backlash, **options)
        directions = ("+", "-") if with_backlash else ("mean",)
        what = f"HEIDENHAIN {table.axis}.COM, {table.positions_mm.size} rows" + (", degrees" if rotary else "")
    left = max(float(np.abs(residuals(table, curve, targets, d, offset=offset)).max()) for d in directions)
    return CompensationResult(
        format=fmt,
        table=table,
        text=table.text(),
        description=what + one_way,
        largest_residual_m=left,
        resolution_m=float(table.resolution),
        reference_offset_m=float(offset),
        rotary=rotary,
    )
