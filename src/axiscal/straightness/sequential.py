"""Point-by-point error separation (paper 001): reversal, sequential two-point and three-point, the fine three-point and the generalized two-point methods.

* :func:`reversal`: two runs of one probe, the workpiece turned over about its long axis.
* :func:`sequential_two_point` (STP, eq 3-4; with a yaw correction eq 13).
* :func:`sequential_three_point` (STRP, eq 1-2).
* :func:`fine_sequential_three_point` (FSTRP, eq 5-6): two STP families with coprime spacings,
  merged by translation and rotation at their common points.
* :func:`generalized_two_point` (GTP, eq 7): sampling step smaller than the spacing.

All recurrences are cumulative sums; no Python loop runs over the points. Separated profiles are
defined up to a straight line (R and S share it; gamma up to a constant): the first point(s) of
each chain are set to zero.
"""

from __future__ import annotations

import math

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_number, check_same_length
from axiscal.straightness.probes import (
    _EMPTY,
    ProbeReadings,
    Separation,
    _finish,
    _readings,
    _step,
    _steps_in,
    _third_probe,
)
from axiscal.units import MM

__all__ = [
    "reversal",
    "sequential_two_point",
    "sequential_three_point",
    "fine_sequential_three_point",
    "generalized_two_point",
    "gtp_amplitude_response",
]


def reversal(position_m: np.ndarray, normal_m: np.ndarray, reversed_m: np.ndarray) -> Separation:
    """Reversal: one probe, two runs, the workpiece turned over about its long axis in between.

    The first run reads ``R - S`` (eq 1, probe A); turning the workpiece over and probing it
    from the other side reads ``R + S``, so ``R = (normal + reversed) / 2`` and
    ``S = (reversed - normal) / 2``. Exact, with no line left undetermined; needs no even step.

    Parameters
    ----------
    position_m, normal_m, reversed_m : array_like, shape (n,)
        Positions and the two runs' readings at the same positions, metres.

    Returns
    -------
    Separation
        Profile R and motion S at the given positions; no yaw.

    Raises
    ------
    AxiscalError
        Runs of different shapes or not one-dimensional.

    Examples
    --------
    >>> from axiscal.units import UM
    >>> result = reversal([0.0, 0.01], [0.5 * UM, 1.0 * UM], [1.5 * UM, 1.0 * UM])
    >>> (result.profile_m / UM).round(6).tolist()
    [1.0, 1.0]
    """
    x, n, r = (check_array(name, v, ndim=1) for name, v in (("position_m", position_m), ("normal_m", normal_m), ("reversed_m", reversed_m)))
    if not (x.shape == n.shape == r.shape):
        raise AxiscalError(
            f"reversal needs the normal and the reversed run at the same positions: position_m, normal_m and "
            f"reversed_m must have the same length, not {x.size}, {n.size} and {r.size}"
        )
    if x.size < 1:
        raise AxiscalError("position_m needs at least 1 value, got 0")
    profile = 0.5 * (n + r)
    return Separation("reversal", x, profile, 0.5 * (r - n), np.full(x.shape, np.nan), _EMPTY)


def sequential_two_point(readings: ProbeReadings, *, yaw_rad: np.ndarray | None = None) -> Separation:
    """Sequential two-point method (STP, paper 001 eq 3-4), optionally with yaw (eq 13).

    ``R(n + 1) = R(n) - a(n) + b(n) + d1 gamma(n)`` with R(0) = 0, on the readings one spacing
    apart (every ``d1 / step``-th reading, starting with the first). Without ``yaw_rad`` the yaw
    is neglected (eq 4) and its error accumulates as eq (14).

    Parameters
    ----------
    readings : ProbeReadings
        Evenly stepped, with ``spacing_ab_m`` a whole number of steps.
    yaw_rad : array_like, shape (n,), optional
        Yaw at every reading, radians, used as in eq (13).

    Returns
    -------
    Separation
        Profile at ``x0 + j d1``, j = 0..J (J readings used).

    Raises
    ------
    AxiscalError
        Fewer than 2 readings, positions not increasing in even steps, or a spacing that is not a
        positive whole number of steps.
    """
    x = _readings(readings).position_m
    m = _steps_in(readings.spacing_ab_m, _step(x, "STP"), "STP")
    diff = readings.b_m[::m] - readings.a_m[::m]
    if yaw_rad is not None:
        yaw = check_array("yaw_rad", yaw_rad, ndim=1)
        check_same_length(position_m=x, yaw_rad=yaw)
        diff = diff + readings.spacing_ab_m * yaw[::m]
    profile = np.concatenate([[0.0], np.cumsum(diff)])
    position = x[0] + readings.spacing_ab_m * np.arange(profile.size)
    return _finish("stp", position, profile, readings)


def _strp_chain(a: np.ndarray, b: np.ndarray, c: np.ndarray, d: float) -> tuple[np.ndarray, np.ndarray]:
    """STRP on one chain (eq 2): profile (J + 2 points, R0 = R1 = 0) and yaw (J points)."""
    second = c - 2.0 * b + a
    slope = np.concatenate([[0.0], np.cumsum(second)])
    profile = np.concatenate([[0.0], np.cumsum(slope)])
    yaw = (profile[1:-1] - profile[:-2] + a - b) / d
    return profile, yaw


