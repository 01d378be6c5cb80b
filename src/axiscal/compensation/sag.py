"""Cross-axis (sag and straightness) compensation tables: SINUMERIK ``$AN_CEC`` and HEIDENHAIN dependent-axis ``.COM``.

SINUMERIK function manual "Compensations" (K3), interpolatory compensation, sag and angularity
error compensation: table ``t`` of ``%_N_NC_CEC_INI`` holds ``$AN_CEC[t,N]`` (mm) at equidistant
positions of a base axis (``$AN_CEC_INPUT_AXIS``) from ``$AN_CEC_MIN`` in steps of
``$AN_CEC_STEP`` to ``$AN_CEC_MAX``, applied to a compensation axis (``$AN_CEC_OUTPUT_AXIS``),
linearly interpolated, the end values held beyond. The number of points is reserved by MD18342
``$MN_MM_CEC_MAX_POINTS[t]`` (fixed at 200 on an 828D). Sign: K3 defines a compensation value as
the position reached minus the programmed position, the convention of the measuring-system table
(:class:`axiscal.compensation.SiemensTable`): the table holds the straightness deviation of the
compensation axis and the control removes it.

HEIDENHAIN technical manuals (TNC 407, MANUALplus 620), nonlinear axis error compensation with a
dependent axis: a ``.COM`` table whose AXISPOS column holds positions of the base axis and whose
axis column holds the error of the compensation axis (``Z = F(Y)``), entered in the base axis's
column of the ``.CMA`` table; at most 256 rows, the error subtracted by the control with linear
interpolation (:class:`axiscal.compensation.HeidenhainTable`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pathlib import Path

from axiscal.compensation.heidenhain import HEIDENHAIN_MAX_ENTRIES, HeidenhainTable
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_integer, check_number
from axiscal.straightness import reference_line
from axiscal.units import MM

__all__ = ["SAG_CONTROLLERS", "SAG_REFERENCES", "SinumerikSagTable", "heidenhain_sag_table", "sag_table_file",
           "sinumerik_sag_table"]

#: how much of the measured deviation the table takes: all of it, or what is left about a line
SAG_REFERENCES = ("none", "least-squares", "end-points")
#: controllers with a cross-axis table axiscal writes
SAG_CONTROLLERS = ("siemens", "heidenhain")


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
        return -np.interp(check_array("x", x, unit="metres"), self.nodes, self.values_mm * MM)

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
    if check_integer("direction", direction) not in (0, 1, -1):
        raise AxiscalError(f"$AN_CEC_DIRECTION is 0, 1 or -1, not {direction}")
    if check_integer("table", table) < 0:
        raise AxiscalError(f"table indices start at 0, not {table}")
    x, e = _cross_axis_run(position_m, deviation_m, input_axis, output_axis, reference)
    if max_points is not None:
        check_integer("max_points", max_points)
    count = _point_count(x, step_m)
    if max_points is not None and count > max_points:
        raise AxiscalError(f"{count} points: MD18342 reserves {max_points} for table {table}; give a larger step")
    nodes = x[0] + step_m * np.arange(count)
    resampled = _moved(nodes, x)
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


def _cross_axis_run(position_m, deviation_m, base_axis: str, compensation_axis: str, reference: str):
    """The checked run (positions strictly increasing, finite) with the chosen line removed."""
    x = check_array("position_m", position_m, finite=False)
    e = check_array("deviation_m", deviation_m, finite=False)
    if x.shape != e.shape or x.ndim != 1 or x.size < 2:
        raise AxiscalError("positions and deviations must be two equal lists of at least 2 values")
    if not (np.isfinite(x).all() and np.isfinite(e).all()):
        raise AxiscalError("positions and deviations must be finite numbers")
    if np.any(np.diff(x) <= 0):
        raise AxiscalError("the positions of the run must be strictly increasing")
    if not isinstance(reference, str) or reference not in SAG_REFERENCES:
        raise AxiscalError(f"unknown reference {reference!r}; use one of {', '.join(SAG_REFERENCES)}")
    if not (isinstance(base_axis, str) and isinstance(compensation_axis, str) and base_axis.strip() and compensation_axis.strip()):
        raise AxiscalError("name the base axis and the compensation axis")
    if base_axis.strip().upper() == compensation_axis.strip().upper():
        raise AxiscalError("the base axis and the compensation axis must differ (sag is a cross-axis compensation)")
    if reference != "none":
        e = reference_line(x, e, reference=reference).residuals(x, e)
    return x, e


def _point_count(x: np.ndarray, step_m: float) -> int:
    """Points of an equidistant table from the run's first position past its last."""
    step_m = check_number("step_m", step_m)
    if not step_m > 0:
        raise AxiscalError(f"the step must be a positive length, not {step_m / MM:g} mm")
    count = (x[-1] - x[0]) / step_m
    if count > 1e6:
        raise AxiscalError(f"a step of {step_m / MM:g} mm gives more than 10^6 points over the run; give a larger step")
    return int(math.ceil(count - 1e-9)) + 1


