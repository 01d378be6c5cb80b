"""HEIDENHAIN compensation table: nonlinear axis error compensation, ``<axis>.COM``.

After the technical manuals of the TNC 407 and MANUALplus 620: rows ``NR AXISPOS <axis> BACKLASH``,
at most 256, the error subtracted by the control with linear interpolation between rows. A table
entered in the ``.CMA`` column of one axis may hold the errors of another axis (a dependent axis:
``[axis of the .COM column] = F(axis of the .CMA column)``, e.g. sag of Z as Y travels); AXISPOS
then holds positions of the .CMA column's axis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.compensation.curve import ErrorCurve, _check_direction
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_instance, check_number
from axiscal.units import MM

HEIDENHAIN_MAX_ENTRIES = 256

__all__ = ["HEIDENHAIN_MAX_ENTRIES", "HeidenhainTable", "heidenhain_table"]


@dataclass(frozen=True)
class HeidenhainTable:
    """HEIDENHAIN nonlinear axis error compensation table (``<axis>.COM``).

    Rows ``NR AXISPOS <axis> BACKLASH`` between ``BEGIN <axis>.COM MM`` and ``[END]``, at most
    256 rows, AXISPOS (mm, machine datum) increasing. The axis column holds the error measured
    in the + direction (actual - nominal, mm: positive when the axis travels too far, as in
    HEIDENHAIN's linear axis error parameter); the BACKLASH column the additional error when
    traversing in the - direction (``mean_down - mean_up`` = -B_i). The control subtracts the
    error, interpolating linearly between rows. Without BACKLASH the axis column holds the
    bidirectional mean. For a rotary axis (``unit_m`` = one degree) AXISPOS and the error columns
    are in degrees, as the control gives rotary axis positions; the header keeps the table's MM.

    Attributes
    ----------
    axis : str
        Axis letter.
    positions_mm, error_mm : ndarray, shape (k,), mm
        AXISPOS and the axis column as written.
    backlash_mm : ndarray, shape (k,), mm, or None
        The BACKLASH column (None: one mean column).
    decimals : int
        Decimals written.
    unit_m : float
        Metres per unit of the columns (1e-3: mm); radians per degree for a rotary axis, whose
        columns ``positions_mm``, ``error_mm`` and ``backlash_mm`` then hold degrees.
    base_axis : str or None
        For a dependent-axis table, the axis whose positions AXISPOS holds (the ``.CMA`` column
        the table is entered in); None when it is ``axis`` itself.
    name : str or None
        The file's name without ``.COM`` (default: the axis letter).
    resampled : bool
        True when the measured positions were resampled onto the table's rows.

    Examples
    --------
    >>> from axiscal.compensation.curve import error_curve
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> curve = error_curve(target_statistics(paper003_table4_run()))
    >>> print(heidenhain_table(curve).text(), end="")
    BEGIN X.COM MM
    NR           AXISPOS             X      BACKLASH
    0            +0.0000       +0.0007       +0.0015
    1           +20.0000       +0.0016       +0.0011
    [END]
    """

    axis: str
    positions_mm: np.ndarray
    error_mm: np.ndarray
    backlash_mm: np.ndarray | None
    decimals: int = 4
    unit_m: float = MM
    base_axis: str | None = None
    name: str | None = None
    resampled: bool = False

    @property
    def file_name(self) -> str:
        """The file's name, ``<name>.COM``."""
        return f"{self.name or self.axis}.COM"

    @property
    def note(self) -> str | None:
        """What to do with a dependent-axis table (and whether it was resampled), or None."""
        notes = []
        if self.resampled:
            notes.append(f"the run was resampled onto {self.positions_mm.size} rows"
                         " (linear interpolation; at most 256 rows)")
        if self.base_axis is not None:
            notes.append(f"enter {self.file_name} in column {self.base_axis} of the .CMA table"
                         f" ({self.axis} = F({self.base_axis})); if that column already holds a table for"
                         f" {self.base_axis} = F({self.base_axis}), add this {self.axis} column to it instead"
                         " (one line of the .CMA activates one table per column)")
        return "; ".join(notes) or None

    @property
    def resolution(self) -> float:
        """Smallest step of a written value, metres (radians)."""
        return 10.0 ** (-self.decimals) * self.unit_m

    @property
    def nodes(self) -> np.ndarray:
        """The AXISPOS of the rows, metres (radians), shape (k,)."""
        return self.positions_mm * self.unit_m

    def correction(self, x, direction: str) -> np.ndarray:
        """The correction at commanded positions ``x`` (metres): minus the interpolated error.

        Parameters
        ----------
        x : float or array_like, metres
            Commanded positions (of ``base_axis`` for a dependent-axis table).
        direction : {"+", "-"}
            Direction of travel ("-" adds the BACKLASH column to the error).

        Returns
        -------
        ndarray, shape of ``x``, metres
        """
        _check_direction(direction)
        error = self.error_mm
        if direction == "-" and self.backlash_mm is not None:
            error = error + self.backlash_mm
        return -np.interp(check_array("x", x, unit="metres"), self.nodes, error * self.unit_m)

    def text(self) -> str:
        """The ``.COM`` file."""
        d = self.decimals
        header = f"{'NR':<6}{'AXISPOS':>14}{self.axis:>14}" + (f"{'BACKLASH':>14}" if self.backlash_mm is not None else "")
        lines = [f"BEGIN {self.file_name} MM", header]
        for k, (p, e) in enumerate(zip(self.positions_mm, self.error_mm)):
            row = f"{k:<6}{p:>+14.{d}f}{e:>+14.{d}f}"
            if self.backlash_mm is not None:
                row += f"{self.backlash_mm[k]:>+14.{d}f}"
            lines.append(row)
        lines.append("[END]")
        return "\n".join(lines) + "\n"


def heidenhain_table(
    curve: ErrorCurve, *, axis: str = "X", backlash: bool = True, decimals: int = 4, unit_m: float = MM
) -> HeidenhainTable:
    """HEIDENHAIN ``.COM`` table at the measured targets (see :class:`HeidenhainTable`).

    Parameters
    ----------
    curve : ErrorCurve
        Mean deviations per direction, metres.
    axis : str, keyword-only
        Axis letter(s) (default "X"; written in upper case).
    backlash : bool, keyword-only
        Write the BACKLASH column (default True); False writes the bidirectional mean alone.
    decimals : int, keyword-only
        Decimals written (default 4: 0.1 um in mm).
    unit_m : float, keyword-only
        Metres per unit of the columns (default 1e-3: mm); one degree in radians for a rotary
        axis (give a closed curve, :meth:`ErrorCurve.closed`, to run the table round to 360 deg).

    Returns
    -------
    HeidenhainTable
        One row per position of the curve.

    Raises
    ------
    AxiscalError
        For an axis name that is not letters, or more than 256 targets.

    Examples
    --------
    >>> from axiscal.compensation.curve import error_curve
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> curve = error_curve(target_statistics(paper003_table4_run()))
    >>> heidenhain_table(curve, backlash=False).error_mm.tolist()
    [0.0015, 0.0022]
    """
    check_instance("curve", curve, ErrorCurve)
    if not isinstance(axis, str) or not axis.isalpha():
        raise AxiscalError(f"{axis!r} is not an axis name")
    check_instance("backlash", backlash, (bool, np.bool_))
    decimals = check_count("decimals", decimals, minimum=0, maximum=12)
    unit_m = check_number("unit_m", unit_m, positive=True)
    if curve.positions.size > HEIDENHAIN_MAX_ENTRIES:
        raise AxiscalError(f"{curve.positions.size} targets: a .COM table holds at most {HEIDENHAIN_MAX_ENTRIES} rows")
    positions = np.round(curve.positions / unit_m, decimals)
    if backlash:
        error = np.round(curve.up / unit_m, decimals) + 0.0
        extra = np.round((curve.down - curve.up) / unit_m, decimals) + 0.0
    else:
        error, extra = np.round(curve.mean / unit_m, decimals) + 0.0, None
    return HeidenhainTable(axis.upper(), positions, error, extra, decimals, unit_m)
