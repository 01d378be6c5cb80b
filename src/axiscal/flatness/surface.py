"""Flatness of a surface measured along lines: the surface by least squares, its closure errors,
and the flatness about the least-squares plane and the minimum zone.

ISO 230-1 (flatness: the distance between the two parallel planes closest together that enclose
the surface, and the least-squares plane as the alternative reference) measured as in the grid
and Union Jack methods: straightness lines across the surface (from levels, an autocollimator or
a straightedge), each known only up to an offset and a tilt of its own. The heights of the
stations, one per place where lines cross, and each line's offset and tilt are fitted together by
least squares (the evaluation of Moody's eight lines "in a least-squares sense" of "Moody
Revisited", *Metrology* 2026, 6(2), 27, generalised to any layout of lines that tie the surface
together); the
lines' disagreement at a crossing is that crossing's closure error. The minimum zone is found by
linear programming (``scipy.optimize.linprog``, HiGHS).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_instance, check_number, check_same_length
from axiscal.levels.profile import level_profile

__all__ = [
    "EVALUATIONS",
    "FlatnessLine",
    "line_from_angles",
    "Closure",
    "FlatnessZone",
    "flatness_zone",
    "FlatnessSurface",
    "surface_from_lines",
]

#: how the lines are joined into a surface
EVALUATIONS = ("least-squares", "moody")
#: the largest coordinate or height taken, metres
_LIMIT_M = 1e6


def _point(name: str, value) -> np.ndarray:
    return check_array(name, value, ndim=1, last=2, limit=_LIMIT_M)


@dataclass(frozen=True)
class FlatnessLine:
    """One measured line across the surface: its ends and the heights of its stations.

    Attributes
    ----------
    name : str
        The line's name (``"NW-SE"``, ``"row 3"``).
    start_m, end_m : ndarray, shape (2,)
        Plan coordinates (x, y) of the line's first and last points, metres.
    distance_m : ndarray, shape (n,)
        Distance of each station from ``start_m`` along the line, metres, increasing, within the line.
    height_m : ndarray, shape (n,)
        The measured heights, metres, up to an offset and a tilt along the line.
    gravity : bool
        The heights' tilt along the line is measured against gravity (a level whose zero is
        known), so the least-squares evaluation keeps it and fits the line's offset only
        (default False: offset and tilt are fitted).
    """

    name: str
    start_m: np.ndarray
    end_m: np.ndarray
    distance_m: np.ndarray
    height_m: np.ndarray
    gravity: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise AxiscalError(f"a line's name must be a text, not {self.name!r}")
        if not isinstance(self.gravity, (bool, np.bool_)):
            raise AxiscalError(f"gravity must be True or False, not {self.gravity!r}")
        object.__setattr__(self, "start_m", _point("start_m", self.start_m))
        object.__setattr__(self, "end_m", _point("end_m", self.end_m))
        distance = check_array("distance_m", self.distance_m, ndim=1, min_len=2, limit=_LIMIT_M)
        height = check_array("height_m", self.height_m, ndim=1, limit=_LIMIT_M)
        check_same_length(distance_m=distance, height_m=height)
        object.__setattr__(self, "distance_m", distance)
        object.__setattr__(self, "height_m", height)
        length = self.length_m
        if not length > 0.0:
            raise AxiscalError(f"line {self.name!r}: its two ends are the same point")
        if np.any(np.diff(distance) <= 0.0):
            raise AxiscalError(f"line {self.name!r}: the stations' distances along the line must increase")
        slack = 1e-6 * length
        if distance[0] < -slack or distance[-1] > length + slack:
            raise AxiscalError(
                f"line {self.name!r}: the stations' distances reach {distance[0] * 1e3:g}..{distance[-1] * 1e3:g} mm along a line"
                f" {length * 1e3:g} mm long"
            )

    @property
    def length_m(self) -> float:
        """The distance between the line's ends, metres."""
        return float(np.hypot(*(self.end_m - self.start_m)))

    @property
    def points_m(self) -> np.ndarray:
        """Plan coordinates of the stations, metres, shape (n, 2)."""
        direction = (self.end_m - self.start_m) / self.length_m
        return self.start_m + self.distance_m[:, None] * direction


