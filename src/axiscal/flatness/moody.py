"""Moody's evaluation of a Union Jack: eight lines joined through the diagonals, the closure at the centre lines.

J. C. Moody, "How to calibrate surface plates in the plant", *The Tool Engineer*, October 1955
(the method of Hume's *Engineering Metrology*, and of ASME B89.3.7 surface plate calibration);
its worksheets as corrected by B. Allen (2018). The two diagonals are tilted so that their ends
stand level and they meet at height zero in the middle; the four edges are tilted to meet the
diagonals' corners; the two centre lines are tilted to meet the edges' middles. Where a centre
line's middle then stands above or below the diagonals' crossing is its closure error, and the
line is shifted by it (Moody's column 6a). The heights are about Moody's reference (the
diagonals' plane), the flatness the spread of all heights; :class:`FlatnessSurface` adds the
least-squares and minimum-zone figures of the same points.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.flatness.surface import (
    Closure,
    FlatnessLine,
    FlatnessSurface,
    _check_crossings,
    _check_lines,
    _nodes,
    flatness_zone,
)

__all__ = ["moody_union_jack"]


def _middle(line: FlatnessLine, heights: np.ndarray) -> float:
    """The height of the line's middle station (the crossings are checked to be stations)."""
    return float(heights[np.argmin(np.abs(line.distance_m - 0.5 * line.length_m))])


def _ends(line: FlatnessLine, heights: np.ndarray, first: float, last: float) -> np.ndarray:
    """The line tilted and raised so that its ends stand at ``first`` and ``last``."""
    s = line.distance_m / line.length_m
    return heights + (first - heights[0]) * (1.0 - s) + (last - heights[-1]) * s