def sequential_three_point(readings: ProbeReadings) -> Separation:
    """Sequential three-point method (STRP, paper 001 eq 1-2) with equal spacings d1 = d2 = d.

    ``R(n + 2) = c(n) - 2 b(n) + a(n) + 2 R(n + 1) - R(n)`` with R(0) = R(1) = 0 and
    ``gamma(n) = (R(n + 1) - R(n) + a(n) - b(n)) / d`` (eq 2 with S = R - a), on the readings one
    spacing apart. Yaw is separated; zero offsets accumulate quadratically (eq 10).

    Parameters
    ----------
    readings : ProbeReadings
        Three probes, evenly stepped, the spacing a whole number of steps.

    Returns
    -------
    Separation
        Profile at ``x0 + j d``, j = 0..J + 1, yaw at the J reading positions.

    Raises
    ------
    AxiscalError
        Fewer than 2 readings, positions not increasing in even steps, or a spacing that is not a
        positive whole number of steps. Also when probe C is missing or the spacings differ.
    """
    x = _readings(readings).position_m
    c, d2 = _third_probe(readings, "STRP")
    d = readings.spacing_ab_m
    if not abs(d2 - d) <= 1e-9 * d:
        raise AxiscalError(f"STRP needs equal spacings (A-B {d / MM:g} mm, B-C {d2 / MM:g} mm); use FSTRP for unequal ones")
    m = _steps_in(d, _step(x, "STRP"), "STRP")
    profile, yaw = _strp_chain(readings.a_m[::m], readings.b_m[::m], c[::m], d)
    position = x[0] + d * np.arange(profile.size)
    chain = ProbeReadings(x[::m], readings.a_m[::m], readings.b_m[::m], c[::m], d, d2)
    return _finish("strp", position, profile, chain, yaw)