def line_from_angles(
    name: str, start_m: np.ndarray, end_m: np.ndarray, angle_rad: np.ndarray, *, foot_m: float, gravity: bool = False
) -> FlatnessLine:
    """A line measured with a level or an autocollimator, one reading per step, from start to end.

    The ``n`` readings are the slopes of ``n`` steps spread evenly over the line (``n + 1``
    stations, the first at the start, the last at the end); the rise of each step is the foot
    spacing times the reading (:func:`axiscal.levels.level_profile`, the classic foot chain).

    Parameters
    ----------
    name : str
        The line's name.
    start_m, end_m : array_like, shape (2,)
        Plan coordinates of the ends, metres.
    angle_rad : array_like, shape (n,)
        The readings, radians (rise over foot), positive when the surface rises towards ``end_m``.
    foot_m : float, keyword-only
        The foot spacing the rises are computed with, metres.
    gravity : bool, keyword-only
        The readings are against gravity (the level's zero is known): the line keeps its tilt
        (see :class:`FlatnessLine`; default False).

    Returns
    -------
    FlatnessLine

    Raises
    ------
    AxiscalError
        Fewer than 2 readings, readings that are not finite, a foot spacing that is not positive,
        ends that are not two finite coordinates or are the same point.

    Examples
    --------
    >>> line = line_from_angles("edge", [0, 0], [0.3, 0], [1e-5, 0.0, -1e-5], foot_m=0.1)
    >>> (line.height_m / 1e-6).round(6).tolist()
    [0.0, 1.0, 1.0, 0.0]
    """
    foot_m = check_number("foot_m", foot_m, positive=True, high=_LIMIT_M)
    angle = check_array("angle_rad", angle_rad, ndim=1, min_len=2)
    chain = level_profile(np.arange(angle.size) * foot_m, angle, foot_m=foot_m)
    start, end = _point("start_m", start_m), _point("end_m", end_m)
    length = float(np.hypot(*(end - start)))
    return FlatnessLine(name, start, end, np.linspace(0.0, length, angle.size + 1), chain.deviation_m, gravity)


@dataclass(frozen=True)
class Closure:
    """The lines' disagreement where they cross.

    Attributes
    ----------
    x_m, y_m : float
        Where, metres.
    lines : tuple of str
        The lines that cross there.
    value_m : float
        The closure error, metres: the spread (max - min) of the heights the lines give there
        (least-squares evaluation), or the height of a centre line's middle above the diagonals'
        crossing (Moody's evaluation, signed).
    """

    x_m: float
    y_m: float
    lines: tuple[str, ...]
    value_m: float

    def __post_init__(self) -> None:
        for name in ("x_m", "y_m", "value_m"):
            object.__setattr__(self, name, check_number(name, getattr(self, name)))
        if not isinstance(self.lines, tuple) or not self.lines or not all(isinstance(n, str) for n in self.lines):
            raise AxiscalError(f"lines must be a tuple of the crossing lines' names, not {self.lines!r}")


