"""SIEMENS compensation table: SINUMERIK measuring-system error compensation, ``$AA_ENC_COMP``.

After the function manual "Compensations" (K3): compensation values at ``$AA_ENC_COMP_MIN +
i $AA_ENC_COMP_STEP``, interpolated linearly; a positive value moves the axis negative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.compensation.curve import ErrorCurve, _check_direction, _grid
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_count, check_instance, check_integer, check_number, check_optional_number
from axiscal.units import MM

__all__ = ["SiemensTable", "siemens_table"]


@dataclass(frozen=True)
class SiemensTable:
    """SINUMERIK measuring-system (lead-screw) error compensation, ``%_N_AX_EEC_INI``.

    ``$AA_ENC_COMP[e, i, AXIS]`` holds the compensation value of point i (mm) for encoder e,
    from ``$AA_ENC_COMP_MIN`` in steps of ``$AA_ENC_COMP_STEP`` up to ``$AA_ENC_COMP_MAX``.
    The control changes the axis actual value by the compensation value: a positive value
    moves the axis in the negative direction. So the value is the deviation itself
    (``+e``) and the correction applied to the command is its negative. Linear interpolation
    between points, end values held beyond MIN and MAX. One curve for both directions.

    A rotary axis (``unit_m`` = one degree) has its positions, step and values in degrees; tested
    round the circle it is written as a modulo compensation (``$AA_ENC_COMP_IS_MODULO = 1``) from
    0 to 360 deg, MIN and MAX the ends of the modulo range, whose first and last values are equal.

    Attributes
    ----------
    axis : str
        Machine axis name.
    start_m, step_m : float, metres
        ``$AA_ENC_COMP_MIN`` and ``$AA_ENC_COMP_STEP``.
    values_mm : ndarray, shape (k,), mm (degrees for a rotary axis)
        The compensation values as written.
    encoder : int
        Encoder index.
    decimals : int
        Decimals written.
    unit_m : float
        Metres per unit of the values (1e-3: mm); radians per degree for a rotary axis.
    modulo : bool
        ``$AA_ENC_COMP_IS_MODULO``: a rotary axis compensated round the circle.

    Examples
    --------
    >>> from axiscal.compensation.curve import error_curve
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> curve = error_curve(target_statistics(paper003_table4_run()))
    >>> siemens_table(curve, step_m=0.01).values_mm.tolist()
    [0.0015, 0.0018, 0.0022]
    """

    axis: str
    start_m: float
    step_m: float
    values_mm: np.ndarray
    encoder: int = 0
    decimals: int = 4
    unit_m: float = MM
    modulo: bool = False

    @property
    def resolution(self) -> float:
        """Smallest step of a written value, metres (radians)."""
        return 10.0 ** (-self.decimals) * self.unit_m

    @property
    def nodes(self) -> np.ndarray:
        """Positions of the compensation points, metres, shape (k,)."""
        return self.start_m + self.step_m * np.arange(self.values_mm.size)

    @property
    def end_m(self) -> float:
        """``$AA_ENC_COMP_MAX``, metres."""
        return float(self.nodes[-1])

    def correction(self, x, direction: str) -> np.ndarray:
        """The correction at commanded positions ``x`` (metres): minus the interpolated value.

        Parameters
        ----------
        x : float or array_like, metres
            Commanded positions.
        direction : {"+", "-"}
            Direction of travel (one curve serves both).

        Returns
        -------
        ndarray, shape of ``x``, metres
        """
        _check_direction(direction)
        return -np.interp(check_array("x", x, unit="metres"), self.nodes, self.values_mm * self.unit_m)

    def text(self) -> str:
        """The ``%_N_AX_EEC_INI`` program that loads the table."""
        e, a, d = self.encoder, self.axis, self.decimals
        lines = ["%_N_AX_EEC_INI", "CHANDATA(1)"]
        lines += [f"$AA_ENC_COMP[{e},{i},{a}]={v:.{d}f}" for i, v in enumerate(self.values_mm)]
        lines += [
            f"$AA_ENC_COMP_STEP[{e},{a}]={self.step_m / self.unit_m:.4f}",
            f"$AA_ENC_COMP_MIN[{e},{a}]={self.start_m / self.unit_m:.4f}",
            f"$AA_ENC_COMP_MAX[{e},{a}]={self.end_m / self.unit_m:.4f}",
            f"$AA_ENC_COMP_IS_MODULO[{e},{a}]={int(self.modulo)}",
            "M17",
        ]
        return "\n".join(lines) + "\n"


def siemens_table(
    curve: ErrorCurve,
    *,
    step_m: float,
    axis: str = "X1",
    direction: str = "mean",
    zero_at_m: float | None = None,
    encoder: int = 0,
    decimals: int = 4,
    max_points: int = 1000,
    unit_m: float = MM,
) -> SiemensTable:
    """SINUMERIK ``$AA_ENC_COMP`` table on an even grid from the first measured target.

    Parameters
    ----------
    curve : ErrorCurve
        Mean deviations per direction, metres.
    step_m : float, keyword-only
        ``$AA_ENC_COMP_STEP``, metres.
    axis : str, keyword-only
        Machine axis name (default "X1").
    direction : {"mean", "+", "-"}, keyword-only
        Which mean deviation the one curve holds (default the bidirectional mean; the reversal
        is then left to backlash compensation, MD32450).
    zero_at_m : float, optional, keyword-only
        Shift the curve so its value is zero here (Siemens recommends zero at the reference
        point, so that switching the compensation on makes no jump).
    encoder : int, keyword-only
        Encoder index (0 = first measuring system).
    decimals : int, keyword-only
        Decimals of mm written (default 4: 0.1 um).
    max_points : int, keyword-only
        MD38000 $MA_MM_ENC_COMP_MAX_POINTS of the control (default 1000).
    unit_m : float, keyword-only
        Metres per unit written (default 1e-3: mm); one degree in radians for a rotary axis. A
        rotary curve with a ``period`` (tested round the circle) is written as a modulo
        compensation from 0 to 360 deg.

    Returns
    -------
    SiemensTable
        Values at ``first target + i step_m`` up to the last target (modulo: 0 .. 360 deg).

    Raises
    ------
    AxiscalError
        For an axis name that is not alphanumeric, a step that is not positive, more points
        than ``max_points``, or a modulo step that does not divide the circle into whole steps.

    Examples
    --------
    >>> from axiscal.compensation.curve import error_curve
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> curve = error_curve(target_statistics(paper003_table4_run()))
    >>> print(siemens_table(curve, step_m=0.01, axis="Y1").text().splitlines()[2])
    $AA_ENC_COMP[0,0,Y1]=0.0015
    """
    check_instance("curve", curve, ErrorCurve)
    if not isinstance(axis, str) or not axis or not axis.replace("_", "").isalnum():
        raise AxiscalError(f"{axis!r} is not a machine axis name")
    step_m = check_number("step_m", step_m)
    zero_at_m = check_optional_number("zero_at_m", zero_at_m)
    check_choice("direction", direction, ("+", "-", "mean"))
    check_integer("encoder", encoder)
    decimals = check_count("decimals", decimals, minimum=0, maximum=12)
    max_points = check_count("max_points", max_points)
    unit_m = check_number("unit_m", unit_m, positive=True)
    modulo = curve.period is not None
    if modulo:
        steps = curve.period / step_m if step_m > 0 else math.nan
        if not (math.isfinite(steps) and abs(steps - round(steps)) <= 1e-9 * steps):
            raise AxiscalError(
                f"a modulo compensation steps through the circle: the step {step_m / unit_m:g} must divide"
                f" {curve.period / unit_m:g} into whole steps"
            )
        nodes = step_m * np.arange(round(steps) + 1)
    else:
        nodes = _grid(float(curve.positions[0]), float(curve.positions[-1]), step_m, max_points, "MD38000")
    if nodes.size > max_points:
        raise AxiscalError(f"{nodes.size} compensation points exceed MD38000 = {max_points}: use a larger step")
    e = curve.at(nodes, direction)
    if zero_at_m is not None:
        e = e - curve.at(zero_at_m, direction)
    values = np.round(e / unit_m, decimals) + 0.0
    if modulo:
        values[-1] = values[0]  # 360 deg is 0 deg again
    return SiemensTable(axis, float(nodes[0]), step_m, values, encoder, decimals, unit_m, modulo)
