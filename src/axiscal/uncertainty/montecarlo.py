"""Monte Carlo propagation of distributions (JCGM 101:2008, GUM Supplement 1): coverage intervals from draws.

The probabilistically symmetric coverage interval (JCGM 101, 7.7) runs from the (1 - p)/2 to the
(1 + p)/2 quantile of the output draws; the shortest one (7.7.2) is the narrowest interval that
holds a fraction p of them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_number

__all__ = ["CoverageInterval", "coverage_interval"]


def _whole_draws(value, what: str = "the number of Monte Carlo draws", *, at_most: int | None = None) -> int:
    """``value`` as a positive int; AxiscalError for a bool, a fraction, nan, anything below 1 or above ``at_most``."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not np.isfinite(value) or int(value) != value or value < 1:
        raise AxiscalError(f"{what} must be a positive whole number, got {value!r}")
    if at_most is not None and value > at_most:
        raise AxiscalError(f"{what} must be at most {at_most:.0e} (memory), got {value:.3g}")
    return int(value)


def _probability(value) -> float:
    """``value`` as a coverage probability, strictly between 0 and 1."""
    p = check_number("probability", value, unit="")
    if not 0.0 < p < 1.0:
        raise AxiscalError(f"coverage probability must lie between 0 and 1, got {p:g}")
    return p


def _draws_array(samples) -> np.ndarray:
    """``samples`` as a float array of finite draws (float32 kept: half the memory, quantiles to 6e-8 relative)."""
    if samples is None or isinstance(samples, (str, bytes)):
        raise AxiscalError(f"samples must be an array of draws, not {samples!r}")
    x = np.asarray(samples)
    if x.dtype.kind not in "iuf":
        raise AxiscalError(f"samples must be an array of numeric draws, not of {x.dtype}")
    if x.ndim == 0:
        raise AxiscalError("samples must be an array of draws, not a single number")
    if not np.issubdtype(x.dtype, np.floating):
        x = x.astype(float)
    if not np.isfinite(x).all():
        raise AxiscalError("samples must hold finite draws (a NaN or an infinity is there)")
    return x


@dataclass(frozen=True)
class CoverageInterval:
    """A coverage interval of an output quantity from Monte Carlo draws (units of the draws).

    Attributes
    ----------
    low, high : float
        Ends of the interval.
    mean, std : float
        Mean and standard deviation of the draws (the estimate and its standard uncertainty).
    probability : float
        Coverage probability p.
    draws : int
        Number of draws.
    """

    low: float
    high: float
    mean: float
    std: float
    probability: float
    draws: int

    @property
    def half_width(self) -> float:
        """Half the width of the interval (the expanded uncertainty of a symmetric output)."""
        return 0.5 * (self.high - self.low)


def coverage_interval(samples, probability: float = 0.95, *, shortest: bool = False, axis: int = 0):
    """Coverage interval of Monte Carlo draws (JCGM 101:2008, 7.7).

    Parameters
    ----------
    samples : array_like, shape (M,) or (M, ...)
        Draws of the output along ``axis``.
    probability : float
        Coverage probability p, 0 < p < 1 (default 0.95).
    shortest : bool, keyword-only
        The shortest interval (JCGM 101 7.7.2) instead of the probabilistically symmetric one.
    axis : int, keyword-only
        The axis of the draws.

    Returns
    -------
    CoverageInterval or tuple of ndarray
        For one-dimensional draws a :class:`CoverageInterval`; otherwise ``(low, high)`` arrays over
        the other axes.

    Raises
    ------
    AxiscalError
        A probability outside (0, 1), fewer than 1 / (1 - p) draws, draws that are not numbers or
        not finite, an ``axis`` the draws do not have.

    Examples
    --------
    >>> import numpy as np
    >>> ci = coverage_interval(np.random.default_rng(0).normal(size=200_000))
    >>> round(ci.high, 1)
    2.0
    """
    probability = _probability(probability)
    if not isinstance(shortest, (bool, np.bool_)):
        raise AxiscalError(f"shortest must be a bool, not {shortest!r}")
    x = _draws_array(samples)
    axis = check_count("axis", axis, minimum=-x.ndim, maximum=x.ndim - 1)
    x = np.moveaxis(x, axis, 0)
    m = x.shape[0]
    if m < max(2.0, 1.0 / (1.0 - probability)):  # two at least: the standard deviation needs them
        raise AxiscalError(f"samples: {m} draws are too few for a {probability:.0%} coverage interval;"
                           f" use at least {max(2, int(np.ceil(1 / (1 - probability))))}")
    if shortest:
        ordered = np.sort(x, axis=0)
        q = int(np.floor(probability * m + 0.5))
        widths = ordered[q - 1 :] - ordered[: m - q + 1]
        start = np.argmin(widths, axis=0)
        low = np.take_along_axis(ordered, start[None, ...], axis=0)[0]
        high = np.take_along_axis(ordered, (start + q - 1)[None, ...], axis=0)[0]
    else:
        low, high = np.quantile(x, [(1.0 - probability) / 2.0, (1.0 + probability) / 2.0], axis=0)
    if x.ndim > 1:
        return low, high
    scale = float(np.max(np.abs(x)))
    if scale < 1e100:  # any physical draws: as they are
        mean, std = float(x.mean()), float(x.std(ddof=1))
    else:  # draws near the float range: mean and std of x / scale, which do not overflow
        unit = x / scale
        mean, std = scale * float(unit.mean()), scale * float(unit.std(ddof=1))
    return CoverageInterval(float(low), float(high), mean, std, probability, m)