@dataclass(frozen=True)
class FlatnessZone:
    """The flatness of points about the least-squares plane and the minimum zone.

    Attributes
    ----------
    least_squares_m : float
        Max - min of the heights about the least-squares plane, metres.
    minimum_zone_m : float
        The minimum-zone width (the vertical distance between the two parallel planes closest
        together that enclose every point), metres.
    least_squares_plane : tuple of float
        ``(slope_x, slope_y, height_m)``: ``z = slope_x x + slope_y y + height_m``.
    minimum_zone_plane : tuple of float
        The lower plane of the minimum zone, in the same form.
    """

    least_squares_m: float
    minimum_zone_m: float
    least_squares_plane: tuple[float, float, float]
    minimum_zone_plane: tuple[float, float, float]

    def __post_init__(self) -> None:
        for name in ("least_squares_m", "minimum_zone_m"):
            object.__setattr__(self, name, check_number(name, getattr(self, name), nonnegative=True))
        for name in ("least_squares_plane", "minimum_zone_plane"):
            plane = check_array(name, getattr(self, name), ndim=1)
            if plane.size != 3:
                raise AxiscalError(f"{name} must be (slope_x, slope_y, height_m), not {getattr(self, name)!r}")
            object.__setattr__(self, name, tuple(float(v) for v in plane))


def flatness_zone(x_m: np.ndarray, y_m: np.ndarray, z_m: np.ndarray) -> FlatnessZone:
    """Flatness of points about the least-squares plane and by the minimum zone (ISO 230-1).

    Parameters
    ----------
    x_m, y_m : array_like, shape (n,)
        Plan coordinates, metres; at least 3 points not on one line.
    z_m : array_like, shape (n,)
        Heights, metres.

    Returns
    -------
    FlatnessZone

    Raises
    ------
    AxiscalError
        Arrays of different lengths, values that are not finite, fewer than 3 points or points all
        on one line in plan.

    Examples
    --------
    >>> zone = flatness_zone([0, 1, 0, 1], [0, 0, 1, 1], [0, 1e-6, 1e-6, 0])
    >>> round(zone.minimum_zone_m / 1e-6, 9), round(zone.least_squares_m / 1e-6, 9)
    (1.0, 1.0)
    """
    x = check_array("x_m", x_m, ndim=1, min_len=3, limit=_LIMIT_M)
    y = check_array("y_m", y_m, ndim=1, limit=_LIMIT_M)
    z = check_array("z_m", z_m, ndim=1, limit=_LIMIT_M)
    check_same_length(x_m=x, y_m=y, z_m=z)
    centre = np.array([x.mean(), y.mean()])
    scale = max(float(np.ptp(x)), float(np.ptp(y)))
    if not scale > 0.0:
        raise AxiscalError("the points are all at one place in plan: a plane needs 3 points not on one line")
    u, v = (x - centre[0]) / scale, (y - centre[1]) / scale
    design = np.column_stack([u, v, np.ones_like(u)])
    if np.linalg.matrix_rank(design, tol=1e-9) < 3:
        raise AxiscalError("the points lie on one line in plan: a plane needs 3 points not on one line")
    coef, *_ = np.linalg.lstsq(design, z, rcond=None)
    residual = z - design @ coef
    ls_width = float(np.ptp(residual))
    mz_coef, mz_width = _minimum_zone(design, z, coef, ls_width)
    return FlatnessZone(ls_width, min(mz_width, ls_width), _plane(coef, centre, scale), _plane(mz_coef, centre, scale))


def _plane(coef: np.ndarray, centre: np.ndarray, scale: float) -> tuple[float, float, float]:
    p, q, r = (float(c) for c in coef)
    return p / scale, q / scale, r - (p * centre[0] + q * centre[1]) / scale


def _minimum_zone(design: np.ndarray, z: np.ndarray, ls_coef: np.ndarray, ls_width: float) -> tuple[np.ndarray, float]:
    """Lower plane and width of the minimum zone: minimise w subject to plane <= z <= plane + w."""
    from scipy.optimize import linprog

    if ls_width == 0.0:
        return ls_coef.copy(), 0.0
    zs = (z - design @ ls_coef) / ls_width  # about the least-squares plane, in units of its width
    n = zs.size
    below = np.column_stack([design, np.zeros(n)])           # plane_i <= z_i
    above = np.column_stack([-design, -np.ones(n)])          # z_i - plane_i <= w
    result = linprog(
        c=[0.0, 0.0, 0.0, 1.0],
        A_ub=np.vstack([below, above]),
        b_ub=np.concatenate([zs, -zs]),
        bounds=[(None, None)] * 3 + [(0.0, None)],
        method="highs",
    )
    if result.status != 0:
        raise AxiscalError(f"the minimum zone was not found: {result.message}")
    coef = ls_coef + result.x[:3] * ls_width
    width = float(np.ptp(z - design @ coef))
    return coef, width


