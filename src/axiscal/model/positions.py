"""Positions of a machine's axes named by people: a grid specification (``"X=0:190:10,Z=5"``) or
a list of points, turned into arrays of SI positions, and the unit of each axis in files."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from axiscal.conventions import ROTARY_LETTERS
from axiscal.errors import AxiscalError
from axiscal.io.formats.machine import MAX_MACHINE_SIZE_MM
from axiscal.model.kinematics import AXIS_INDEX
from axiscal.model.tables import _floats
from axiscal.units import ANGLE_UNITS, MM

__all__ = ["AXIS_UNITS", "MAX_GRID_POINTS", "MAX_MACHINE_SIZE_MM", "axis_positions_from_grid", "positions_from_points"]

#: factor to SI and display unit of each axis' positions in files and on the command line
AXIS_UNITS = {letter: (MM, "mm") for letter in AXIS_INDEX} | {letter: (ANGLE_UNITS["deg"], "deg") for letter in ROTARY_LETTERS}
#: most points a grid may name (about 1 GB of positions and errors)
MAX_GRID_POINTS = 20_000_000


def axis_positions_from_grid(spec: str) -> dict[str, np.ndarray]:
    """Every combination of axis positions a grid specification names.

    Parameters
    ----------
    spec : str
        ``"X=0:190:10,Z=0:190:10"``: per axis ``start:end:step`` in mm, or degrees for a rotary
        axis (``"C=0:360:15"``), ends inclusive, or a single value ``"Y=50"``.

    Returns
    -------
    dict of str to ndarray, shape (N,)
        Position of each named axis (metres; radians for rotary axes), N the product of the
        axes' counts.

    Raises
    ------
    AxiscalError
        A part that is not of that form, a number that is not finite, an axis named twice,
        ``end < start``, ``step <= 0``, or more than :data:`MAX_GRID_POINTS` points.

    Examples
    --------
    >>> {k: v.tolist() for k, v in axis_positions_from_grid("X=0:20:10,Z=5").items()}
    {'X': [0.0, 0.01, 0.02], 'Z': [0.005, 0.005, 0.005]}
    """
    if not isinstance(spec, str):
        raise AxiscalError(f"a grid is a string such as 'X=0:190:10,Z=5', not {spec!r}")
    ranges: dict[str, np.ndarray] = {}
    total = 1
    for part in spec.split(","):
        letter, sep, rng = part.partition("=")
        letter = letter.strip().upper()
        bits = [b.strip() for b in rng.split(":")]
        if not sep or letter not in AXIS_UNITS or len(bits) not in (1, 3):
            raise AxiscalError(
                f"grid '{spec}': expected parts like 'X=0:190:10' (start:end:step in mm, deg for A, B, C) or 'Y=50'"
            )
        try:
            numbers = [float(b) for b in bits]
        except ValueError:
            raise AxiscalError(f"grid '{spec}': '{rng}' is not numbers") from None
        if not all(math.isfinite(v) and abs(v) <= MAX_MACHINE_SIZE_MM for v in numbers):
            raise AxiscalError(f"grid '{spec}': axis {letter} needs finite numbers within ±{MAX_MACHINE_SIZE_MM:g} mm")
        if letter in ranges:
            raise AxiscalError(f"grid '{spec}' names axis {letter} twice")
        if len(numbers) == 1:
            ranges[letter] = np.array(numbers)
            continue
        start, end, step = numbers
        if step <= 0 or end < start:
            raise AxiscalError(f"grid '{spec}': need start <= end and step > 0 for axis {letter}")
        count = math.floor((end - start) / step + 1e-9) + 1
        total *= count
        if total > MAX_GRID_POINTS:
            raise AxiscalError(f"grid '{spec}' has more than {MAX_GRID_POINTS} points; use a coarser step")
        # the grid's resolution is that of its numbers as written: 0.1 * 3 is 0.3, not 0.30000000000000004
        decimals = max(len(b.lower().split("e")[0].partition(".")[2]) for b in bits) + 3
        ranges[letter] = np.round(start + step * np.arange(count), decimals)
    mesh = np.meshgrid(*ranges.values(), indexing="ij")
    return {letter: grid.ravel() * AXIS_UNITS[letter][0] for letter, grid in zip(ranges, mesh)}


def positions_from_points(sequence: Sequence[Mapping[str, float]]) -> dict[str, np.ndarray]:
    """Turn a list of points into arrays per axis.

    Parameters
    ----------
    sequence : sequence of mapping of str to float
        Points such as ``{"X": 0.1, "Z": 0.05}`` (metres), all naming the same axes.

    Returns
    -------
    dict of str to ndarray, shape (N,)
        Metres.

    Raises
    ------
    AxiscalError
        Points that are not mappings, name different axes, or hold values that are not numbers.
    """
    if not isinstance(sequence, Sequence) or not sequence or not all(isinstance(p, Mapping) for p in sequence):
        raise AxiscalError("points must be a list of at least one mapping such as {'X': 0.1, 'Z': 0.05}")
    letters = list(sequence[0]) if sequence else []
    for k, point in enumerate(sequence):
        if set(point) != set(letters):
            raise AxiscalError(f"point {k + 1} names axes {sorted(point)}, the first point {sorted(letters)}")
    out = {k: _floats([p[k] for p in sequence], f"point positions of axis {k}") for k in letters}
    for k, q in out.items():
        if q.ndim != 1:
            raise AxiscalError(f"point positions of axis {k} must be one number per point")
        if not np.all(np.isfinite(q)):
            raise AxiscalError(f"point {int(np.argmax(~np.isfinite(q))) + 1}: the position of axis {k} must be a finite number")
    return out
