"""The pentaprism's deviation against its set-up: paper 002 section 3, Fig. 5 and eq (12).

Ray-vector tracing by :func:`axiscal.instruments.optics.pentaprism_sensitivity`: the angle between
the incident and the exit beam minus 90 degrees, as the prism turns about X, Y and Z and as it
shifts. Eq (12): a rotation gamma about Z changes it by ``-gamma^2`` (rad), 4.84803e-6 gamma^2 in
arc seconds when gamma is in arc seconds.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_number
from axiscal.instruments.optics import (
    BK7_INDEX,
    PentaprismSensitivity,
    pentaprism_sensitivity,
)
from axiscal.straightness.report import render_report
from axiscal.units import ARCMIN, ARCSEC, MM

__all__ = ["PAPER_002_QUADRATIC_ARCSEC", "PENTAPRISM_SHIFTS_M", "PentaprismStudy", "pentaprism_study"]

#: paper 002 eq (12): change of the deviation per gamma^2 for a rotation gamma about Z, both in arc seconds
PAPER_002_QUADRATIC_ARCSEC = 4.84803e-6
#: the shifts of Fig. 5 (d), metres
PENTAPRISM_SHIFTS_M = np.linspace(-2.0, 2.0, 5) * MM
#: largest sweep accepted, radians (10 degrees)
MAX_ROTATION_RAD = 600 * ARCMIN
#: most rotation angles in one sweep
MAX_STEPS = 2001


def _arcsec(value_rad: float) -> float:
    """Arc seconds rounded to 4 places, without a minus sign on a rounded zero."""
    return round(value_rad / ARCSEC, 4) + 0.0


@dataclass(frozen=True)
class PentaprismStudy:
    """The pentaprism's sensitivity table, ready to print or to write as JSON.

    Attributes
    ----------
    table : PentaprismSensitivity
        The ray-trace results, radians and metres.
    """

    table: PentaprismSensitivity

    def __post_init__(self) -> None:
        check_instance("table", self.table, PentaprismSensitivity, what="a PentaprismSensitivity (pentaprism_sensitivity)")

    def payload(self) -> dict[str, Any]:
        """The JSON object: rotations in arcmin, changes in arcsec, shifts in mm, eq (12)'s coefficient."""
        table = self.table
        return {
            "index": table.index,
            "rotation_arcmin": table.rotation_rad / ARCMIN,
            "deviation_change_arcsec": {axis: table.change_rad[k] / ARCSEC for k, axis in enumerate("XYZ")},
            "translation_mm": table.translation_m / MM,
            "translation_deviation_change_arcsec": {
                axis: table.translation_change_rad[k] / ARCSEC for k, axis in enumerate("XYZ")
            },
            "quadratic_coefficient_per_rad": table.quadratic_coefficient,
            "quadratic_coefficient_arcsec": table.quadratic_coefficient * ARCSEC,
        }

    def report(self) -> str:
        """The readable table: change of the deviation per rotation and per shift, and eq (12)."""
        table = self.table
        rotations = [
            (angle / ARCMIN, [_arcsec(table.change_rad[axis, k]) for axis in range(3)])
            for k, angle in enumerate(table.rotation_rad)
        ]
        shifts = [
            (shift / MM, [_arcsec(table.translation_change_rad[axis, k]) for axis in range(3)])
            for k, shift in enumerate(table.translation_m)
        ]
        return render_report(
            "squareness_pentaprism.txt.j2",
            index=table.index,
            rotations=rotations,
            shifts=shifts,
            coefficient_per_rad=table.quadratic_coefficient,
            coefficient_arcsec=table.quadratic_coefficient * ARCSEC,
            paper_coefficient=np.format_float_scientific(PAPER_002_QUADRATIC_ARCSEC, exp_digits=1),
        )


def pentaprism_study(
    *,
    index: float = BK7_INDEX,
    range_rad: float = 10 * ARCMIN,
    steps: int = 21,
    plot_path: str | Path | None = None,
) -> PentaprismStudy:
    """Sweep the pentaprism of paper 002 through rotations about X, Y, Z and through shifts (Fig. 5).

    Parameters
    ----------
    index : float, keyword-only
        Refractive index of the glass (default BK7).
    range_rad : float, keyword-only
        Rotations run from ``-range_rad`` to ``+range_rad``, radians (default 10 arc minutes;
        at most 10 degrees).
    steps : int, keyword-only
        Number of rotation angles, 2 to 2001 (default 21).
    plot_path : str or Path, optional, keyword-only
        Write Fig. 5 to this image.

    Returns
    -------
    PentaprismStudy

    Raises
    ------
    AxiscalError
        A range outside (0, 10 deg], a number of steps outside 2..2001, or an index the ray trace
        refuses.

    Examples
    --------
    >>> study = pentaprism_study(range_rad=5 * ARCMIN, steps=3)
    >>> float(round(study.payload()["deviation_change_arcsec"]["Z"][0], 4))
    -0.4363
    """
    range_rad = check_number("range_rad (the rotation range)", range_rad, unit="radians")
    if not 0 < range_rad <= MAX_ROTATION_RAD:
        raise AxiscalError(f"the rotation range range_rad must be in (0, {MAX_ROTATION_RAD / ARCMIN:g}] arc minutes, got {range_rad / ARCMIN:g}")
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or not 2 <= steps <= MAX_STEPS:
        raise AxiscalError(f"the sweep needs 2 to {MAX_STEPS} rotation angles (steps), got {steps!r}")
    angles = np.linspace(-range_rad, range_rad, steps)
    table = pentaprism_sensitivity(angles, PENTAPRISM_SHIFTS_M, index=index)
    if plot_path is not None:
        from axiscal.squareness.plot import plot_pentaprism

        plot_pentaprism(plot_path, table)
    return PentaprismStudy(table)
