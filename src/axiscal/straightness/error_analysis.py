"""Errors of multi-probe separation in closed form (paper 001; checked by simulation in the tests).

Probe offsets accumulate linearly in STP and quadratically in STRP (eq 9-11; the printed eq 10-11
slip, see docs/straightness.md), neglected yaw in STP (eq 14, 17) and sensor noise per method.
"""

from __future__ import annotations


import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_number

__all__ = [
    "stp_offset_error",
    "strp_offset_error",
    "strp_yaw_offset_error",
    "stp_yaw_neglect_error",
    "stp_residual_yaw_error",
    "stp_noise_std",
    "strp_noise_std",
    "gtp_noise_std",
]


def _chain_points(n: np.ndarray) -> np.ndarray:
    """Chain point numbers as floats, refused when not finite or negative."""
    points = check_array("n (chain point numbers)", n)
    if np.any(points < 0):
        raise AxiscalError("n (chain point numbers) must not be negative")
    return points


def stp_offset_error(n: np.ndarray, delta1_m: float) -> np.ndarray:
    """Profile error of STP from the zero offset Delta1 = xi_b - xi_a (eq 9): ``-n Delta1``.

    Linear in the point number n (R(0) = 0), so it tilts the profile and leaves its straightness
    unchanged. (Eq 9 prints ``+n Delta1``; the sign follows from eq 8, where offsets are subtracted.)

    Parameters
    ----------
    n : array_like
        Chain point numbers.
    delta1_m : float
        Delta1, metres.

    Returns
    -------
    ndarray
        Profile error at each n, metres.
    """
    return -_chain_points(n) * check_number("delta1_m", delta1_m)


def strp_offset_error(n: np.ndarray, delta1_m: float, delta2_m: float) -> np.ndarray:
    """Profile error of STRP from the zero offsets Delta1 = xi_b - xi_a, Delta2 = xi_c - xi_a.

    Only the second difference's offset ``Delta2 - 2 Delta1`` enters, every step, and sums twice:
    ``-(Delta2 - 2 Delta1) n (n - 1) / 2`` with R(0) = R(1) = 0 (the corrected eq 10).

    Parameters
    ----------
    n : array_like
        Chain point numbers.
    delta1_m, delta2_m : float
        Delta1 and Delta2, metres.

    Returns
    -------
    ndarray
        Profile error at each n, metres.
    """
    n = _chain_points(n)
    delta1_m, delta2_m = check_number("delta1_m", delta1_m), check_number("delta2_m", delta2_m)
    return -(delta2_m - 2.0 * delta1_m) * n * (n - 1.0) / 2.0


def strp_yaw_offset_error(n: np.ndarray, delta1_m: float, delta2_m: float, *, spacing_m: float) -> np.ndarray:
    """Yaw error of STRP from the zero offsets (corrected eq 11): ``((2n + 1) Delta1 - n Delta2) / d``.

    Parameters
    ----------
    n : array_like
        Chain point numbers.
    delta1_m, delta2_m : float
        Delta1 and Delta2, metres.
    spacing_m : float, keyword-only
        Probe spacing d, metres.

    Returns
    -------
    ndarray
        Yaw error at each n, radians.
    """
    n = _chain_points(n)
    delta1_m, delta2_m = check_number("delta1_m", delta1_m), check_number("delta2_m", delta2_m)
    return ((2.0 * n + 1.0) * delta1_m - n * delta2_m) / check_number("spacing_m", spacing_m, positive=True)


def stp_yaw_neglect_error(yaw_rad: np.ndarray, *, spacing_m: float) -> np.ndarray:
    """Profile error of STP when the yaw is neglected (eq 14): ``delta(n) = -d sum_{i<n} gamma(i)``.

    Parameters
    ----------
    yaw_rad : array_like, shape (J,)
        Yaw at the J readings of the chain, radians.
    spacing_m : float, keyword-only
        Probe spacing d, metres.

    Returns
    -------
    ndarray, shape (J + 1,)
        Error at the J + 1 chain points, metres (delta(0) = 0).
    """
    spacing_m = check_number("spacing_m", spacing_m, positive=True)
    return -spacing_m * np.concatenate([[0.0], np.cumsum(check_array("yaw_rad", yaw_rad, ndim=1))])


def stp_residual_yaw_error(n: np.ndarray, *, spacing_m: float, mean_rad: float, slope_rad_per_step: float) -> np.ndarray:
    """Error of STP corrected with a yaw whose mean and slope were removed (eq 17).

    ``delta(n) = -n d mu - n (n - 1) / 2 d eta``: the mean accumulates linearly (a tilt), the
    slope quadratically (a bow).

    Parameters
    ----------
    n : array_like
        Chain point numbers.
    spacing_m : float, keyword-only
        Probe spacing d, metres.
    mean_rad, slope_rad_per_step : float, keyword-only
        Mean mu and slope eta of the yaw left, radians and radians per step.

    Returns
    -------
    ndarray
        Profile error at each n, metres.
    """
    n = _chain_points(n)
    spacing_m = check_number("spacing_m", spacing_m, positive=True)
    mean_rad = check_number("mean_rad", mean_rad)
    slope_rad_per_step = check_number("slope_rad_per_step", slope_rad_per_step)
    return -n * spacing_m * mean_rad - 0.5 * n * (n - 1.0) * spacing_m * slope_rad_per_step


def stp_noise_std(n: np.ndarray, noise_m: float) -> np.ndarray:
    """Standard deviation of the STP profile at chain point n from independent probe noise sigma.

    Each step adds ``b - a`` (variance 2 sigma^2): a random walk, ``sigma sqrt(2 n)``.

    Parameters
    ----------
    n : array_like
        Chain point numbers.
    noise_m : float
        Standard deviation sigma of each reading, metres.

    Returns
    -------
    ndarray
        Standard deviation at each n, metres.
    """
    return check_number("noise_m", noise_m, nonnegative=True) * np.sqrt(2.0 * _chain_points(n))


def strp_noise_std(n: np.ndarray, noise_m: float) -> np.ndarray:
    """Standard deviation of the STRP profile at chain point n (R(0) = R(1) = 0) from probe noise.

    ``c - 2b + a`` has variance 6 sigma^2 and enters point n with weight n - 1 - k, so the
    variance is ``6 sigma^2 sum_{j<n} j^2 = sigma^2 (n - 1) n (2n - 1)``: it grows as n^3.

    Parameters
    ----------
    n : array_like
        Chain point numbers.
    noise_m : float
        Standard deviation sigma of each reading, metres.

    Returns
    -------
    ndarray
        Standard deviation at each n, metres.
    """
    n = _chain_points(n)
    return check_number("noise_m", noise_m, nonnegative=True) * np.sqrt(np.clip((n - 1.0) * n * (2.0 * n - 1.0), 0.0, None))


def gtp_noise_std(n: np.ndarray, noise_m: float, *, steps_per_spacing: int) -> np.ndarray:
    """Standard deviation of the GTP profile at point n: a random walk scaled by s / d.

    Parameters
    ----------
    n : array_like
        Point numbers.
    noise_m : float
        Standard deviation of each reading, metres.
    steps_per_spacing : int, keyword-only
        d / s.

    Returns
    -------
    ndarray
        Standard deviation at each n, metres.
    """
    steps_per_spacing = check_count("steps_per_spacing", steps_per_spacing)
    return check_number("noise_m", noise_m, nonnegative=True) * np.sqrt(2.0 * _chain_points(n)) / steps_per_spacing
