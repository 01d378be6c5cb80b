"""Lead-screw error tables of open and PC-based controllers: TwinCAT CNC leadscrew error compensation (``kw.ssfk``).

Beckhoff TwinCAT CNC (TF5200) axis compensation, leadscrew error compensation (SSFK): a
compensation value list per axis, ``kopf.*`` header and ``kw.ssfk.*`` body. P-COMP-00017
``kw.ssfk.unit`` = 1 gives lengths in 0.1 um; P-COMP-00018 ``kw.ssfk.interval`` is the spacing of
equidistant points (0: the points are listed as ``kw.ssfk.table[i].setpoint``); P-COMP-00019
``kw.ssfk.kw_startpos`` the first point; P-COMP-00020 ``kw.ssfk.kw_nr_max`` the number of points;
``kw.ssfk.bilateral`` = 1 one table per direction; P-COMP-00023/24 ``kw.ssfk.table[i].pos`` /
``.neg`` the compensation values, given as the absolute position error (actual - setpoint) that
the control removes, linearly interpolated between points. The manual's worked example: a point
programmed at 19866.7 um reached at 19856.5 um (+) and 19874.7 um (-) is entered as -102 and 80.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.compensation.curve import ErrorCurve
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM

__all__ = ["TWINCAT_UNIT", "TwincatTable", "twincat_table"]

#: length unit of a metric TwinCAT compensation list (kw.ssfk.unit = 1), metres
TWINCAT_UNIT = 0.1 * UM
_SGN32 = 2**31 - 1


@dataclass(frozen=True)
class TwincatTable:
    """A TwinCAT CNC leadscrew error compensation list of one axis.

    Attributes
    ----------
    axis : str
        Logical axis name (``kopf.log_achs_name``).
    axis_number : int
        Logical axis number (``kopf.achs_nr``).
    setpoints : ndarray of int, shape (n,)
        Interpolation points, 0.1 um.
    pos, neg : ndarray of int, shape (n,)
        Position error (actual - setpoint) in the + and - direction, 0.1 um; ``neg`` equals ``pos``
        for a unilateral table.
    interval : int
        Spacing of equidistant points, 0.1 um; 0 when the points are listed.
    bilateral : bool
        One table per direction.
    resampled : bool
        True when the measured targets were resampled onto equidistant points.
    """

    axis: str
    axis_number: int
    setpoints: np.ndarray
    pos: np.ndarray
    neg: np.ndarray
    interval: int
    bilateral: bool
    resampled: bool = False

    @property
    def note(self) -> str | None:
        """A sentence saying the curve was resampled onto equidistant points, or None."""
        if not self.resampled:
            return None
        return (f"the mean deviations were resampled onto {self.setpoints.size} points"
                f" {self.interval * TWINCAT_UNIT / MM:g} mm apart (linear interpolation)")

    def correction(self, x, direction: str) -> np.ndarray:
        """What the control adds to a command at ``x`` (metres) moving in ``direction`` ("+" or "-"), metres."""
        if direction not in ("+", "-"):
            raise AxiscalError(f"unknown direction '{direction}'; use + or -")
        values = self.pos if direction == "+" or not self.bilateral else self.neg
        return -np.interp(np.asarray(x, dtype=float), self.setpoints * TWINCAT_UNIT, values * TWINCAT_UNIT)

    def text(self) -> str:
        """The compensation value list (ASCII, ``#`` comments)."""
        lines = [
            "# leadscrew error compensation (SSFK), written by axiscal",
            f"kopf.achs_nr {self.axis_number}",
            f"kopf.log_achs_name {self.axis}",
            f"kw.ssfk.interval {self.interval}",
            f"kw.ssfk.kw_startpos {int(self.setpoints[0])}",
            f"kw.ssfk.kw_nr_max {self.setpoints.size}",
            "kw.ssfk.unit 1",
            f"kw.ssfk.bilateral {int(self.bilateral)}",
        ]
        if self.interval == 0:
            lines += [f"kw.ssfk.table[{i}].setpoint {int(v)}" for i, v in enumerate(self.setpoints)]
        lines += [f"kw.ssfk.table[{i}].pos {int(v)}" for i, v in enumerate(self.pos)]
        if self.bilateral:
            lines += [f"kw.ssfk.table[{i}].neg {int(v)}" for i, v in enumerate(self.neg)]
        return "\n".join(lines) + "\n"


def twincat_table(
    curve: ErrorCurve,
    *,
    axis: str = "X",
    axis_number: int = 1,
    interval_m: float | None = None,
    bilateral: bool = True,
    max_points: int | None = None,
) -> TwincatTable:
    """A TwinCAT CNC leadscrew error compensation list from the mean deviations of a positioning test.

    Parameters
    ----------
    curve : ErrorCurve
        Mean deviation per direction (:func:`axiscal.compensation.error_curve`), metres.
    axis : str, keyword-only
        Logical axis name.
    axis_number : int, keyword-only
        Logical axis number (>= 1).
    interval_m : float, optional, keyword-only
        Spacing of equidistant points, metres (a whole multiple of 0.1 um); the curve is
        resampled on it from the first target (linear interpolation, the end value held for a last
        point beyond the last target). None: the measured targets are listed (``interval`` 0).
    bilateral : bool, keyword-only
        One table per direction (default); False: one table of the bidirectional mean.
    max_points : int, optional, keyword-only
        The number of table entries the control reserves (P-COMP-00059); a longer table is refused.

    Returns
    -------
    TwincatTable

    Raises
    ------
    AxiscalError
        For a non-positive or non-finite interval, an axis number below 1, more points than
        ``max_points``, or values beyond SGN32.

    Examples
    --------
    >>> import numpy as np
    >>> curve = ErrorCurve(np.array([0.0, 0.01]), np.array([0.0, -10.2e-6]), np.array([0.0, 8e-6]))
    >>> twincat_table(curve).pos.tolist(), twincat_table(curve).neg.tolist()
    ([0, -102], [0, 80])
    """
    if axis_number < 1:
        raise AxiscalError(f"axis numbers start at 1, not {axis_number}")
    positions = np.asarray(curve.positions, dtype=float)
    if interval_m is None:
        nodes = positions
        interval = 0
    else:
        if not (math.isfinite(interval_m) and interval_m > 0):
            raise AxiscalError(f"the interval must be a positive length, not {interval_m / MM:g} mm")
        interval = round(interval_m / TWINCAT_UNIT)
        if interval < 1 or abs(interval * TWINCAT_UNIT - interval_m) > 1e-3 * TWINCAT_UNIT:
            raise AxiscalError(f"the interval {interval_m / MM:g} mm is not a whole number of 0.1 um")
        count = int(math.ceil((positions[-1] - positions[0]) / (interval * TWINCAT_UNIT) - 1e-9)) + 1
        nodes = positions[0] + interval * TWINCAT_UNIT * np.arange(count)
    if max_points is not None and nodes.size > max_points:
        raise AxiscalError(
            f"{nodes.size} points: the control reserves {max_points} (P-COMP-00059); give a larger interval"
        )
    up = curve.at(nodes, "+")
    down = curve.at(nodes, "-")
    if not bilateral:
        up = down = curve.at(nodes, "mean")
    setpoints = np.rint(nodes / TWINCAT_UNIT).astype(np.int64)
    pos = np.rint(up / TWINCAT_UNIT).astype(np.int64)
    neg = np.rint(down / TWINCAT_UNIT).astype(np.int64)
    if max(np.abs(setpoints).max(), np.abs(pos).max(), np.abs(neg).max()) > _SGN32:
        raise AxiscalError("a position or value is beyond the SGN32 range of the list (0.1 um units)")
    return TwincatTable(
        axis=axis, axis_number=axis_number, setpoints=setpoints, pos=pos, neg=neg, interval=interval,
        bilateral=bilateral,
        resampled=interval != 0 and (nodes.size != positions.size or not np.allclose(nodes, positions, rtol=0, atol=1e-9)),
    )
