"""A figure's drift over the campaigns: the fit, the date it leaves its tolerance, the next calibration.

The drift is a straight line ``y = a + b (t - t0)`` fitted by weighted least squares, each campaign
weighted by ``1 / u^2`` with ``u = U / 2`` its standard uncertainty (unweighted when a campaign
states no U); the covariance of ``a, b`` is ``(X^T W X)^-1``, enlarged by the Birge ratio
``chi2 / (n - 2)`` when the scatter exceeds the stated uncertainties (or, unweighted, estimated
from the residuals). The robust option reweights by Huber's function (c = 1.345, scale by the
median absolute deviation) until the weights settle (Huber, *Robust Statistics*, 1981).

The date the line crosses the tolerance ``L`` is ``t0 + (L - a) / b``; its interval is Fieller's
(1954): the times where ``|a + b (t - t0) - L| <= k u_fit(t)``, bounded only when the slope is
significant (``|b| > k u(b)``). A crossing further than :data:`CROSSING_HORIZON_YEARS` from the last
campaign is not given as a date (it says "not within 100 years"), nor is an end of its interval
that far (unbounded). The next calibration follows ILAC-G24 / OIML D 10 (2007):

- **fixed risk** (from the drift fit): the first date where the one-sided probability of being out
  of tolerance reaches ``risk``: ``a + b (t - t0) + z u_fit(t) = L`` with ``z = Phi^-1(1 - risk)``;
- **staircase** (method 1, automatic adjustment): the interval grows by ``extend`` after a campaign
  that found the figure in tolerance and shrinks by ``shrink`` after one that did not, from
  ``initial_days``; the next date is the last campaign's plus the interval.

The recommended date is the earlier of the two.

A figure that cannot be negative (ISO 230-2's A, E, R, B, M; a straightness, a flatness: see
:func:`one_sided_figure`) has a one-sided limit: only ``+L`` is held against it, so a falling line of
such a figure never crosses (it does not predict the crossing of ``-L``). A signed figure (a
squareness) is held against ``+L`` and ``-L``.
"""

from __future__ import annotations

import datetime as _dt
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_instance, check_number

__all__ = ["TREND_METHODS", "CROSSING_HORIZON_YEARS", "ONE_SIDED_FIGURES", "DriftFit", "Trend", "fit_drift", "crossing", "staircase", "trend_of",
           "one_sided_figure"]

#: figure names (the last part of KIND.AXIS.FIGURE, unit suffix removed) that are magnitudes, >= 0
ONE_SIDED_FIGURES = frozenset({"A", "E", "R", "B", "M", "A_up", "A_down", "E_up", "E_down", "R_up", "R_down",
                               "B_mean", "M_up", "M_down", "straightness", "flatness"})


def one_sided_figure(figure: str) -> bool:
    """Whether a figure cannot be negative, so that its limit is one-sided (``+L`` only).

    Parameters
    ----------
    figure : str
        ``KIND.AXIS.FIGURE`` (``positioning.X.E``) or the figure's name alone.

    Returns
    -------
    bool
        True for ISO 230-2's A, E, R, B, M (each way too) and for straightness and flatness
        figures; False for a signed figure (a squareness, a slope).

    Examples
    --------
    >>> one_sided_figure("positioning.X.E"), one_sided_figure("squareness.XZ.squareness_arcsec")
    (True, False)
    """
    check_instance("figure", figure, str)
    name = figure.rsplit(".", 1)[-1]
    stem, _, unit = name.rpartition("_")
    if stem and unit in ("um", "nm", "mm", "m", "arcsec", "urad", "deg", "rad"):
        name = stem
    return name in ONE_SIDED_FIGURES or name.endswith(("straightness", "flatness"))

