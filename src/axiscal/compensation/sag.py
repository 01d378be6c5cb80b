"""Cross-axis (sag and straightness) compensation tables: SINUMERIK interpolatory sag compensation (``$AN_CEC``).

SINUMERIK function manual "Compensations" (K3), interpolatory compensation, sag and angularity
error compensation: table ``t`` of ``%_N_NC_CEC_INI`` holds ``$AN_CEC[t,N]`` (mm) at equidistant
positions of a base axis (``$AN_CEC_INPUT_AXIS``) from ``$AN_CEC_MIN`` in steps of
``$AN_CEC_STEP`` to ``$AN_CEC_MAX``, applied to a compensation axis (``$AN_CEC_OUTPUT_AXIS``),
linearly interpolated, the end values held beyond. The number of points is reserved by MD18342
``$MN_MM_CEC_MAX_POINTS[t]`` (fixed at 200 on an 828D). Sign: K3 defines a compensation value as
the position reached minus the programmed position, the convention of the measuring-system table
(:class:`axiscal.compensation.SiemensTable`): the table holds the straightness deviation of the
compensation axis and the control removes it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.straightness import reference_line
from axiscal.units import MM

__all__ = ["SAG_REFERENCES", "SinumerikSagTable", "sinumerik_sag_table"]

#: how much of the measured deviation the table takes: all of it, or what is left about a line
SAG_REFERENCES = ("none", "least-squares", "end-points")


@dataclass(frozen=True)
class SinumerikSagTable:
    """One SINUMERIK sag compensation table (``$AN_CEC``).

    Attributes
    ----------
    table : int
        Table index ``t`` (0-based).
    input_axis, output_axis : str
        Machine axis names of the base axis and the compensation axis (e.g. ``AX2``, ``AX1``).
    start_m, step_m : float
        ``$AN_CEC_MIN`` and ``$AN_CEC_STEP``, metres.
    values_mm : ndarray, shape (n,)
        ``$AN_CEC[t, N]``, mm (the deviation of the compensation axis).
    direction : int
        ``$AN_CEC_DIRECTION``: 0 both directions, 1 positive only, -1 negative only.
    resampled : bool
        True when the measured positions were not already on the table's points.
    """

    table: int
    input_axis: str
    output_axis: str
    start_m: float
    step_m: float
    values_mm: np.ndarray
    direction: int = 0
    resampled: bool = False

    @property
    def nodes(self) -> np.ndarray:
        """Base axis position of each point, metres."""
        return self.start_m + self.step_m * np.arange(self.values_mm.size)

    @property
    def note(self) -> str | None:
        """A sentence saying the run was resampled onto the table's points, or None."""
        if not self.resampled:
            return None
        return (f"the run was resampled onto {self.values_mm.size} points {self.step_m / MM:g} mm apart"
                " (linear interpolation; the controller needs equidistant points)")

    def correction(self, x) -> np.ndarray:
        """What the control adds to the compensation axis with the base axis at ``x`` (metres), metres."""
        return -np.interp(np.asarray(x, dtype=float), self.nodes, self.values_mm * MM)

    def text(self) -> str:
        """The ``%_N_NC_CEC_INI`` program."""
        t = self.table
        lines = ["%_N_NC_CEC_INI", "CHANDATA(1)"]
        lines += [f"$AN_CEC[{t},{i}]={v:.4f}" for i, v in enumerate(self.values_mm)]
        lines += [
            f"$AN_CEC_INPUT_AXIS[{t}]=({self.input_axis})",
            f"$AN_CEC_OUTPUT_AXIS[{t}]=({self.output_axis})",
            f"$AN_CEC_STEP[{t}]={self.step_m / MM:.4f}",
            f"$AN_CEC_MIN[{t}]={self.start_m / MM:.4f}",
            f"$AN_CEC_MAX[{t}]={self.nodes[-1] / MM:.4f}",
            f"$AN_CEC_DIRECTION[{t}]={self.direction}",
            f"$AN_CEC_MULT_BY_TABLE[{t}]=0",
            f"$AN_CEC_IS_MODULO[{t}]=0",
            "M17",
        ]
        return "\n".join(lines) + "\n"