def _chains(diff: np.ndarray, m: int) -> np.ndarray:
    """Solve R(n + m) - R(n) = diff(n), n = 0..N-1, with R(r) = 0 for r < m (m interleaved chains)."""
    n = diff.size
    total = n + m
    rows = -(-total // m)
    padded = np.zeros(rows * m)
    padded[m : m + n] = diff
    return np.cumsum(padded.reshape(rows, m), axis=0).ravel()[:total]


def fine_sequential_three_point(readings: ProbeReadings) -> Separation:
    """Fine sequential three-point method (FSTRP, paper 001 eq 5-6), yaw neglected.

    With the sampling step s and spacings d1 = p s, d1 + d2 = q s (p and q coprime), eq (5)
    gives R on p interleaved chains from ``b - a`` and eq (6) on q chains from ``c - a``. The two
    families share their points; the chain offsets and one relative tilt (the two families
    accumulate zero offsets at different rates) are fitted by least squares at the common points,
    then the families are averaged where both exist. Resolves every step.

    Parameters
    ----------
    readings : ProbeReadings
        Three probes, evenly stepped, both spacings whole numbers of steps.

    Returns
    -------
    Separation
        Profile at every step, up to probe C's reach; no yaw.

    Raises
    ------
    AxiscalError
        Fewer than 2 readings, positions not increasing in even steps, or a spacing that is not a
        positive whole number of steps. Also when probe C is missing, the spacings in
        steps are not coprime, or there are fewer readings than the A-C spacing has steps.
    """
    x = _readings(readings).position_m
    c, d2 = _third_probe(readings, "FSTRP")
    step = _step(x, "FSTRP")
    p = _steps_in(readings.spacing_ab_m, step, "FSTRP", "A-B spacing")
    q = p + _steps_in(d2, step, "FSTRP", "B-C spacing")
    if math.gcd(p, q) != 1:
        raise AxiscalError(
            f"FSTRP needs the spacings in steps to be coprime (A-B {p}, A-C {q} steps): otherwise the chains never meet"
        )
    if x.size < q:
        # the common points n < N + p tie the p + q chains and the tilt together exactly when N >= q
        raise AxiscalError(
            f"FSTRP needs at least as many readings as the A-C spacing has steps ({q}) for the two families to meet, got {x.size}"
        )
    first = _chains(readings.b_m - readings.a_m, p)
    second = _chains(c - readings.a_m, q)
    n = np.arange(first.size)
    rp, rq = n % p, n % q
    tilt = n / n.size
    solution = _merge_families(second[: first.size] - first, rp, rq, tilt, p, q)
    aligned_first = first + solution[rp] + solution[p + q - 1] * tilt
    offsets2 = np.concatenate([[0.0], solution[p : p + q - 1]])
    profile = second + offsets2[np.arange(second.size) % q]
    profile[: first.size] = 0.5 * (profile[: first.size] + aligned_first)
    position = x[0] + step * np.arange(profile.size)
    return _finish("fstrp", position, profile, readings)


def _merge_families(rhs: np.ndarray, rp: np.ndarray, rq: np.ndarray, t: np.ndarray, p: int, q: int) -> np.ndarray:
    """Least squares for the FSTRP merge, as normal equations summed per chain (no loop over points).

    Unknowns: the offsets of the p chains of family 1, of chains 1..q-1 of family 2 (chain 0 is
    the datum) and a tilt of family 1; one equation per common point n:
    ``c1[n % p] + tilt * t(n) - c2[n % q] = rhs(n)`` (family 2 minus family 1).
    """
    k = p + q
    unknown1 = rp
    unknown2 = np.where(rq > 0, p + rq - 1, -1)
    normal = np.zeros((k, k))
    rhs_vec = np.zeros(k)
    normal[:p, :p] += np.diag(np.bincount(unknown1, minlength=p).astype(float))
    has2 = unknown2 >= 0
    u2 = unknown2[has2]
    normal[p : k - 1, p : k - 1] += np.diag(np.bincount(u2 - p, minlength=q - 1).astype(float))
    cross = np.bincount(unknown1[has2] * (q - 1) + (u2 - p), minlength=p * (q - 1)).reshape(p, q - 1)
    normal[:p, p : k - 1] -= cross
    normal[p : k - 1, :p] -= cross.T
    tsum1 = np.bincount(unknown1, weights=t, minlength=p)
    tsum2 = np.bincount(u2 - p, weights=t[has2], minlength=q - 1)
    normal[:p, k - 1] = normal[k - 1, :p] = tsum1
    normal[p : k - 1, k - 1] = normal[k - 1, p : k - 1] = -tsum2
    normal[k - 1, k - 1] = float(np.dot(t, t))
    rhs_vec[:p] = np.bincount(unknown1, weights=rhs, minlength=p)
    rhs_vec[p : k - 1] = -np.bincount(u2 - p, weights=rhs[has2], minlength=q - 1)
    rhs_vec[k - 1] = float(np.dot(t, rhs))
    solution, *_ = np.linalg.lstsq(normal, rhs_vec, rcond=None)
    return solution


def generalized_two_point(readings: ProbeReadings) -> Separation:
    """Generalized two-point method (GTP, paper 001 eq 7), yaw neglected.

    ``z(n + 1) = z(n) + (b(n) - a(n)) s / d1`` integrates the chord slope with the sampling step
    s < d1. Summed, z(n) is exactly the mean of R over the m = d1 / s samples n..n + m - 1, so it
    is placed at the window's centre ``x_n + (d1 - s) / 2``; its amplitude response to a
    wavelength lambda is ``sinc(d1 / lambda) / sinc(s / lambda)`` (6.5 % short at 75 mm for
    d1 = 15 mm, s = 1 mm, as the paper says).

    Parameters
    ----------
    readings : ProbeReadings
        Evenly stepped, the A-B spacing a whole number of steps.

    Returns
    -------
    Separation
        Profile at the window centres, one per reading plus one; no yaw.

    Raises
    ------
    AxiscalError
        Fewer than 2 readings, positions not increasing in even steps, or a spacing that is not a
        positive whole number of steps.
    """
    x = _readings(readings).position_m
    step = _step(x, "GTP")
    d = readings.spacing_ab_m
    _steps_in(d, step, "GTP")
    profile = np.concatenate([[0.0], np.cumsum(readings.b_m - readings.a_m) * (step / d)])
    position = x[0] + 0.5 * (d - step) + step * np.arange(profile.size)
    return _finish("gtp", position, profile, readings)


def gtp_amplitude_response(wavelength_m: np.ndarray, *, spacing_m: float, step_m: float) -> np.ndarray:
    """Amplitude ratio of the GTP profile to the true one for a sinusoid of the given wavelength.

    The difference over d1 has gain ``|sin(pi d1 / lambda)| / (pi d1 / lambda)`` relative to the
    derivative, the rectangle-rule sum over s has ``(pi s / lambda) / sin(pi s / lambda)``
    relative to the integral.

    Parameters
    ----------
    wavelength_m : array_like
        Wavelengths, metres.
    spacing_m, step_m : float, keyword-only
        Probe spacing d1 and sampling step s, metres.

    Returns
    -------
    ndarray
        The amplitude ratio for each wavelength.

    Examples
    --------
    >>> round(float(gtp_amplitude_response(75e-3, spacing_m=15e-3, step_m=1e-3)), 3)
    0.936
    """
    lam = check_array("wavelength_m", wavelength_m)
    if np.any(lam <= 0.0):
        raise AxiscalError("wavelength_m must hold positive wavelengths (metres)")
    spacing_m = check_number("spacing_m", spacing_m, positive=True)
    step_m = check_number("step_m", step_m, nonnegative=True)
    if np.any(step_m >= lam):
        raise AxiscalError(f"step_m ({step_m:g} m) must be shorter than every wavelength: sampling cannot see a wavelength at or below its step")
    return (np.abs(np.sinc(spacing_m / lam))) / np.sinc(step_m / lam)
