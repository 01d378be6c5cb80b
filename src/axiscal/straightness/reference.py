"""Straightness of a measured profile about a reference line: least squares, end points, minimum zone.

ISO 230-1 (straightness of a line: the width, across the motion, of the zone that holds the
deviations about a reference straight line, fitted by least squares or through the end points)
and the minimum-zone line of ISO 12780-1 (MZLI). Three reference lines are offered:

* ``"least-squares"``: the line minimising the sum of squared deviations;
* ``"end-points"``: the line through the points at the smallest and the largest position;
* ``"minimum-zone"``: the two parallel lines closest together that enclose every point (the
  Chebyshev line). It is computed exactly: the optimal slope is the slope of an edge of the
  profile's convex hull, and every edge slope is evaluated against the hull's opposite chain.

The width is measured along the deviation axis (the usual convention for straightness, where the
slopes are of order 1e-4 and the perpendicular width differs by a factor 1/sqrt(1 + slope^2)).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_number, check_same_length

__all__ = ["REFERENCES", "ReferenceLine", "reference_line"]

REFERENCES = ("least-squares", "end-points", "minimum-zone")

#: the largest position or deviation taken, metres: beyond it a value has no physical meaning
#: (the tabular reader's limit, 1e12 mm)
_LIMIT_M = 1e9


@dataclass(frozen=True)
class ReferenceLine:
    """A reference straight line ``deviation = slope * position + intercept`` and the zone width.

    Attributes
    ----------
    slope : float
        Dimensionless (m/m): deviation per unit of position.
    intercept_m : float
        Deviation of the line at position 0, metres.
    straightness_m : float
        Width of the zone of the residuals about the line, metres: max residual - min residual
        (for the minimum zone this is the minimum zone width, and the line is the zone's mid-line).
    reference : str
        ``"least-squares"``, ``"end-points"`` or ``"minimum-zone"``.
    """

    slope: float
    intercept_m: float
    straightness_m: float
    reference: str

    def __post_init__(self) -> None:
        for name in ("slope", "intercept_m", "straightness_m"):
            object.__setattr__(self, name, check_number(name, getattr(self, name), unit="" if name == "slope" else "metres"))
        check_choice("reference line", self.reference, REFERENCES)

    def residuals(self, position_m: np.ndarray, deviation_m: np.ndarray) -> np.ndarray:
        """Deviations about the line, metres.

        Parameters
        ----------
        position_m, deviation_m : array_like, shape (n,)
            Positions along the axis and deviations across it, metres.

        Returns
        -------
        ndarray, shape (n,)
            ``deviation_m - (slope * position_m + intercept_m)``, metres.
        """
        position = check_array("position_m", position_m, ndim=1)
        deviation = check_array("deviation_m", deviation_m, ndim=1, finite=False)  # NaN: not resolved, stays NaN
        check_same_length(position_m=position, deviation_m=deviation)
        return deviation - (self.slope * position + self.intercept_m)


def reference_line(position_m: np.ndarray, deviation_m: np.ndarray, *, reference: str = "least-squares") -> ReferenceLine:
    """Fit a reference straight line to a profile and return it with the straightness.

    Parameters
    ----------
    position_m : array_like, shape (n,)
        Positions along the axis, metres (any order; repeated positions are allowed where the
        reference line stays defined).
    deviation_m : array_like, shape (n,)
        Deviations across the axis at those positions, metres.
    reference : {"least-squares", "end-points", "minimum-zone"}, keyword-only
        Which reference line (default ``"least-squares"``).

    Returns
    -------
    ReferenceLine
        The line (slope, intercept in metres) and the straightness, metres.

    Raises
    ------
    AxiscalError
        Fewer than 2 points, arrays of different shapes, non-finite values, all positions equal,
        an unknown reference, or (end points only) a repeated smallest or largest position.

    Examples
    --------
    >>> from axiscal.units import MM, UM
    >>> line = reference_line([0 * MM, 50 * MM, 100 * MM], [0 * UM, 1 * UM, 0 * UM], reference="end-points")
    >>> round(line.straightness_m / UM, 6), line.slope
    (1.0, 0.0)
    """
    if not isinstance(reference, str) or reference not in REFERENCES:
        raise AxiscalError(f"unknown reference line {reference!r}; use one of {', '.join(REFERENCES)}")
    position = check_array("position_m", position_m, finite=False)
    deviation = check_array("deviation_m", deviation_m, finite=False)
    if position.ndim != 1 or position.shape != deviation.shape:
        raise AxiscalError(
            f"positions and deviations (position_m, deviation_m) must be 1-D arrays of the same length "
            f"(shapes {position.shape} and {deviation.shape})"
        )
    if position.size < 2:
        raise AxiscalError(f"{position.size} point(s): a reference line needs at least 2")
    if not (np.all(np.isfinite(position)) and np.all(np.isfinite(deviation))):
        raise AxiscalError("positions and deviations (position_m, deviation_m) must be finite numbers")
    check_array("position_m", position, limit=_LIMIT_M)
    check_array("deviation_m", deviation, limit=_LIMIT_M)
    centre = 0.5 * (position.min() + position.max())
    half_span = 0.5 * (position.max() - position.min())
    if not half_span > 0.0:
        raise AxiscalError("all positions are equal: a reference line needs at least 2 distinct positions")
    u = (position - centre) / half_span

    if reference == "least-squares":
        gain, offset = _least_squares(u, deviation)
    elif reference == "end-points":
        gain, offset = _end_points(u, deviation)
    else:
        ls_gain, ls_offset = _least_squares(u, deviation)
        k, c = _minimum_zone(u, deviation - (ls_gain * u + ls_offset))
        gain, offset = ls_gain + k, ls_offset + c
    residual = deviation - (gain * u + offset)
    width = float(residual.max() - residual.min())
    if reference == "minimum-zone":
        offset += 0.5 * (residual.max() + residual.min())
    with np.errstate(over="ignore"):
        slope = gain / half_span
        intercept = offset - slope * centre
    if not (np.isfinite(slope) and np.isfinite(intercept)):
        raise AxiscalError(f"position_m spans {2 * half_span:g} m: too little for a finite slope of the reference line")
    return ReferenceLine(
        slope=float(slope), intercept_m=float(intercept), straightness_m=width, reference=reference
    )


def _least_squares(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    xm, ym = x.mean(), y.mean()
    dx = x - xm
    slope = float(np.dot(dx, y - ym) / np.dot(dx, dx))
    return slope, float(ym - slope * xm)


def _end_points(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    first = np.flatnonzero(x == x.min())
    last = np.flatnonzero(x == x.max())
    if first.size > 1 or last.size > 1:
        raise AxiscalError("the smallest or largest position is repeated: the end-point line is not defined")
    i, j = first[0], last[0]
    slope = float((y[j] - y[i]) / (x[j] - x[i]))
    return slope, float(y[i] - slope * x[i])


def _upper_chain(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Upper convex hull (Andrew's monotone chain) of points with one highest point per position.

    Points lower than some point on each side are dropped first (vectorised); the chain then
    loops over the few left, typically O(log n) for measured profiles.
    """
    xs, ys = x, y
    if np.any(np.diff(x) < 0):
        order = np.argsort(x, kind="stable")
        xs, ys = x[order], y[order]
    starts = np.r_[0, np.flatnonzero(xs[1:] != xs[:-1]) + 1]
    xs, ys = xs[starts], np.maximum.reduceat(ys, starts)
    # a point with a higher point on each side lies below their chord: never on the upper hull
    higher_left = np.r_[-np.inf, np.maximum.accumulate(ys)[:-1]]
    higher_right = np.r_[np.maximum.accumulate(ys[::-1])[::-1][1:], -np.inf]
    keep = ys >= np.minimum(higher_left, higher_right)
    xs, ys = xs[keep], ys[keep]
    hx: list[float] = []
    hy: list[float] = []
    for px, py in zip(xs.tolist(), ys.tolist()):
        while len(hx) >= 2 and (hx[-1] - hx[-2]) * (py - hy[-2]) - (hy[-1] - hy[-2]) * (px - hx[-2]) >= 0.0:
            hx.pop()
            hy.pop()
        hx.append(px)
        hy.append(py)
    return np.array(hx), np.array(hy)


def _minimum_zone(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Slope and offset of the lower line of the minimum zone of points (x, y) (vertical width).

    The width ``f(k) = max(y - k x) - min(y - k x)`` is convex and piecewise linear in k with its
    breakpoints at the slopes of the hull edges, so its minimum is at one of them. For a slope k
    the maximum lies at the upper-hull vertex where the (decreasing) edge slopes cross k, the
    minimum at the lower-hull vertex where the (increasing) edge slopes cross k.
    """
    ux, uy = _upper_chain(x, y)
    lx, ly = _upper_chain(x, -y)
    ly = -ly
    upper_slopes = np.diff(uy) / np.diff(ux)
    lower_slopes = np.diff(ly) / np.diff(lx)
    candidates = np.concatenate([upper_slopes, lower_slopes])
    top = np.searchsorted(-upper_slopes, -candidates, side="left")
    bottom = np.searchsorted(lower_slopes, candidates, side="left")
    width = (uy[top] - candidates * ux[top]) - (ly[bottom] - candidates * lx[bottom])
    best = int(np.argmin(width))
    k = float(candidates[best])
    return k, float(ly[bottom[best]] - k * lx[bottom[best]])