def sinumerik_sag_table(
    position_m: np.ndarray,
    deviation_m: np.ndarray,
    *,
    input_axis: str,
    output_axis: str,
    step_m: float,
    table: int = 0,
    reference: str = "none",
    direction: int = 0,
    max_points: int | None = None,
) -> SinumerikSagTable:
    """A SINUMERIK sag compensation table from a straightness run of the base axis.

    Parameters
    ----------
    position_m : ndarray, shape (n,)
        Base axis positions of the run, metres, strictly increasing.
    deviation_m : ndarray, shape (n,)
        Deviation of the tool along the compensation axis (position reached - programmed), metres.
    input_axis, output_axis : str, keyword-only
        Machine axis names of the base axis and the compensation axis (``AX1``, ``X1``, ...).
    step_m : float, keyword-only
        ``$AN_CEC_STEP``, metres; the run is resampled on it from its first position (linear
        interpolation; a last point beyond the run holds the end value).
    table : int, keyword-only
        Table index (0-based).
    reference : str, keyword-only
        ``"none"``: the whole deviation (sag and angularity); ``"least-squares"`` or
        ``"end-points"``: the deviation about that line only (sag, the angularity left to a
        squareness correction).
    direction : int, keyword-only
        ``$AN_CEC_DIRECTION``: 0, 1 or -1.
    max_points : int, optional, keyword-only
        MD18342 ``$MN_MM_CEC_MAX_POINTS[t]`` of the control (200 on an 828D); a longer table is refused.

    Returns
    -------
    SinumerikSagTable

    Raises
    ------
    AxiscalError
        For positions not strictly increasing, mismatched shapes, a non-positive step, an unknown
        reference or direction, a negative table index, the same axis as input and output, or more
        points than ``max_points``.

    Examples
    --------
    >>> import numpy as np
    >>> y = np.array([0.0, 0.1, 0.2])
    >>> t = sinumerik_sag_table(y, np.array([0.0, -12e-6, 0.0]), input_axis="AX2", output_axis="AX3", step_m=0.1)
    >>> t.text().splitlines()[2:5]
    ['$AN_CEC[0,0]=0.0000', '$AN_CEC[0,1]=-0.0120', '$AN_CEC[0,2]=0.0000']
    """
    x = np.asarray(position_m, dtype=float)
    e = np.asarray(deviation_m, dtype=float)
    if x.shape != e.shape or x.ndim != 1 or x.size < 2:
        raise AxiscalError("positions and deviations must be two equal lists of at least 2 values")
    if np.any(np.diff(x) <= 0):
        raise AxiscalError("the positions of the run must be strictly increasing")
    if not (math.isfinite(step_m) and step_m > 0):
        raise AxiscalError(f"the step must be a positive length, not {step_m / MM:g} mm")
    if reference not in SAG_REFERENCES:
        raise AxiscalError(f"unknown reference '{reference}'; use one of {', '.join(SAG_REFERENCES)}")
    if direction not in (0, 1, -1):
        raise AxiscalError(f"$AN_CEC_DIRECTION is 0, 1 or -1, not {direction}")
    if table < 0:
        raise AxiscalError(f"table indices start at 0, not {table}")
    if input_axis.strip().upper() == output_axis.strip().upper():
        raise AxiscalError("the base axis and the compensation axis must differ (sag is a cross-axis compensation)")
    if reference != "none":
        e = reference_line(x, e, reference=reference).residuals(x, e)
    count = int(math.ceil((x[-1] - x[0]) / step_m - 1e-9)) + 1
    if max_points is not None and count > max_points:
        raise AxiscalError(f"{count} points: MD18342 reserves {max_points} for table {table}; give a larger step")
    nodes = x[0] + step_m * np.arange(count)
    resampled = nodes.size != x.size or not np.allclose(nodes, x, rtol=0, atol=1e-9)
    values_mm = np.round(np.interp(nodes, x, e) / MM, 4)
    return SinumerikSagTable(
        table=table,
        input_axis=input_axis.strip(),
        output_axis=output_axis.strip(),
        start_m=float(x[0]),
        step_m=float(step_m),
        values_mm=values_mm,
        direction=direction,
        resampled=resampled,
    )