def _moved(nodes: np.ndarray, x: np.ndarray) -> bool:
    return nodes.size != x.size or not np.allclose(nodes, x, rtol=0, atol=1e-9)


def heidenhain_sag_table(
    position_m: np.ndarray,
    deviation_m: np.ndarray,
    *,
    base_axis: str,
    compensation_axis: str,
    step_m: float | None = None,
    reference: str = "none",
    name: str | None = None,
    decimals: int = 4,
) -> HeidenhainTable:
    """A HEIDENHAIN dependent-axis ``.COM`` table (``compensation_axis = F(base_axis)``) from a straightness run.

    Parameters
    ----------
    position_m : ndarray, shape (n,)
        Base axis positions of the run (machine datum), metres, strictly increasing.
    deviation_m : ndarray, shape (n,)
        Deviation of the tool along the compensation axis (position reached - programmed), metres.
    base_axis, compensation_axis : str, keyword-only
        Axis keys of CfgAxes/axisList (letters): the ``.CMA`` column the table is entered in and
        the ``.COM`` column that holds the error.
    step_m : float, optional, keyword-only
        Row spacing, metres: the run is resampled on it from its first position (linear
        interpolation; a last row beyond the run holds the end value). Default: one row per
        measured position.
    reference : str, keyword-only
        ``"none"``: the whole deviation; ``"least-squares"`` or ``"end-points"``: the deviation about
        that line only (the angularity left to a squareness correction).
    name : str, optional, keyword-only
        File name without ``.COM`` (default ``<base><compensation>``, e.g. ``YZ``).
    decimals : int, keyword-only
        Decimals of the mm columns (default 4: 0.1 um).

    Returns
    -------
    HeidenhainTable
        With ``axis`` the compensation axis and ``base_axis`` the base axis; its ``note`` says
        where to enter it.

    Raises
    ------
    AxiscalError
        For positions not strictly increasing or not finite, mismatched shapes, an axis name that
        is not letters, the same axis twice, a non-positive step, an unknown reference, a name
        that is not a plain file name, or more than 256 rows.

    Examples
    --------
    >>> import numpy as np
    >>> y = np.array([0.0, 0.1, 0.2])
    >>> t = heidenhain_sag_table(y, np.array([0.0, -12e-6, 0.0]), base_axis="Y", compensation_axis="Z")
    >>> print(t.text(), end="")
    BEGIN YZ.COM MM
    NR           AXISPOS             Z
    0            +0.0000       +0.0000
    1          +100.0000       -0.0120
    2          +200.0000       +0.0000
    [END]
    """
    x, e = _cross_axis_run(position_m, deviation_m, base_axis, compensation_axis, reference)
    base, axis = base_axis.strip().upper(), compensation_axis.strip().upper()
    for letters in (base, axis):
        if not letters.isalpha() or not letters.isascii():
            raise AxiscalError(f"'{letters}' is not an axis key (letters, as in CfgAxes/axisList)")
    name = name if name is not None else base + axis
    if not (isinstance(name, str) and name and all(c.isalnum() or c in "_-" for c in name) and name.isascii()):
        raise AxiscalError(f"'{name}' is not a plain file name (letters, digits, _ and -)")
    if not isinstance(decimals, int) or not 0 <= decimals <= 6:
        raise AxiscalError(f"decimals must be a whole number 0..6, not {decimals}")
    nodes = x if step_m is None else x[0] + step_m * np.arange(_point_count(x, step_m))
    if nodes.size > HEIDENHAIN_MAX_ENTRIES:
        raise AxiscalError(f"{nodes.size} rows: a .COM table holds at most {HEIDENHAIN_MAX_ENTRIES}; give a step"
                           f" of at least {(x[-1] - x[0]) / (HEIDENHAIN_MAX_ENTRIES - 1) / MM:.4g} mm")
    positions = np.round(nodes / MM, decimals) + 0.0
    error = np.round(np.interp(nodes, x, e) / MM, decimals) + 0.0
    return HeidenhainTable(axis, positions, error, None, decimals, MM, base_axis=base, name=name,
                           resampled=_moved(nodes, x))


