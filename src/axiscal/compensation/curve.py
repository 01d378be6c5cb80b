"""The error curve shared by every controller table: the mean ISO 230-2 deviations per direction.

Controller compensation tables from the mean positioning deviations of an ISO 230-2 test.

Writes the pitch (lead-screw) error tables of four controls: the LinuxCNC joint ``COMP_FILE``
(types 0 and 1), FANUC pitch error compensation (parameters 3620-3627 and the incremental
compensation data), SIEMENS SINUMERIK measuring-system error compensation (``$AA_ENC_COMP``) and
HEIDENHAIN nonlinear axis error compensation (``*.COM``). Each table knows how its control
applies it (:meth:`correction`: interpolate between the points, add to the command), so the
tests check the table by applying it to the measured errors. See docs/compensation.md for the
formats, the sources and the sign conventions.

Sign convention of this module: a control *correction* ``c(x)`` is what the control adds to the
commanded position ``x`` before it moves the axis; the error left after compensation is
``e(x) + c(x)`` with ``e = actual - target`` (the ISO 230-2 deviation). A perfect table has
``c = -e``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_number, check_optional_number
from axiscal.positioning.evaluation import TargetStatistics
from axiscal.units import MM

__all__ = [
    "DIRECTIONS",
    "ErrorCurve",
    "error_curve",
    "residuals",
]

DIRECTIONS = ("+", "-")


@dataclass(frozen=True)
class ErrorCurve:
    """Mean positional deviation per approach direction against nominal position (metres).

    Between the measured positions the error is taken as piecewise linear; beyond the end
    positions it is held at the end values, or, for a rotary axis tested round the circle
    (``period`` = 2 pi), interpolated round the circle from the last position to the first.

    Attributes
    ----------
    positions : ndarray, shape (m,), metres (radians for a rotary axis)
        Nominal positions, strictly increasing.
    up, down : ndarray, shape (m,), metres (radians)
        Mean deviation (actual - target) approaching in the + and - direction.
    period : float or None
        One revolution (2 pi) for a rotary axis tested round the circle; None otherwise.

    Examples
    --------
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> from axiscal.units import UM
    >>> curve = error_curve(target_statistics(paper003_table4_run()))
    >>> round(float(curve.at(0.01, "mean")) / UM, 3)
    1.825
    """

    positions: np.ndarray
    up: np.ndarray
    down: np.ndarray
    period: float | None = None

    def __post_init__(self) -> None:
        positions = check_array("positions", self.positions, ndim=1, min_len=1, unit="")
        up = check_array("up", self.up, ndim=1, unit="")
        down = check_array("down", self.down, ndim=1, unit="")
        if up.size != positions.size or down.size != positions.size:
            raise AxiscalError(
                f"up and down must hold one value per position ({positions.size}), not {up.size} and {down.size}"
            )
        if np.any(np.diff(positions) <= 0):
            raise AxiscalError("positions must be strictly increasing")
        period = check_optional_number("period", self.period, positive=True, unit="")
        for name, value in (("positions", positions), ("up", up), ("down", down), ("period", period)):
            object.__setattr__(self, name, value)

    @property
    def mean(self) -> np.ndarray:
        """Bidirectional mean deviation, shape (m,), metres."""
        return 0.5 * (self.up + self.down)

    def at(self, x, direction: str) -> np.ndarray:
        """Deviation at positions ``x`` for direction "+", "-" or "mean", metres.

        Parameters
        ----------
        x : float or array_like, metres
            Positions; beyond the ends the end values are held.
        direction : {"+", "-", "mean"}
            Which curve.

        Returns
        -------
        ndarray, shape of ``x``, metres

        Raises
        ------
        AxiscalError
            For an unknown direction.
        """
        values = {"+": self.up, "-": self.down, "mean": self.mean}.get(direction) if isinstance(direction, str) else None
        if values is None:
            raise AxiscalError(f"unknown direction {direction!r}; use +, - or mean")
        return np.interp(check_array("x", x, unit="metres"), self.positions, values, period=self.period)

    def closed(self) -> ErrorCurve:
        """The curve with one more position a turn after the first, holding the first values (rotary axes).

        A table written at the positions of the closed curve runs from the first target round to
        it again (0 .. 360 deg), so that a control interpolating between its rows goes back to
        the first value. A curve without a ``period`` is returned as it is.

        Returns
        -------
        ErrorCurve
            Without ``period``; one position more when it had one.

        Examples
        --------
        >>> import numpy as np
        >>> c = ErrorCurve(np.array([0.0, np.pi]), np.array([1.0, 2.0]), np.array([1.0, 2.0]), period=2 * np.pi)
        >>> c.closed().positions.round(3).tolist(), c.closed().up.tolist()
        ([0.0, 3.142, 6.283], [1.0, 2.0, 1.0])
        """
        if self.period is None:
            return self
        x = np.append(self.positions, self.positions[0] + self.period)
        return ErrorCurve(x, np.append(self.up, self.up[0]), np.append(self.down, self.down[0]))


def error_curve(stats: TargetStatistics, *, period: float | None = None) -> ErrorCurve:
    """The mean deviations of a positioning test as an :class:`ErrorCurve`.

    For a one-direction test (the other direction's means are NaN) both curves are the means of
    the direction tested: the reversal was not measured, and a table from it holds that
    direction's deviations.

    Parameters
    ----------
    stats : TargetStatistics
        From :func:`axiscal.positioning.evaluation.target_statistics`, metres.
    period : float, optional, keyword-only
        2 pi for a rotary axis tested round the circle (see :attr:`ErrorCurve.period`).

    Returns
    -------
    ErrorCurve
        ``positions`` = the targets, ``up``/``down`` = the mean unidirectional deviations, metres.

    Examples
    --------
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> error_curve(target_statistics(paper003_table4_run())).positions.tolist()
    [0.0, 0.02]
    """
    check_instance("stats", stats, TargetStatistics)
    up, down = np.asarray(stats.mean_up), np.asarray(stats.mean_down)
    if np.all(np.isnan(down)):
        down = up
    elif np.all(np.isnan(up)):
        up = down
    return ErrorCurve(np.asarray(stats.targets), up, down, period)


def _check_direction(direction: str) -> None:
    if not isinstance(direction, str) or direction not in DIRECTIONS:
        raise AxiscalError(f"unknown direction {direction!r}; use + or -")


def _grid(start: float, end: float, step: float, limit: int | None = None, what: str = "") -> np.ndarray:
    """Nodes from ``start`` past ``end`` at ``step``; more than ``limit`` nodes are refused before any is made."""
    if not (math.isfinite(step) and step > 0):
        raise AxiscalError(f"the table interval must be positive, got {step / MM:g} mm")
    steps = (end - start) / step
    if limit is not None and steps > limit:
        raise AxiscalError(f"{steps + 1:.0f} compensation points exceed {what} = {limit}: use a larger step")
    if not steps < 1e9:
        raise AxiscalError(f"a table interval of {step / MM:g} mm gives more than 10^9 points; use a larger one")
    count = int(math.ceil(steps - 1e-9)) + 1
    if limit is not None and count > limit:
        raise AxiscalError(f"{count} compensation points exceed {what} = {limit}: use a larger step")
    return start + step * np.arange(count)



def residuals(table, curve: ErrorCurve, x, direction: str, *, offset: float = 0.0) -> np.ndarray:
    """Error left at ``x`` (metres) after ``table`` is applied: ``e(x) - offset + c(x)``.

    ``direction`` is "+", "-" or "mean"; for "mean" the table's + correction is used (tables
    with one curve apply it in both directions). ``offset`` is the part of the error a table
    leaves to the reference position by construction: FANUC tables are zero at the reference
    position, so there it is the deviation at the reference position (of the + direction for a
    bidirectional table, which assumes the reference is approached in +), see
    :attr:`FanucTable.reference_deviation_m`.

    Parameters
    ----------
    table : LinuxcncTable, FanucTable, SiemensTable or HeidenhainTable
        Any table with ``correction(x, direction)``.
    curve : ErrorCurve
        The deviations the table is to correct, metres.
    x : float or array_like, metres
        Commanded positions.
    direction : {"+", "-", "mean"}
        Direction of travel.
    offset : float, keyword-only, metres
        Deviation left to the reference position setting (default 0).

    Returns
    -------
    ndarray, shape of ``x``, metres

    Examples
    --------
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> from axiscal.units import UM
    >>> curve = error_curve(target_statistics(paper003_table4_run()))
    >>> from axiscal.compensation.heidenhain import heidenhain_table
    >>> left = residuals(heidenhain_table(curve), curve, curve.positions, "+")
    >>> bool(abs(left).max() <= 0.05 * UM)
    True
    """
    check_instance("curve", curve, ErrorCurve)
    if not callable(getattr(table, "correction", None)):
        raise AxiscalError(f"table must be a compensation table (with correction(x, direction)), not {type(table).__name__}")
    offset = check_number("offset", offset, unit="metres")
    return curve.at(x, direction) - offset + table.correction(x, "+" if direction == "mean" else direction)