@dataclass(frozen=True)
class FlatnessSurface:
    """A surface joined from measured lines, with its closure errors and its flatness.

    Attributes
    ----------
    lines : tuple of FlatnessLine
        The lines as measured.
    line_heights_m : tuple of ndarray
        Each line's station heights as joined into the surface, metres (one array per line,
        its offset and tilt applied; Moody's centre lines after their shift).
    x_m, y_m, z_m : ndarray, shape (m,)
        The surface's points (stations where lines cross counted once), metres; ``z_m`` about the
        least-squares plane.
    closures : tuple of Closure
        The closure error at each crossing.
    zone : FlatnessZone
        The flatness about the least-squares plane and by the minimum zone.
    evaluation : str
        ``"least-squares"`` or ``"moody"``.
    warnings : tuple of str
        What the evaluation noticed (a foot spacing that does not fit the line's length ...).
    """

    lines: tuple[FlatnessLine, ...]
    line_heights_m: tuple[np.ndarray, ...]
    x_m: np.ndarray
    y_m: np.ndarray
    z_m: np.ndarray
    closures: tuple[Closure, ...]
    zone: FlatnessZone
    evaluation: str
    warnings: tuple[str, ...] = field(default=())

    def __post_init__(self) -> None:
        if not isinstance(self.lines, tuple) or not all(isinstance(line, FlatnessLine) for line in self.lines):
            raise AxiscalError("lines must be a tuple of FlatnessLine")
        check_instance("zone", self.zone, FlatnessZone)
        check_choice("evaluation", self.evaluation, EVALUATIONS)
        check_same_length(x_m=self.x_m, y_m=self.y_m, z_m=self.z_m)

    @property
    def closure_max_m(self) -> float:
        """The largest closure error in magnitude, metres (0 without crossings)."""
        return max((abs(c.value_m) for c in self.closures), default=0.0)


def _check_lines(lines: Sequence[FlatnessLine]) -> tuple[FlatnessLine, ...]:
    if isinstance(lines, (str, bytes)) or not isinstance(lines, Sequence):
        raise AxiscalError(f"lines must be a sequence of FlatnessLine, not {type(lines).__name__}")
    lines = tuple(lines)
    for line in lines:
        check_instance("lines", line, FlatnessLine, what="a sequence of FlatnessLine")
    if len(lines) < 2:
        raise AxiscalError(f"{len(lines)} line(s): a surface needs at least 2 lines that cross")
    names = [line.name for line in lines]
    for name in names:
        if names.count(name) > 1:
            raise AxiscalError(f"two lines are named {name!r}")
    return lines