#: the ways a drift line is fitted
TREND_METHODS = ("wls", "robust")
#: a crossing date further than this from the last campaign, years, is not stated as a date
CROSSING_HORIZON_YEARS = 100.0
_YEAR_DAYS = 365.25
_HUBER_C = 1.345
# bounds that keep the normal equations far from overflow: dates within 100 000 years, figures and
# uncertainties within 1e15 of their unit, an uncertainty not below 1e-100
_MAX_YEARS = 1e5
_MAX_VALUE = 1e15
_MIN_U = 1e-100
# the longest interval a method may recommend, days (100 years)
_MAX_INTERVAL_DAYS = 36525.0


@dataclass(frozen=True)
class DriftFit:
    """A straight line through a figure's values over time, with its covariance.

    Attributes
    ----------
    t0 : float
        Reference time, years since 1970-01-01 (the weighted mean time: ``a`` and ``b`` are then
        nearly uncorrelated).
    a : float
        The line at ``t0``, in the figure's unit.
    b : float
        The slope, unit per year.
    cov : ndarray, shape (2, 2)
        Covariance of ``(a, b)``.
    chi2 : float
        Weighted sum of squared residuals.
    dof : int
        ``n - 2``.
    method : str
        ``"wls"`` or ``"robust"``.
    """

    t0: float
    a: float
    b: float
    cov: np.ndarray
    chi2: float
    dof: int
    method: str

    @property
    def u_b(self) -> float:
        """Standard uncertainty of the slope, unit per year."""
        return math.sqrt(self.cov[1, 1])

    def at(self, t: np.ndarray | float) -> np.ndarray:
        """The line at times ``t`` (years since 1970).

        Parameters
        ----------
        t : float or ndarray

        Returns
        -------
        ndarray
        """
        return self.a + self.b * (np.asarray(t, dtype=float) - self.t0)

    def u_at(self, t: np.ndarray | float) -> np.ndarray:
        """Standard uncertainty of the line at times ``t``.

        Parameters
        ----------
        t : float or ndarray

        Returns
        -------
        ndarray
        """
        d = np.asarray(t, dtype=float) - self.t0
        return np.sqrt(np.maximum(self.cov[0, 0] + 2 * d * self.cov[0, 1] + d * d * self.cov[1, 1], 0.0))


def years(date: _dt.date) -> float:
    """``date`` in years since 1970-01-01."""
    return (date - _dt.date(1970, 1, 1)).days / _YEAR_DAYS


def date_of(t: float) -> _dt.date:
    """The date at ``t`` years since 1970-01-01 (to the day).

    Raises
    ------
    AxiscalError
        For a ``t`` whose date is not between 0001-01-01 and 9999-12-31.
    """
    days = t * _YEAR_DAYS + 0.5 if math.isfinite(t) else math.inf
    first, last = _dt.date.min - _dt.date(1970, 1, 1), _dt.date.max - _dt.date(1970, 1, 1)
    if not first.days <= days < last.days + 1:
        raise AxiscalError(f"{t:.6g} years after 1970 is not a date between {_dt.date.min} and {_dt.date.max}")
    return _dt.date(1970, 1, 1) + _dt.timedelta(days=int(math.floor(days)))


def _within(t: float | None, last: float) -> _dt.date | None:
    """The date at ``t`` when it lies within the horizon of the last campaign ``last``, else None."""
    if t is None or not abs(t - last) <= CROSSING_HORIZON_YEARS:
        return None
    return date_of(t)


def _wls(t: np.ndarray, y: np.ndarray, w: np.ndarray) -> tuple[float, float, float, np.ndarray, float]:
    t0 = float(np.sum(w * t) / np.sum(w))
    X = np.column_stack([np.ones_like(t), t - t0])
    normal = X.T @ (w[:, None] * X)
    cov = np.linalg.inv(normal)
    a, b = cov @ (X.T @ (w * y))
    chi2 = float(np.sum(w * (y - a - b * (t - t0)) ** 2))
    return t0, float(a), float(b), cov, chi2


