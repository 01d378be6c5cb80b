"""The machine model's input files and point specifications: axis positions, tool targets, diagonal readings.

Formats in docs/formats.md (sections "Points", "Target points", "Diagonal interferometer readings").
Files are in mm; everything returned is SI (metres). A bad file raises :class:`AxiscalError` naming
the file and the line.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from axiscal.conventions import AXIS_INDEX
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_mapping
from axiscal.io.tabular import read_csv
from axiscal.model.machine import AXIS_UNITS, Machine
from axiscal.units import MM, UM

__all__ = [
    "READING_TOLERANCE_M",
    "read_points",
    "check_travel",
    "parse_point",
    "read_targets",
    "read_interferometer",
]

#: how closely ``nominal_mm`` of a diagonal reading must match the diagonal's own point
READING_TOLERANCE_M = 1.0 * UM


def read_points(path: str | Path, machine: Machine) -> tuple[dict[str, np.ndarray], tuple[int, ...]]:
    """Axis positions from a CSV with one ``<axis>_mm`` column per axis of the machine.

    Parameters
    ----------
    path : str or Path
        CSV with columns ``x_mm``, ``y_mm``, ``z_mm`` and, for rotary axes, ``a_deg``, ``b_deg``,
        ``c_deg`` (those of the machine's chain; ``X_mm`` is accepted too; other columns are
        ignored).
    machine : Machine
        The machine whose axes are read; every position must lie inside its error tables.

    Returns
    -------
    positions : dict of str to ndarray, shape (N,)
        Position of every axis of the chain: metres, radians for rotary axes.
    lines : tuple of int
        The file's line number of each point.

    Raises
    ------
    AxiscalError
        A missing column, a cell that is not a finite number, or a position outside an error
        table, naming the file and the line.

    Examples
    --------
    >>> positions, lines = read_points("points.csv", machine)  # doctest: +SKIP
    """
    check_instance("machine", machine, Machine)
    table = read_csv(path)
    positions = {}
    for letter in machine.letters:
        factor, unit = AXIS_UNITS[letter]
        column = f"{letter.lower()}_{unit}" if table.has(f"{letter.lower()}_{unit}") else f"{letter}_{unit}"
        if not table.has(column):
            raise AxiscalError(
                f"missing column '{letter.lower()}_{unit}' for axis {letter}", path=str(path), line=table.header_line
            )
        positions[letter] = table.numeric(column) * factor
    check_travel(machine, positions, path=str(path), lines=table.lines)
    return positions, table.lines


def check_travel(
    machine: Machine, positions: Mapping[str, np.ndarray], *, path: str | None = None, lines: Sequence[int] | None = None
) -> None:
    """Raise naming the first point outside an axis' error table.

    Parameters
    ----------
    machine : Machine
        The machine whose error tables bound the travel.
    positions : mapping of str to ndarray, shape (N,)
        Positions of the machine's axes, metres (axes not in the mapping are not checked).
    path : str, optional
        The file (or option, such as ``"--grid"``) the positions came from, for the message.
    lines : sequence of int, optional
        Line of each position in that file.

    Returns
    -------
    None
        Returns only when every position is inside its table.

    Raises
    ------
    AxiscalError
        ``"X = 200 mm is outside the error table of axis X (0 to 190 mm)"``, with file and line.
    """
    check_instance("machine", machine, Machine)
    check_mapping("positions", positions, what="a mapping of axis letters to positions")
    given = {k: check_array(f"positions[{k!r}]", positions[k], finite=False, unit="") for k in machine.letters if k in positions}
    if lines is not None:
        if isinstance(lines, (str, bytes)) or not isinstance(lines, Sequence) or any(
            not isinstance(n, (int, np.integer)) for n in lines
        ):
            raise AxiscalError(f"lines must be a sequence of line numbers, not {lines!r:.40}")
        if any(len(lines) < q.size for q in given.values()):
            raise AxiscalError("lines must give a line number for every position")
    for letter, q in given.items():
        machine.table(letter).check_range(q, path=path, lines=lines)


def parse_point(text: str, option: str = "point") -> dict[str, float]:
    """Axis positions written as ``"X=0,Z=190"`` (mm), in metres.

    Parameters
    ----------
    text : str
        Comma-separated ``<axis>=<mm>`` parts; axes X, Y, Z.
    option : str
        Name used in the error message (the command-line option, e.g. ``"--from"``).

    Returns
    -------
    dict of str to float
        Axis letter to position, metres.

    Raises
    ------
    AxiscalError
        If a part is not ``<axis>=<number>``.

    Examples
    --------
    >>> parse_point("X=0,Z=190")
    {'X': 0.0, 'Z': 0.19}
    """
    check_instance("option", option, str)
    if not isinstance(text, str):
        raise AxiscalError(f"{option} must be axis positions in mm like 'X=0,Z=190', not {text!r:.40}")
    point: dict[str, float] = {}
    for part in text.split(","):
        letter, sep, value = part.partition("=")
        letter = letter.strip().upper()
        try:
            number = float(value)
        except ValueError:
            number = float("nan")
        if not sep or letter not in AXIS_INDEX or letter in point or not np.isfinite(number):
            raise AxiscalError(f"{option} '{text}': expected axis positions in mm like 'X=0,Z=190'")
        point[letter] = number * MM
    return point


def read_targets(path: str | Path) -> tuple[np.ndarray, tuple[int, ...]]:
    """Wanted tool points from a CSV ``x_mm, y_mm, z_mm`` (relative to the workpiece point, workpiece frame).

    Parameters
    ----------
    path : str or Path
        The CSV file (docs/formats.md, "Target points").

    Returns
    -------
    targets : ndarray, shape (N, 3)
        The points, metres.
    lines : tuple of int
        The file's line number of each point.

    Raises
    ------
    AxiscalError
        A missing column or a cell that is not a finite number, naming the file and the line.
    """
    table = read_csv(path)
    table.require("x_mm", "y_mm", "z_mm")
    return np.column_stack([table.numeric(f"{c}_mm") for c in "xyz"]) * MM, table.lines


def read_interferometer(path: str | Path, nominal_m: np.ndarray | None = None) -> np.ndarray:
    """Interferometer readings on a diagonal: CSV ``nominal_mm, measured_mm``, zeroed at the start.

    Parameters
    ----------
    path : str or Path
        The CSV file (docs/formats.md, "Diagonal interferometer readings"), at least 2 rows.
    nominal_m : ndarray, shape (N,), optional
        The diagonal's nominal displacements, metres: the file must have as many rows, each
        ``nominal_mm`` within :data:`READING_TOLERANCE_M` of its point, so that readings cannot be
        paired with the wrong points.

    Returns
    -------
    ndarray, shape (N,)
        The readings (``measured_mm``), metres.

    Raises
    ------
    AxiscalError
        A missing column, a bad cell, a different number of rows or a ``nominal_mm`` that does not
        match, naming the file and the line.
    """
    if nominal_m is not None:
        nominal_m = check_array("nominal_m", nominal_m, ndim=1)
    table = read_csv(path, min_rows=2)
    table.require("nominal_mm", "measured_mm")
    nominal = table.numeric("nominal_mm") * MM
    measured = table.numeric("measured_mm") * MM
    if nominal_m is not None:
        if nominal.size != nominal_m.size:
            raise AxiscalError(f"{nominal.size} readings for a diagonal of {nominal_m.size} points", path=str(path))
        off = np.abs(nominal - nominal_m) > READING_TOLERANCE_M
        if np.any(off):
            k = int(np.argmax(off))
            raise AxiscalError(
                f"nominal_mm {nominal[k] / MM:.6f} does not match the diagonal's point {k} at {nominal_m[k] / MM:.6f} mm",
                path=str(path),
                line=table.lines[k],
            )
    return measured
