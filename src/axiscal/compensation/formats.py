"""One call from a positioning run to the compensation table of a controller, with what it leaves uncorrected.

Chooses the controller module (LinuxCNC, FANUC, SIEMENS, HEIDENHAIN), fills in the defaults the
command line documents (interval: the mean target spacing in whole millimetres; reference
position: the first target), refuses an option that belongs to another controller instead of
ignoring it, and measures the error the table leaves at the measured targets (the residual
``e(x) - offset + c(x)`` of :func:`axiscal.compensation.curve.residuals`).
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
from axiscal.positioning.evaluation import PositioningRun, target_statistics
from axiscal.positioning.reader import read_positioning_run
from axiscal.units import MM, UM

__all__ = ["FORMATS", "FORMAT_OPTIONS", "CompensationResult", "compensation_table"]

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
    """

    format: str
    table: Any
    text: str
    description: str
    largest_residual_m: float
    resolution_m: float
    reference_offset_m: float

    @property
    def note(self) -> str:
        """One line for the user: the table, the largest error left and the reference offset, in um."""
        zero_point = (
            f"; the table is zero at the reference position, whose own deviation {self.reference_offset_m / UM:+.3f} um"
            f" is left to the reference position setting" if self.reference_offset_m else ""
        )
        return (
            f"{self.description}; largest error left at the measured targets {self.largest_residual_m / UM:.3f} um"
            f" (table resolution {self.resolution_m / UM:g} um){zero_point}"
        )


def _refuse_options_of_other_formats(fmt: str, given: dict[str, Any]) -> None:
    for name, value in given.items():
        if name not in FORMAT_OPTIONS:
            raise AxiscalError(f"unknown compensation option '{name}'; use one of {', '.join(FORMAT_OPTIONS)}")
        formats = FORMAT_OPTIONS[name]
        if value is not None and fmt not in formats:
            raise AxiscalError(f"{name} applies to format {' or '.join(formats)}, not {fmt}")


def _default_interval(targets: np.ndarray) -> float:
    """The mean target spacing rounded to whole millimetres (at least 1 mm), metres."""
    return max(1.0, round(np.ptp(targets) / (targets.size - 1) / MM)) * MM


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
) -> CompensationResult:
    """The compensation table of controller ``fmt`` from the mean deviations of a positioning run.

    An option left at None takes the format's default; an option given (not None) to a format
    that does not read it (see :data:`FORMAT_OPTIONS`) is an error.

    Parameters
    ----------
    run : PositioningRun, or str or Path
        The bidirectional test, metres, or a run file read with
        :func:`axiscal.positioning.reader.read_positioning_run`; the table corrects its mean
        deviation per direction.
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

    Returns
    -------
    CompensationResult
        The table, its text, a description, the largest error it leaves at the targets (m),
        its resolution (m) and the reference offset (m).

    Raises
    ------
    AxiscalError
        For an unknown format, an option of another format, a run file the reader refuses
        (naming its line), or a value the controller's table cannot hold (see the controller modules).

    Examples
    --------
    >>> import numpy as np
    >>> run = PositioningRun(np.array([0.0, 0.1, 0.2]), np.full((3, 2), 2e-6), np.full((3, 2), -2e-6))
    >>> result = compensation_table(run, "heidenhain", backlash=False)
    >>> result.largest_residual_m
    0.0
    """
    if fmt not in FORMATS:
        raise AxiscalError(f"unknown compensation table format '{fmt}'; use one of {', '.join(FORMATS)}")
    _refuse_options_of_other_formats(
        fmt,
        dict(comp_type=comp_type, interval_m=interval_m, magnification=magnification, detection_unit_m=detection_unit_m,
             reference_position_m=reference_position_m, reference_point=reference_point, bidirectional=bidirectional,
             axis=axis, axis_number=axis_number, backlash=backlash),
    )
    if not isinstance(run, PositioningRun):
        run = read_positioning_run(run).run
    curve: ErrorCurve = error_curve(target_statistics(run))
    targets = run.targets
    interval = _default_interval(targets) if interval_m is None else interval_m
    offset = 0.0
    if fmt == "linuxcnc":
        comp_type = 1 if comp_type is None else comp_type
        table = linuxcnc_table(curve, comp_type=comp_type)
        directions: tuple[str, ...] = ("+", "-")
        what = f"LinuxCNC COMP_FILE_TYPE = {comp_type}, {table.nominal.size} entries"
    elif fmt == "fanuc":
        table = fanuc_table(
            curve,
            interval_m=interval,
            reference_position_m=targets[0] if reference_position_m is None else reference_position_m,
            reference_point=reference_point,
            magnification=1 if magnification is None else magnification,
            detection_unit_m=UM if detection_unit_m is None else detection_unit_m,
            bidirectional=bool(bidirectional),
            axis_number=1 if axis_number is None else axis_number,
        )
        directions = ("+", "-") if bidirectional else ("mean",)
        offset = table.reference_deviation_m
        what = (f"FANUC pitch error compensation, points {table.points[0]}..{table.points[-1]}, reference point"
                f" {table.reference_point}, interval {interval / MM:g} mm, unit {table.resolution / UM:g} um")
    elif fmt == "siemens":
        table = siemens_table(curve, step_m=interval, axis=axis or "X1", zero_at_m=reference_position_m)
        directions = ("mean",)
        offset = 0.0 if reference_position_m is None else float(curve.at(reference_position_m, "mean"))
        what = f"SINUMERIK $AA_ENC_COMP, {table.values_mm.size} points, step {interval / MM:g} mm"
    else:
        with_backlash = True if backlash is None else backlash
        table = heidenhain_table(curve, axis=axis or "X", backlash=with_backlash)
        directions = ("+", "-") if with_backlash else ("mean",)
        what = f"HEIDENHAIN {table.axis}.COM, {table.positions_mm.size} rows"
    left = max(float(np.abs(residuals(table, curve, targets, d, offset=offset)).max()) for d in directions)
    return CompensationResult(
        format=fmt,
        table=table,
        text=table.text(),
        description=what,
        largest_residual_m=left,
        resolution_m=float(table.resolution),
        reference_offset_m=float(offset),
    )