def fit_drift(
    t_years: np.ndarray,
    values: np.ndarray,
    U: np.ndarray | None = None,
    *,
    method: str = "wls",
) -> DriftFit:
    """Fit the drift line of a figure.

    Parameters
    ----------
    t_years : ndarray, shape (n,)
        Campaign times, years (any origin; at least two distinct).
    values : ndarray, shape (n,)
        The figure, in its unit.
    U : ndarray, shape (n,), optional
        Expanded uncertainties (k = 2) in the same unit, all positive; None fits unweighted.
    method : {"wls", "robust"}, keyword-only
        Weighted least squares, or Huber-reweighted.

    Returns
    -------
    DriftFit

    Raises
    ------
    AxiscalError
        For fewer than three points, arrays of other lengths, non-finite values, a U that is not
        positive, all times equal, or an unknown method.

    Examples
    --------
    >>> fit = fit_drift(np.array([0.0, 1.0, 2.0]), np.array([1.0, 3.0, 5.0]), np.array([0.2, 0.2, 0.2]))
    >>> round(fit.b, 6), round(fit.u_b, 4)
    (2.0, 0.0707)
    """
    method = check_choice("method", method, TREND_METHODS)
    t = np.asarray(t_years, dtype=float)
    y = np.asarray(values, dtype=float)
    if t.ndim != 1 or y.shape != t.shape:
        raise AxiscalError(f"t_years and values must be 1-D arrays of one length, not {t.shape} and {y.shape}")
    if len(t) < 3:
        raise AxiscalError(f"a drift fit needs three campaigns at least, not {len(t)}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
        raise AxiscalError("t_years and values must be finite numbers")
    if np.max(np.abs(t)) > _MAX_YEARS or np.max(np.abs(y)) > _MAX_VALUE:
        raise AxiscalError(f"t_years must lie within ±{_MAX_YEARS:g} years and values within ±{_MAX_VALUE:g}")
    if np.ptp(t) < 1e-6 * max(1.0, float(np.max(np.abs(t)))):
        raise AxiscalError("a drift fit needs campaigns on two dates at least")
    stated = U is not None
    if stated:
        U = np.asarray(U, dtype=float)
        if U.shape != t.shape or not np.all(np.isfinite(U)) or np.any(U < _MIN_U) or np.any(U > _MAX_VALUE):
            raise AxiscalError(f"U must hold one expanded uncertainty per campaign, between {_MIN_U:g} and {_MAX_VALUE:g}")
        base = 1.0 / (U / 2.0) ** 2
    else:
        base = np.ones_like(t)
    w = base
    t0, a, b, cov, chi2 = _wls(t, y, w)
    if method == "robust":
        for _ in range(100):
            z = (y - a - b * (t - t0)) * np.sqrt(base)
            scale = 1.4826 * float(np.median(np.abs(z - np.median(z))))
            scale = max(scale, 1.0) if stated else max(scale, 1e-12 * (1.0 + float(np.max(np.abs(y)))))
            h = np.minimum(1.0, _HUBER_C / np.maximum(np.abs(z) / scale, 1e-300))
            new = base * h
            if np.allclose(new, w, rtol=1e-10, atol=0.0):
                break
            w = new
            t0, a, b, cov, chi2 = _wls(t, y, w)
    dof = len(t) - 2
    if not (np.isfinite(a) and np.isfinite(b) and np.all(np.isfinite(cov)) and np.isfinite(chi2)):
        raise AxiscalError("the drift line is not defined by these campaigns (their times or weights are too unequal)")
    if stated:
        cov = cov * max(1.0, chi2 / dof)
    else:
        cov = cov * (chi2 / dof)
    return DriftFit(t0, a, b, cov, chi2, dof, method)


def _band_roots(fit: DriftFit, limit: float, k: float) -> tuple[float, list[float]]:
    """The leading coefficient and the real times where ``(a + b d - L)^2 = k^2 u_fit(d)^2``, d = t - t0."""
    c = fit.a - limit
    A = fit.b ** 2 - k * k * fit.cov[1, 1]
    B = 2.0 * (c * fit.b - k * k * fit.cov[0, 1])
    C = c * c - k * k * fit.cov[0, 0]
    if A == 0:
        return A, [] if B == 0 else [fit.t0 - C / B]
    disc = B * B - 4 * A * C
    if disc < 0:
        return A, []
    r = math.sqrt(disc)
    return A, sorted([fit.t0 + (-B - r) / (2 * A), fit.t0 + (-B + r) / (2 * A)])


def _roots(fit: DriftFit, limit: float, k: float) -> tuple[float | None, float | None]:
    """Fieller's interval on the crossing time; None, None where it is unbounded (slope not significant)."""
    A, roots = _band_roots(fit, limit, k)
    if A <= 0 or len(roots) != 2:
        return None, None
    return roots[0], roots[1]


def crossing(fit: DriftFit, tolerance: float, *, k: float = 2.0,
             one_sided: bool = False) -> tuple[float | None, float | None, float | None]:
    """When the drift line reaches the tolerance, with Fieller's interval on that time.

    Parameters
    ----------
    fit : DriftFit
    tolerance : float
        The limit of the figure's magnitude, positive, in its unit: the line is held against
        ``+tolerance`` when it rises and ``-tolerance`` when it falls.
    k : float, keyword-only
        Coverage factor of the interval (2: about 95 %).
    one_sided : bool, keyword-only
        The figure cannot be negative (:func:`one_sided_figure`): only ``+tolerance`` is a limit, and a
        falling line never crosses.

    Returns
    -------
    (float or None, float or None, float or None)
        The crossing time and the interval's ends, years since 1970; None where the line never
        reaches the limit (no slope, or falling with a one-sided limit) or the interval is
        unbounded (slope not significant at k).

    Raises
    ------
    AxiscalError
        For a tolerance or k that is not a positive number.
    """
    tolerance = check_number("tolerance", tolerance, positive=True)
    k = check_number("k", k, positive=True)
    check_instance("one_sided", one_sided, bool)
    if fit.b == 0 or (one_sided and fit.b < 0):
        return None, None, None
    limit = tolerance if fit.b > 0 else -tolerance
    t_cross = fit.t0 + (limit - fit.a) / fit.b
    low, high = _roots(fit, limit, k)
    return t_cross, low, high


def staircase(
    passed: Sequence[bool],
    *,
    initial_days: float = 365.0,
    extend: float = 1.25,
    shrink: float = 0.5,
    min_days: float = 30.0,
    max_days: float = 1095.0,
) -> float:
    """The next calibration interval by the staircase (ILAC-G24 method 1, automatic adjustment).

    Parameters
    ----------
    passed : sequence of bool
        Whether each campaign, oldest first, found the figure within tolerance.
    initial_days : float, keyword-only
        The interval before the first campaign.
    extend, shrink : float, keyword-only
        Factors applied after an in-tolerance and an out-of-tolerance finding.
    min_days, max_days : float, keyword-only
        Bounds of the interval.

    Returns
    -------
    float
        The interval after the last campaign, days.

    Raises
    ------
    AxiscalError
        For factors or days that are not positive, or ``extend < 1 < shrink``.

    Examples
    --------
    >>> staircase([True, True, False])
    285.15625
    """
    initial_days = check_number("initial_days", initial_days, positive=True)
    extend = check_number("extend", extend, low=1.0)
    shrink = check_number("shrink", shrink, positive=True, high=1.0)
    min_days = check_number("min_days", min_days, positive=True)
    max_days = check_number("max_days", max_days, low=min_days)
    interval = initial_days
    for ok in passed:
        interval = min(max(interval * (extend if ok else shrink), min_days), max_days)
    return interval


@dataclass(frozen=True)
class Trend:
    """A figure of one machine over its campaigns: drift, crossing date and next calibration.

    Attributes
    ----------
    machine, figure, unit : str
        The machine's label, the figure's key (``positioning.X.E``) and unit.
    dates : tuple of datetime.date
    values : ndarray, shape (n,)
    U : ndarray, shape (n,)
        Expanded uncertainties (k = 2); NaN where a campaign states none.
    tolerance : float
        The latest campaign's tolerance.
    fit : DriftFit
    k : float
        Coverage factor of the intervals.
    crossing_date : datetime.date or None
        When the line reaches the tolerance (None: it never does, or not within
        :data:`CROSSING_HORIZON_YEARS` of the last campaign; :attr:`crossing_note` says which).
    crossing_interval : (date or None, date or None)
        Fieller's interval on that date; None at an unbounded end (or one beyond the horizon).
    fixed_risk_date : datetime.date or None
        ILAC-G24 from the drift fit: out of tolerance with probability ``risk`` (None: never
        within ``max_days`` of the last campaign, or the fit cannot tell).
    risk : float
    staircase_date : datetime.date
        ILAC-G24 method 1.
    next_date : datetime.date
        The recommended next calibration: the earlier of the two.
    crossing_note : str
        Why there is no crossing date: ``"never (no drift)"``, ``"not within 100 years"`` or
        ``"over 100 years before the last campaign"``; ``""`` when there is one.
    one_sided : bool
        Whether the figure cannot be negative, so that only ``+tolerance`` is its limit.
    """

    machine: str
    figure: str
    unit: str
    dates: tuple[_dt.date, ...]
    values: np.ndarray
    U: np.ndarray
    tolerance: float
    fit: DriftFit
    k: float
    crossing_date: _dt.date | None
    crossing_interval: tuple[_dt.date | None, _dt.date | None]
    fixed_risk_date: _dt.date | None
    risk: float
    staircase_date: _dt.date
    next_date: _dt.date
    crossing_note: str = ""

    @property
    def crossing_text(self) -> str:
        """The crossing date (ISO), or why there is none, as messages and reports show it."""
        return self.crossing_date.isoformat() if self.crossing_date is not None else self.crossing_note
    one_sided: bool = False

    @property
    def limits(self) -> tuple[float, ...]:
        """The limits held against the figure, in its unit: ``(+tolerance,)`` or ``(+tolerance, -tolerance)``."""
        return (self.tolerance,) if self.one_sided else (self.tolerance, -self.tolerance)

    def payload(self) -> dict:
        """The trend as ``history trend --json`` prints it (dates ISO, slope per year).

        Parameters
        ----------
        (none)

        Returns
        -------
        dict
        """
        iso = lambda d: None if d is None else d.isoformat()  # noqa: E731
        return {
            "machine": self.machine, "figure": self.figure, "unit": self.unit, "tolerance": self.tolerance,
            "limits": list(self.limits),
            "campaigns": [{"date": d.isoformat(), "value": float(v), "U": None if math.isnan(u) else float(u)}
                          for d, v, u in zip(self.dates, self.values, self.U)],
            "fit": {"method": self.fit.method, "slope_per_year": self.fit.b, "u_slope_per_year": self.fit.u_b,
                    "value_at_reference": self.fit.a, "reference_date": iso(date_of(self.fit.t0)),
                    "chi2": self.fit.chi2, "dof": self.fit.dof},
            "k": self.k,
            "crossing_date": iso(self.crossing_date),
            "crossing_note": self.crossing_note or None,
            "crossing_interval": [iso(self.crossing_interval[0]), iso(self.crossing_interval[1])],
            "next_calibration": {"fixed_risk": iso(self.fixed_risk_date), "risk": self.risk,
                                 "staircase": iso(self.staircase_date), "recommended": iso(self.next_date)},
        }


def trend_of(
    machine: str,
    figure: str,
    dates: Sequence[_dt.date],
    values: Sequence[float],
    U: Sequence[float | None],
    tolerance: float,
    passed: Sequence[bool],
    *,
    unit: str = "",
    method: str = "wls",
    k: float = 2.0,
    risk: float = 0.05,
    max_days: float = 1095.0,
    one_sided: bool | None = None,
) -> Trend:
    """The trend of one figure from its campaigns.

    Parameters
    ----------
    machine, figure : str
        How the result names them.
    dates : sequence of datetime.date
        The campaigns' dates, oldest first.
    values : sequence of float
        The figure at each, in ``unit``.
    U : sequence of float or None
        Its expanded uncertainty (k = 2) at each; the fit is weighted only when every campaign
        states one.
    tolerance : float
        The limit of its magnitude.
    passed : sequence of bool
        Whether each campaign found it within tolerance (for the staircase).
    unit : str, keyword-only
    method : {"wls", "robust"}, keyword-only
    k : float, keyword-only
        Coverage factor of the crossing interval.
    risk : float, keyword-only
        The accepted probability of being out of tolerance at the next calibration (0 < risk < 0.5).
    max_days : float, keyword-only
        The longest interval either method recommends (at most 100 years).
    one_sided : bool, keyword-only
        The figure cannot be negative: only ``+tolerance`` is its limit (default: :func:`one_sided_figure`
        of ``figure``).

    Returns
    -------
    Trend
        A crossing further than :data:`CROSSING_HORIZON_YEARS` from the last campaign has no date
        (its ``crossing_note`` says "not within 100 years").

    Raises
    ------
    AxiscalError
        For fewer than three campaigns, a tolerance that is not positive, arrays of different
        lengths, a risk outside (0, 0.5), or a next date after 9999-12-31.
    """
    from scipy.stats import norm

    tolerance = check_number("tolerance", tolerance, positive=True)
    risk = check_number("risk", risk, positive=True, high=0.4999)
    max_days = check_number("max_days", max_days, positive=True, high=_MAX_INTERVAL_DAYS)
    if not (len(dates) == len(values) == len(U) == len(passed)):
        raise AxiscalError("dates, values, U and passed must have one entry per campaign")
    t = np.array([years(d) for d in dates])
    y = np.asarray(values, dtype=float)
    u = np.array([np.nan if x is None else float(x) for x in U])
    weighted = bool(np.all(np.isfinite(u) & (u > 0)))
    fit = fit_drift(t, y, u if weighted else None, method=method)
    one_sided = one_sided_figure(figure) if one_sided is None else check_instance("one_sided", one_sided, bool)
    limits = (tolerance,) if one_sided else (tolerance, -tolerance)
    t_cross, low, high = crossing(fit, tolerance, k=k, one_sided=one_sided)
    last = t[-1]
    z = float(norm.ppf(1.0 - risk))
    horizon = last + max_days / _YEAR_DAYS
    at_last = float(fit.at(last)) if one_sided else abs(float(fit.at(last)))
    if at_last + z * float(fit.u_at(last)) >= tolerance:
        fixed = last
    else:
        # the band's edge reaches a limit (+tolerance, or -tolerance for a signed figure), whichever comes first
        candidates = [r for limit in limits for r in _band_roots(fit, limit, z)[1] if r >= last]
        fixed = min(candidates) if candidates and min(candidates) <= horizon else None
    stair = last + staircase(passed, max_days=max_days) / _YEAR_DAYS
    next_t = min(stair, fixed) if fixed is not None else stair
    crossing_date = _within(t_cross, last)
    if t_cross is None:
        note = "never (no drift)"
    elif crossing_date is not None:
        note = ""
    elif t_cross > last:
        note = f"not within {CROSSING_HORIZON_YEARS:g} years"
    else:
        note = f"over {CROSSING_HORIZON_YEARS:g} years before the last campaign"
    return Trend(
        machine, figure, unit, tuple(dates), y, u, tolerance, fit, k, crossing_date,
        (_within(low, last), _within(high, last)),
        None if fixed is None else date_of(fixed), risk, date_of(stair), date_of(next_t), note, one_sided,
    )