def moody_union_jack(lines: Sequence[FlatnessLine]) -> FlatnessSurface:
    """Join the eight lines of a Union Jack by Moody's method (1955).

    Parameters
    ----------
    lines : sequence of FlatnessLine
        The eight lines, in any order and direction: two diagonals joining opposite corners of the
        rectangle the lines span, its four edges, and two centre lines joining the middles of
        opposite edges. Each line's stations must include both its ends.

    Returns
    -------
    FlatnessSurface
        The evaluation ``"moody"``: ``line_heights_m`` are Moody's heights (his column 6, the
        centre lines' column 6a), the two closures are the centre lines' middles before their
        shift; ``x_m, y_m, z_m`` are the points about their least-squares plane.

    Raises
    ------
    AxiscalError
        Lines that do not make a Union Jack (naming what is missing), a line whose stations do
        not reach both its ends, or two lines that meet at a place (the centre, an edge's middle)
        that is not a station of both (naming them and the place): nothing is interpolated.

    Examples
    --------
    >>> import numpy as np
    >>> from axiscal.flatness.surface import FlatnessLine
    >>> corners = {"SW": (0, 0), "SE": (2, 0), "NE": (2, 1), "NW": (0, 1), "S": (1, 0), "N": (1, 1),
    ...            "W": (0, 0.5), "E": (2, 0.5)}
    >>> def flat(a, b):
    ...     return FlatnessLine(f"{a}-{b}", corners[a], corners[b], [0, 0.5 * np.hypot(*np.subtract(corners[b], corners[a])),
    ...                         np.hypot(*np.subtract(corners[b], corners[a]))], [0, 0, 0])
    >>> jack = [flat(*p) for p in (("SW", "NE"), ("NW", "SE"), ("SW", "SE"), ("NW", "NE"), ("SW", "NW"),
    ...                             ("SE", "NE"), ("W", "E"), ("S", "N"))]
    >>> moody_union_jack(jack).zone.minimum_zone_m
    0.0
    """
    lines = _check_lines(lines)
    if len(lines) != 8:
        raise AxiscalError(f"Moody's method joins the 8 lines of a Union Jack, not {len(lines)}")
    ends = np.array([[line.start_m, line.end_m] for line in lines])
    x0, y0 = ends[..., 0].min(), ends[..., 1].min()
    x1, y1 = ends[..., 0].max(), ends[..., 1].max()
    tolerance = 1e-6 * max(x1 - x0, y1 - y0)
    places = {
        "SW": (x0, y0), "SE": (x1, y0), "NE": (x1, y1), "NW": (x0, y1),
        "S": ((x0 + x1) / 2, y0), "N": ((x0 + x1) / 2, y1), "W": (x0, (y0 + y1) / 2), "E": (x1, (y0 + y1) / 2),
    }

    def place(point: np.ndarray) -> str | None:
        for label, (px, py) in places.items():
            if abs(point[0] - px) <= tolerance and abs(point[1] - py) <= tolerance:
                return label
        return None

    roles: dict[frozenset, int] = {}
    for k, line in enumerate(lines):
        pair = frozenset(filter(None, (place(line.start_m), place(line.end_m))))
        if len(pair) != 2 or pair in roles:
            raise AxiscalError(f"line {line.name!r} is not one of a Union Jack's lines (its diagonals, edges and centre lines)")
        slack = 1e-6 * line.length_m
        if line.distance_m[0] > slack or line.distance_m[-1] < line.length_m - slack:
            raise AxiscalError(f"line {line.name!r}: Moody's method needs stations at both ends of every line")
        roles[pair] = k
    # every place where two lines meet (the centre, the edges' middles) must be a station of both:
    # nothing is interpolated
    _check_crossings(lines)
    wanted = [frozenset(p) for p in (("SW", "NE"), ("NW", "SE"), ("SW", "SE"), ("NW", "NE"), ("SW", "NW"),
                                     ("SE", "NE"), ("W", "E"), ("S", "N"))]
    missing = ["-".join(sorted(p)) for p in wanted if p not in roles]
    if missing:
        raise AxiscalError(f"the lines are not a Union Jack: no line {', '.join(missing)}")

    heights: dict[int, np.ndarray] = {}
    corner: dict[str, float] = {}
    for pair in wanted[:2]:  # diagonals: ends level, middle at zero
        k = roles[pair]
        line = lines[k]
        h = _ends(line, line.height_m, 0.0, 0.0)
        h = h - _middle(line, h)
        heights[k] = h
        corner[place(line.start_m)] = float(h[0])
        corner[place(line.end_m)] = float(h[-1])
    middle: dict[str, float] = {}
    for pair in wanted[2:6]:  # edges through the corners
        k = roles[pair]
        line = lines[k]
        heights[k] = _ends(line, line.height_m, corner[place(line.start_m)], corner[place(line.end_m)])
        mid = "S" if pair == wanted[2] else "N" if pair == wanted[3] else "W" if pair == wanted[4] else "E"
        middle[mid] = _middle(line, heights[k])
    closures = []
    for pair in wanted[6:]:  # centre lines through the edges' middles, shifted by their closure
        k = roles[pair]
        line = lines[k]
        h = _ends(line, line.height_m, middle[place(line.start_m)], middle[place(line.end_m)])
        error = _middle(line, h)
        heights[k] = h - error
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        closures.append(Closure(float(cx), float(cy), (line.name,), error))
    joined = tuple(heights[k] for k in range(8))
    points = np.vstack([line.points_m for line in lines])
    z = np.concatenate(joined)
    node, spots = _nodes(points, float(max(x1 - x0, y1 - y0)))
    z_nodes = np.bincount(node, weights=z) / np.bincount(node)
    zone = flatness_zone(spots[:, 0], spots[:, 1], z_nodes)
    p = zone.least_squares_plane
    about = z_nodes - (p[0] * spots[:, 0] + p[1] * spots[:, 1] + p[2])
    return FlatnessSurface(lines, joined, spots[:, 0].copy(), spots[:, 1].copy(), about, tuple(closures), zone, "moody")
