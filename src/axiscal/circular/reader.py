"""Reading ballbar traces from CSV (``angle_deg, direction, radius_deviation_um``), with errors that name the file and the line.

Columns (see docs/ballbar.md): ``angle_deg`` (from the plane's first axis towards its second),
``direction`` (``ccw`` or ``cw``, any case) and one ``radius_deviation_<unit>`` with unit nm, um
or mm (measured length minus the nominal radius). Other columns are ignored.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from axiscal.circular.evaluation import (
    DIRECTIONS,
    BallbarTrace,
    check_direction,
    plane_axes,
)
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_path, is_real
from axiscal.io.tabular import read_csv
from axiscal.units import length_factor

__all__ = ["DEVIATION_STEM", "read_ballbar"]

#: the stem of the deviation column, followed by ``_nm``, ``_um`` or ``_mm``
DEVIATION_STEM = "radius_deviation"


def read_ballbar(path: str | Path, *, radius: float, plane: str = "XY") -> BallbarTrace:
    """Read a ballbar trace from CSV.

    Parameters
    ----------
    path : str or Path
        The CSV file.
    radius : float, metres, keyword-only
        Nominal radius of the test (the ballbar's length).
    plane : str, keyword-only
        The plane, first axis then second (``"XY"``, ``"ZX"``, ...).

    Returns
    -------
    BallbarTrace

    Raises
    ------
    AxiscalError
        Naming the file and the line: a missing column, no or two deviation columns, a length
        unit other than nm, um, mm, a cell that is not a finite number, a direction other than
        ccw or cw, a direction with too few points or a gap in its circle; naming the file: a
        radius that is not positive or an unknown plane.

    Examples
    --------
    >>> import tempfile, os
    >>> rows = "\\n".join(f"{k * 5.0},ccw,0.5" for k in range(72))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     p = os.path.join(folder, "run.csv")
    ...     _ = open(p, "w").write("angle_deg,direction,radius_deviation_um\\n" + rows + "\\n")
    ...     trace = read_ballbar(p, radius=0.1)
    >>> trace.present, round(float(trace.deviations[0]) * 1e6, 3)
    (('ccw',), 0.5)
    """
    path = str(check_path("path", path))
    try:
        plane = "".join(plane_axes(plane))
        if not (is_real(radius) and math.isfinite(radius) and radius > 0):
            raise AxiscalError(f"the nominal radius must be a positive length, got {radius!r} m")
    except AxiscalError as exc:
        raise exc.located(path=path) from None
    table = read_csv(path)
    table.require("angle_deg", "direction")
    found = [name for name in table.header if name.rpartition("_")[0] == DEVIATION_STEM]
    if len(found) != 1:
        problem = "no" if not found else f"{len(found)} ({', '.join(found)})"
        raise AxiscalError(
            f"{problem} {DEVIATION_STEM}_<unit> columns; give exactly one, in nm, um or mm (columns are: {', '.join(table.header)})",
            path=path,
            line=table.header_line,
        )
    name = found[0]
    try:
        factor = length_factor(name.rpartition("_")[2], what=f"column '{name}'")
    except AxiscalError as exc:
        raise exc.located(path=path, line=table.header_line) from None
    angles = np.radians(table.numeric("angle_deg"))
    deviations = table.numeric(name) * factor
    directions = []
    for k, text in enumerate(table.text("direction")):
        d = text.lower()
        if d not in DIRECTIONS:
            raise AxiscalError(f"column 'direction': '{text}' is not a direction; use ccw or cw", path=path, line=table.lines[k])
        directions.append(d)
    labels = np.array(directions, dtype=object)
    for d in DIRECTIONS:
        rows = np.flatnonzero(labels == d)
        if rows.size == 0:
            continue
        problem = check_direction(angles[rows], d)
        if problem is not None:
            message, k = problem
            raise AxiscalError(message, path=path, line=table.lines[int(rows[k])])
    return BallbarTrace(angles, tuple(directions), deviations, radius=radius, plane=plane, source=path)