def sag_table_file(
    path: str | Path,
    *,
    controller: str,
    base_axis: str,
    compensation_axis: str,
    step_m: float | None = None,
    reference: str = "none",
    table: int = 0,
    direction: int = 0,
    max_points: int | None = None,
    name: str | None = None,
) -> SinumerikSagTable | HeidenhainTable:
    """A controller's cross-axis table from a straightness run file (what ``axiscal export sag`` writes).

    Parameters
    ----------
    path : str or Path
        A straightness profile (``position_mm`` and a deviation column, as
        :func:`axiscal.straightness.read_profile` reads) measured along the base axis.
    controller : {"siemens", "heidenhain"}, keyword-only
        SINUMERIK ``$AN_CEC`` (:func:`sinumerik_sag_table`) or HEIDENHAIN dependent-axis ``.COM``
        (:func:`heidenhain_sag_table`).
    base_axis, compensation_axis : str, keyword-only
        The controller's names of the axis the run moves and the axis the deviation is along.
    step_m : float, optional, keyword-only
        Point spacing, metres: required for SINUMERIK; for HEIDENHAIN it resamples the run.
    reference : str, keyword-only
        One of :data:`SAG_REFERENCES`.
    table, direction, max_points : keyword-only
        SINUMERIK only: table index, ``$AN_CEC_DIRECTION`` and MD18342.
    name : str, optional, keyword-only
        HEIDENHAIN only: the ``.COM`` file's name without extension.

    Returns
    -------
    SinumerikSagTable or HeidenhainTable
        ``.text()`` is the file; ``.note`` says what to know before loading it.

    Raises
    ------
    AxiscalError
        For a bad file (naming file and line), an unknown controller, a missing SINUMERIK step, an
        option the controller does not have, and every refusal of the table functions.

    Examples
    --------
    >>> t = sag_table_file("examples/squareness_y.csv", controller="heidenhain", base_axis="Y",
    ...                    compensation_axis="X")  # doctest: +SKIP
    """
    from axiscal.straightness import read_profile

    if not isinstance(controller, str) or controller not in SAG_CONTROLLERS:
        raise AxiscalError(f"unknown controller {controller!r}; sag tables are written for {', '.join(SAG_CONTROLLERS)}")
    check_integer("table", table)
    check_integer("direction", direction)
    if controller == "heidenhain" and (table != 0 or direction != 0 or max_points is not None):
        raise AxiscalError("the table index, direction and maximum points are SINUMERIK settings; a HEIDENHAIN .COM has none")
    if controller == "siemens" and name is not None:
        raise AxiscalError("a file name is a HEIDENHAIN setting; the SINUMERIK program is %_N_NC_CEC_INI")
    if controller == "siemens" and step_m is None:
        raise AxiscalError("a SINUMERIK table needs the step ($AN_CEC_STEP) of its equidistant points")
    profile = read_profile(path, increasing=True)
    if controller == "siemens":
        return sinumerik_sag_table(profile.position_m, profile.deviation_m, input_axis=base_axis,
                                   output_axis=compensation_axis, step_m=step_m, table=table, reference=reference,
                                   direction=direction, max_points=max_points)
    return heidenhain_sag_table(profile.position_m, profile.deviation_m, base_axis=base_axis,
                                compensation_axis=compensation_axis, step_m=step_m, reference=reference, name=name)
