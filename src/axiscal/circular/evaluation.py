"""Circular tests of two linear axes: the trace and the ISO 230-4:2005 figures G, H and F.

ISO 230-4:2005 clause 3 defines, for a circular path made by two linear axes moving together:
the circular deviation G (the minimum radial separation of two concentric circles enveloping the
actual path, centred on its least-squares circle), the circular hysteresis H (the maximum radial
difference between the clockwise and the counter-clockwise path) and the radial deviation F
(the deviation of the actual path from the nominal one, about the nominal centre as set up, here
before any centring). See docs/ballbar.md for how each figure is computed.

Angles run from the plane's first axis towards its second; ``ccw`` is the direction of increasing
angle. The API is in metres and radians; files and JSON carry mm, um, deg in their names.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_number, check_same_length
from axiscal.units import LENGTH_UNITS

__all__ = [
    "DIRECTIONS",
    "MAX_GAP_DEG",
    "MIN_POINTS",
    "MM_PER_MIN",
    "PLANES",
    "BallbarTrace",
    "CircularFigures",
    "coverage_gap",
    "check_direction",
    "plane_axes",
    "lsq_circle",
    "radial_deviations",
    "iso230_4",
]

#: the two directions of a circular test, in the order they are reported
DIRECTIONS = ("ccw", "cw")
#: planes a circular test can be made in: the first axis, then the second (the angle runs first -> second)
PLANES = ("XY", "YX", "XZ", "ZX", "YZ", "ZY")
#: fewest points per direction
MIN_POINTS = 36
#: largest nominal radius, metres (a ballbar reaches about 1.5 m; beyond it the diagnostics' search
#: for cyclic errors down to 1 mm pitch would grow without bound)
MAX_RADIUS_M = 10.0
#: the largest angular gap (deg) left in a direction's trace; a test covers the full circle
MAX_GAP_DEG = 10.0
#: metres per second in one millimetre per minute (feeds are given in mm/min)
MM_PER_MIN = LENGTH_UNITS["mm"] / 60.0


def plane_axes(plane: str) -> tuple[str, str]:
    """The first and the second axis of ``plane``.

    Parameters
    ----------
    plane : str
        Two distinct letters of X, Y, Z, e.g. ``"XY"`` (case-insensitive).

    Returns
    -------
    tuple of str
        ``("X", "Y")`` for ``"XY"``.

    Raises
    ------
    AxiscalError
        For anything that is not two distinct linear axes.

    Examples
    --------
    >>> plane_axes("zx")
    ('Z', 'X')
    """
    name = str(plane).upper()
    if name not in PLANES:
        raise AxiscalError(f"unknown plane '{plane}'; use one of {', '.join(PLANES)}")
    return name[0], name[1]


def coverage_gap(angles: np.ndarray) -> tuple[float, int]:
    """The largest gap (rad) between neighbouring angles of a trace, around the full circle.

    Parameters
    ----------
    angles : ndarray, shape (n,), radians
        Angles of one direction's points (any range; taken modulo 2 pi).

    Returns
    -------
    gap : float
        The widest empty arc, radians (2 pi for fewer than two points).
    index : int
        Index into ``angles`` of the point where that gap begins (going ccw), -1 for no point.

    Examples
    --------
    >>> round(coverage_gap(np.radians([0.0, 90.0, 180.0]))[0], 4)
    3.1416
    """
    a = np.mod(check_array("angles", angles, ndim=1, unit="radians"), 2 * math.pi)
    if a.size < 2:
        return 2 * math.pi, (0 if a.size else -1)
    order = np.argsort(a, kind="stable")
    s = a[order]
    gaps = np.diff(np.append(s, s[0] + 2 * math.pi))
    k = int(np.argmax(gaps))
    return float(gaps[k]), int(order[k])


@dataclass(frozen=True)
class BallbarTrace:
    """The radial deviations of a circular test, one or both directions.

    Attributes
    ----------
    angles : ndarray, shape (n,), radians
        Angle of each point, from the plane's first axis towards its second.
    directions : tuple of str, length n
        ``"ccw"`` (angle increasing) or ``"cw"`` for each point.
    deviations : ndarray, shape (n,), metres
        Measured length minus the nominal radius (the ballbar's reading).
    radius : float, metres
        Nominal radius of the circle.
    plane : str
        The plane, first axis then second (see :data:`PLANES`).
    source : str
        Where the data came from (a file name), for messages.

    Raises
    ------
    AxiscalError
        On shapes that differ, a radius that is not positive, an unknown plane or direction, a
        direction with fewer than :data:`MIN_POINTS` points or a gap above :data:`MAX_GAP_DEG`.
    """

    angles: np.ndarray
    directions: tuple[str, ...]
    deviations: np.ndarray
    radius: float
    plane: str = "XY"
    source: str = "<data>"
    _index: dict[str, np.ndarray] = field(default_factory=dict, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.source, str):
            raise AxiscalError(f"source must be a name (str), not {self.source!r}")
        angles = check_array("angles", self.angles, finite=False).ravel()
        deviations = check_array("deviations", self.deviations, finite=False).ravel()
        if isinstance(self.directions, (str, bytes)) or not hasattr(self.directions, "__iter__"):
            raise AxiscalError(f"{self.source}: directions must be one 'ccw' or 'cw' per point, not {self.directions!r}"[:200])
        directions = tuple(str(d).lower() for d in self.directions)
        if not (angles.size == deviations.size == len(directions)):
            raise AxiscalError(
                f"{self.source}: angles, directions and deviations differ in length"
                f" ({angles.size}, {len(directions)}, {deviations.size})"
            )
        if not (np.all(np.isfinite(angles)) and np.all(np.isfinite(deviations))):
            raise AxiscalError(f"{self.source}: angles and deviations must be finite numbers")
        if not (isinstance(self.radius, (int, float, np.floating, np.integer)) and not isinstance(self.radius, bool)
                and math.isfinite(self.radius) and 0 < self.radius <= MAX_RADIUS_M):
            raise AxiscalError(f"{self.source}: the nominal radius must be a positive length of at most {MAX_RADIUS_M:g} m"
                               f" (a ballbar reaches about 1.5 m), got {self.radius!r} m")
        plane = "".join(plane_axes(self.plane))
        unknown = sorted(set(directions) - set(DIRECTIONS))
        if unknown:
            raise AxiscalError(f"{self.source}: unknown direction '{unknown[0]}'; use ccw or cw")
        object.__setattr__(self, "angles", angles)
        object.__setattr__(self, "deviations", deviations)
        object.__setattr__(self, "directions", directions)
        object.__setattr__(self, "plane", plane)
        names = np.array(directions, dtype=object)
        for d in DIRECTIONS:
            rows = np.flatnonzero(names == d)
            if rows.size:
                self._index[d] = rows
        if not self._index:
            raise AxiscalError(f"{self.source}: no points")
        for d, rows in self._index.items():
            problem = check_direction(angles[rows], d)
            if problem is not None:
                raise AxiscalError(f"{self.source}: {problem[0]}")

    @property
    def axes(self) -> tuple[str, str]:
        """The plane's first and second axis letters."""
        return plane_axes(self.plane)

    @property
    def present(self) -> tuple[str, ...]:
        """The directions measured, ccw first."""
        return tuple(d for d in DIRECTIONS if d in self._index)

    def rows(self, direction: str) -> np.ndarray:
        """Indices of the points of ``direction`` (in file order); empty if it was not measured."""
        return self._index.get(direction, np.zeros(0, dtype=int))

    def path(self, direction: str) -> tuple[np.ndarray, np.ndarray]:
        """Angles (rad, in [0, 2 pi)) and deviations (m) of ``direction``, sorted by angle."""
        rows = self.rows(direction)
        a = np.mod(self.angles[rows], 2 * math.pi)
        order = np.argsort(a, kind="stable")
        return a[order], self.deviations[rows][order]

    @property
    def signs(self) -> np.ndarray:
        """+1 for each ccw point, -1 for each cw point."""
        return np.where(np.array(self.directions, dtype=object) == "ccw", 1.0, -1.0)


def check_direction(angles: np.ndarray, direction: str) -> tuple[str, int] | None:
    """The problem with one direction's points, if any: too few, or a gap in the circle.

    Parameters
    ----------
    angles : ndarray, shape (n,), radians
        The angles of the points of ``direction``.
    direction : str
        ``"ccw"`` or ``"cw"``, for the message.

    Returns
    -------
    tuple of (str, int) or None
        The message and the index (into ``angles``) of the point it concerns; None when the
        direction has at least :data:`MIN_POINTS` points and no gap above :data:`MAX_GAP_DEG`.
    """
    angles = check_array("angles", angles, ndim=1, unit="radians")
    if not isinstance(direction, str) or direction not in DIRECTIONS:
        raise AxiscalError(f"unknown direction {direction!r}; use ccw or cw")
    if angles.size < MIN_POINTS:
        return f"{angles.size} points in direction {direction}; at least {MIN_POINTS} needed", max(angles.size - 1, 0)
    gap, k = coverage_gap(angles)
    if math.degrees(gap) > MAX_GAP_DEG * (1 + 1e-9):
        start = math.degrees(float(np.mod(angles[k], 2 * math.pi)))
        return (
            f"direction {direction} leaves {math.degrees(gap):.1f} deg unmeasured after {start:.2f} deg;"
            f" a circular test covers the full circle (gaps up to {MAX_GAP_DEG:g} deg)",
            k,
        )
    return None


def lsq_circle(angles: np.ndarray, deviations: np.ndarray, radius: float) -> tuple[float, float, float]:
    """Least-squares circle of a ballbar trace: its centre and its radius minus the nominal one.

    Fits ``deviation = r0 + cx cos(angle) + cy sin(angle)``, the least-squares circle of a path
    whose deviations are small against the radius (the neglected terms are of order
    centre^2 / radius).

    Parameters
    ----------
    angles : ndarray, shape (n,), radians
    deviations : ndarray, shape (n,), metres
        Measured length minus ``radius``.
    radius : float, metres
        Nominal radius (kept for the signature's symmetry with :func:`radial_deviations`).

    Returns
    -------
    cx, cy : float, metres
        Centre of the path relative to the nominal centre, along the first and second axis.
    r0 : float, metres
        Radius of the least-squares circle minus the nominal radius.

    Raises
    ------
    AxiscalError
        With fewer than three points.

    Examples
    --------
    >>> a = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    >>> [round(v * 1e6, 3) + 0.0 for v in lsq_circle(a, 5e-6 * np.cos(a) + 1e-6, 0.1)]
    [5.0, 0.0, 1.0]
    """
    a, deviations = _series(angles, deviations)
    radius = check_number("radius", radius, positive=True, unit="metres")
    if a.size < 3:
        raise AxiscalError(f"a least-squares circle needs at least 3 points, got {a.size}")
    basis = np.column_stack([np.cos(a), np.sin(a), np.ones_like(a)])
    (cx, cy, r0), *_ = np.linalg.lstsq(basis, deviations, rcond=None)
    return float(cx), float(cy), float(r0)


def _series(angles: np.ndarray, deviations: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Angles (rad) and deviations (m) of a trace as finite 1-D arrays of one length."""
    a = check_array("angles", angles, ndim=1, unit="radians")
    d = check_array("deviations", deviations, ndim=1, unit="metres")
    check_same_length(angles=a, deviations=d)
    return a, d


def radial_deviations(angles: np.ndarray, deviations: np.ndarray, radius: float, centre: tuple[float, float]) -> np.ndarray:
    """Radial deviation of the path about ``centre`` instead of the ballbar's table ball (metres).

    The ballbar reads the distance L from the table ball; the tool is taken at the commanded
    angle a from the path's centre, which sits at ``centre`` from the ball. Then
    ``L^2 = r^2 + 2 r (c . u) + |c|^2`` with u = (cos a, sin a), so the tool's distance from the
    centre is exactly ``r = sqrt(L^2 - |c x u|^2) - c . u``: a circle offset from the ball reads
    as a circle.

    Parameters
    ----------
    angles : ndarray, shape (n,), radians
    deviations : ndarray, shape (n,), metres
        Measured length minus ``radius``.
    radius : float, metres
    centre : (float, float), metres
        Centre of the path relative to the table ball (first, second axis).

    Returns
    -------
    ndarray, shape (n,), metres
        ``r - radius`` for each point.

    Examples
    --------
    >>> a = np.radians([0.0, 90.0])
    >>> L = np.hypot(0.1 * np.cos(a) + 3e-5, 0.1 * np.sin(a))  # a 100 mm circle 30 um along +first
    >>> np.round(radial_deviations(a, L - 0.1, 0.1, (3e-5, 0.0)) * 1e9, 6)
    array([0., 0.])
    """
    a, deviations = _series(angles, deviations)
    radius = check_number("radius", radius, positive=True, unit="metres")
    centre = check_array("centre", centre, ndim=1, unit="metres")
    if centre.shape != (2,):
        raise AxiscalError(f"centre must be 2 numbers of metres (along the plane's first and second axis), not shape {centre.shape}")
    length = radius + deviations
    along = centre[0] * np.cos(a) + centre[1] * np.sin(a)
    across = centre[0] * np.sin(a) - centre[1] * np.cos(a)
    square = length * length - across * across
    if np.any(length <= 0.0) or np.any(square < 0.0):
        raise AxiscalError("centre lies farther from the table ball than the bar reaches: no radial deviation about it")
    return np.sqrt(square) - along - radius


@dataclass(frozen=True)
class CircularFigures:
    """The ISO 230-4 figures of a circular test (metres).

    Attributes
    ----------
    G : dict of str to float
        Circular deviation per direction measured (``"ccw"``, ``"cw"``), each about its own
        least-squares centre.
    H : float
        Circular hysteresis, NaN when only one direction was measured.
    F_max, F_min : float
        Largest and smallest radial deviation from the nominal radius about the nominal centre
        (before centring), over every direction measured.
    centre : (float, float)
        Least-squares centre of all the points measured, relative to the nominal centre, along
        the plane's first and second axis.
    radius_offset : float
        Radius of that least-squares circle minus the nominal radius.
    centres : dict of str to (float, float)
        Each direction's own least-squares centre.
    """

    G: dict[str, float]
    H: float
    F_max: float
    F_min: float
    centre: tuple[float, float]
    radius_offset: float
    centres: dict[str, tuple[float, float]]


def iso230_4(trace: BallbarTrace) -> CircularFigures:
    """The ISO 230-4:2005 figures G (per direction), H, F_max, F_min and the least-squares centre.

    G of a direction is the spread (max - min) of the distances of its points from its own
    least-squares centre. H is the largest difference, at equal angle, between the ccw and the cw
    path, both measured from the common least-squares centre of all points (the cw path is
    interpolated linearly at the ccw angles). F_max and F_min are the extreme readings as taken,
    about the nominal centre.

    Parameters
    ----------
    trace : BallbarTrace

    Returns
    -------
    CircularFigures

    Examples
    --------
    >>> a = np.radians(np.arange(0.0, 360.0, 1.0))
    >>> t = BallbarTrace(a, ("ccw",) * a.size, 3e-6 * np.cos(a), radius=0.1)
    >>> f = iso230_4(t)
    >>> round(f.G["ccw"] * 1e6, 3), round(f.F_max * 1e6, 3), round(f.centre[0] * 1e6, 3)
    (0.0, 3.0, 3.0)
    """
    check_instance("trace", trace, BallbarTrace, what="a BallbarTrace")
    cx, cy, r0 = lsq_circle(trace.angles, trace.deviations, trace.radius)
    G: dict[str, float] = {}
    centres: dict[str, tuple[float, float]] = {}
    around: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    for d in trace.present:
        a, dev = trace.path(d)
        dx, dy, _ = lsq_circle(a, dev, trace.radius)
        own = radial_deviations(a, dev, trace.radius, (dx, dy))
        G[d] = float(own.max() - own.min())
        centres[d] = (dx, dy)
        around[d] = (a, radial_deviations(a, dev, trace.radius, (cx, cy)))
    H = math.nan
    if len(around) == 2:
        a_ccw, r_ccw = around["ccw"]
        a_cw, r_cw = around["cw"]
        H = float(np.max(np.abs(r_ccw - np.interp(a_ccw, a_cw, r_cw, period=2 * math.pi))))
    return CircularFigures(
        G=G,
        H=H,
        F_max=float(trace.deviations.max()),
        F_min=float(trace.deviations.min()),
        centre=(cx, cy),
        radius_offset=r0,
        centres=centres,
    )

