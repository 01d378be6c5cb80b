"""HEIDENHAIN compensation table."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.compensation.curve import ErrorCurve, _check_direction
from axiscal.errors import AxiscalError
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
    bidirectional mean.
    """

    axis: str
    positions_mm: np.ndarray
    error_mm: np.ndarray
    backlash_mm: np.ndarray | None
    decimals: int = 4

    @property
    def resolution(self) -> float:
        return 10.0 ** (-self.decimals) * MM

    @property
    def nodes(self) -> np.ndarray:
        return self.positions_mm * MM

    def correction(self, x, direction: str) -> np.ndarray:
        _check_direction(direction)
        error = self.error_mm
        if direction == "-" and self.backlash_mm is not None:
            error = error + self.backlash_mm
        return -np.interp(np.asarray(x, dtype=float), self.nodes, error * MM)

    def text(self) -> str:
        d = self.decimals
        header = f"{'NR':<6}{'AXISPOS':>14}{self.axis:>14}" + (f"{'BACKLASH':>14}" if self.backlash_mm is not None else "")
        lines = [f"BEGIN {self.axis}.COM MM", header]
        for k, (p, e) in enumerate(zip(self.positions_mm, self.error_mm)):
            row = f"{k:<6}{p:>+14.{d}f}{e:>+14.{d}f}"
            if self.backlash_mm is not None:
                row += f"{self.backlash_mm[k]:>+14.{d}f}"
            lines.append(row)
        lines.append("[END]")
        return "\n".join(lines) + "\n"


def heidenhain_table(curve: ErrorCurve, *, axis: str = "X", backlash: bool = True, decimals: int = 4) -> HeidenhainTable:
    """HEIDENHAIN ``.COM`` table at the measured targets (see :class:`HeidenhainTable`)."""
    if not axis.isalpha():
        raise AxiscalError(f"'{axis}' is not an axis name")
    if curve.positions.size > HEIDENHAIN_MAX_ENTRIES:
        raise AxiscalError(f"{curve.positions.size} targets: a .COM table holds at most {HEIDENHAIN_MAX_ENTRIES} rows")
    positions = np.round(curve.positions / MM, decimals)
    if backlash:
        error = np.round(curve.up / MM, decimals) + 0.0
        extra = np.round((curve.down - curve.up) / MM, decimals) + 0.0
    else:
        error, extra = np.round(curve.mean / MM, decimals) + 0.0, None
    return HeidenhainTable(axis.upper(), positions, error, extra, decimals)