def _check_crossings(lines: tuple[FlatnessLine, ...]) -> None:
    """Refuse two lines that cross (or where one ends on the other) at a place that is not a station of both.

    Lines are joined only at shared stations: a crossing that one line has no station at would be
    left out of the join (or, in Moody's method, filled in by interpolation) without a word.
    Parallel lines do not cross; the places are compared to 1e-6 of the surface's extent.
    """
    points = np.vstack([line.points_m for line in lines])
    extent = float(max(np.ptp(points[:, 0]), np.ptp(points[:, 1])))
    tolerance = 1e-6 * extent
    for i, a in enumerate(lines):
        u = (a.end_m - a.start_m) / a.length_m
        for b in lines[i + 1:]:
            v = (b.end_m - b.start_m) / b.length_m
            turn = u[0] * v[1] - u[1] * v[0]
            if abs(turn) < 1e-9:
                continue
            gap = b.start_m - a.start_m
            t = (gap[0] * v[1] - gap[1] * v[0]) / turn  # along a
            r = (gap[0] * u[1] - gap[1] * u[0]) / turn  # along b
            if not (-tolerance <= t <= a.length_m + tolerance and -tolerance <= r <= b.length_m + tolerance):
                continue
            for line, along in ((a, t), (b, r)):
                if np.min(np.abs(line.distance_m - along)) > tolerance:
                    x, y = (a.start_m + t * u) / 1e-3
                    other = b if line is a else a
                    raise AxiscalError(
                        f"lines {a.name!r} and {b.name!r} cross at x = {x:.6g} mm, y = {y:.6g} mm, where {line.name!r} has"
                        f" no station: lines are joined only at stations they share, so {line.name!r} needs one there"
                        f" (a Union Jack's centre lines, diagonals and edges an even number of steps; a grid's lines stepped"
                        f" to meet), or {other.name!r} must not cross it"
                    )


def _nodes(points: np.ndarray, extent: float) -> tuple[np.ndarray, np.ndarray]:
    """Merge points closer than 1e-6 of the extent: the node of every point and the nodes' places."""
    from scipy.spatial import cKDTree

    tolerance = 1e-6 * extent
    tree = cKDTree(points)
    node = np.arange(len(points))
    for i, j in sorted(tree.query_pairs(tolerance)):
        node[j] = node[i] if node[i] < node[j] else node[j]
    _, first, index = np.unique(node, return_index=True, return_inverse=True)
    return index, points[first]


def surface_from_lines(lines: Sequence[FlatnessLine]) -> FlatnessSurface:
    """Join measured lines into a surface by least squares and give its closure errors and flatness.

    Every station height ``h`` of line ``L`` at distance ``s`` is modelled as
    ``h = z_node + a_L + b_L s``: the height of the surface at the station (shared by every line
    through that place) plus the line's own offset and tilt. The sum of squared residuals is
    minimised; the surface is fixed up to a plane, which is taken out (heights about the
    least-squares plane). Union Jack or grid layouts alike: every line must cross the others at two
    stations at least, and a grid needs a diagonal through its crossings (rows and columns alone
    cannot tell a twist of the surface from the tilts of the lines). A line measured against
    gravity (``FlatnessLine.gravity``) keeps its tilt and needs one crossing: levels whose zero is
    known tie rows and columns together without a diagonal, and add redundancy to a Union Jack
    (as "Moody Revisited", 2026, proposes).

    Parameters
    ----------
    lines : sequence of FlatnessLine
        The lines, at least 2; stations closer than 1e-6 of the surface's extent are one place.

    Returns
    -------
    FlatnessSurface
        The evaluation ``"least-squares"``; closures are the spread of the lines' heights at each
        crossing.

    Raises
    ------
    AxiscalError
        Lines that are not FlatnessLine, two lines of one name, two lines that cross (or where
        one ends on the other) at a place that is not a station of both (naming them and the
        place), or lines that do not tie the surface together (a line crossing the others at
        fewer than 2 stations, naming it).

    Examples
    --------
    >>> edges = [FlatnessLine(n, p, q, [0, 0.5, 1], [0, 0, 0]) for n, p, q in (
    ...     ("S", [0, 0], [1, 0]), ("N", [0, 1], [1, 1]), ("W", [0, 0], [0, 1]), ("E", [1, 0], [1, 1]))]
    >>> r = 2 ** 0.5
    >>> diagonals = [FlatnessLine("SW-NE", [0, 0], [1, 1], [0, r / 2, r], [0, 1e-6, 0]),
    ...              FlatnessLine("NW-SE", [0, 1], [1, 0], [0, r / 2, r], [0, 1e-6, 0])]
    >>> round(surface_from_lines(edges + diagonals).zone.minimum_zone_m / 1e-6, 6)
    1.0
    """
    lines = _check_lines(lines)
    _check_crossings(lines)
    points = np.vstack([line.points_m for line in lines])
    owner = np.concatenate([np.full(line.distance_m.size, k) for k, line in enumerate(lines)])
    extent = float(max(np.ptp(points[:, 0]), np.ptp(points[:, 1])))
    node, places = _nodes(points, extent)
    shared = np.bincount(node, minlength=len(places))
    for k, line in enumerate(lines):
        crossings = np.count_nonzero(shared[node[owner == k]] > 1)
        needed = 1 if line.gravity else 2
        if crossings < needed:
            raise AxiscalError(
                f"line {line.name!r} crosses the other lines at {crossings} station(s): at least {needed} are needed to"
                " place it (stations of crossing lines must fall on the same places)"
            )
    n_nodes, n_lines = len(places), len(lines)
    distance = np.concatenate([line.distance_m for line in lines])
    height = np.concatenate([line.height_m for line in lines])
    counts = shared.astype(float)

    def less_node_mean(values: np.ndarray) -> np.ndarray:
        """Each row less the mean of its node's rows (columns of a 2-D array alike)."""
        flat = values.reshape(len(values), -1)
        sums = np.stack([np.bincount(node, weights=column, minlength=n_nodes) for column in flat.T], axis=1)
        return (flat - (sums / counts[:, None])[node]).reshape(values.shape)

    # the heights of the places follow from the lines' offsets and tilts (the mean of the lines'
    # values there), so the least squares reduces to the 2 per line (a Schur complement)
    # a line against gravity keeps its tilt: an offset only; a plane through the surface stays free
    # but for the slopes the gravity lines fix (along the directions they run in)
    free_tilt = np.array([not line.gravity for line in lines])
    tilt_column = n_lines + np.cumsum(free_tilt) - 1
    lines_design = np.zeros((len(points), n_lines + int(free_tilt.sum())))
    rows = np.arange(len(points))
    lines_design[rows, owner] = 1.0
    tilted = free_tilt[owner]
    lines_design[rows[tilted], tilt_column[owner[tilted]]] = distance[tilted] / extent
    fixed = [(line.end_m - line.start_m) / line.length_m for line in lines if line.gravity]
    gauge = 3 - (int(np.linalg.matrix_rank(np.array(fixed), tol=1e-9)) if fixed else 0)
    theta, _, rank, _ = np.linalg.lstsq(less_node_mean(lines_design), less_node_mean(height), rcond=None)
    if rank < lines_design.shape[1] - gauge:
        raise AxiscalError(
            f"the lines leave {lines_design.shape[1] - gauge - rank} shape(s) of the surface free: rows and columns"
            " alone do not see a twist (add a diagonal through their crossings, or read the rows or columns with a"
            " level against gravity), and every line must join one network of crossings"
        )
    estimate = height - lines_design @ theta  # each line's own value of the surface at its stations
    z_nodes = np.bincount(node, weights=estimate, minlength=n_nodes) / counts
    zone = flatness_zone(places[:, 0], places[:, 1], z_nodes)
    plane = zone.least_squares_plane
    about = z_nodes - (plane[0] * places[:, 0] + plane[1] * places[:, 1] + plane[2])
    order = np.argsort(node, kind="stable")
    starts = np.searchsorted(node[order], np.arange(n_nodes))
    closures = []
    for j in np.flatnonzero(shared > 1):
        members = order[starts[j]:starts[j] + shared[j]]
        closures.append(Closure(float(places[j, 0]), float(places[j, 1]),
                                tuple(lines[k].name for k in owner[members]), float(np.ptp(estimate[members]))))
    joined = tuple(
        about[node[owner == k]] for k in range(n_lines)
    )
    return FlatnessSurface(lines, joined, places[:, 0].copy(), places[:, 1].copy(), about, tuple(closures), zone,
                           "least-squares")
