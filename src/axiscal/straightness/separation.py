"""Multi-probe straightness error separation: workpiece profile R, slide motion S and yaw gamma.

Paper 001 (Wang and Li, straightness error combination separation). Probe A sits at the
position x, probe B at x + d1 and probe C at x + d1 + d2 on a carriage that moves along the
workpiece; with probe zero offsets xi (eq 8) they read (eq 1)::

    a(x) = R(x)           - S(x)                   - xi_a
    b(x) = R(x + d1)      - S(x) - d1 gamma(x)       - xi_b
    c(x) = R(x + d1 + d2) - S(x) - (d1 + d2) gamma(x) - xi_c

Methods (each returns a :class:`Separation`):

* :func:`reversal`: two runs of one probe, the workpiece turned over about its long axis.
* :func:`sequential_two_point` (STP, eq 3-4; with a yaw correction eq 13).
* :func:`sequential_three_point` (STRP, eq 1-2).
* :func:`fine_sequential_three_point` (FSTRP, eq 5-6): two STP families with coprime spacings,
  merged by translation and rotation at their common points.
* :func:`generalized_two_point` (GTP, eq 7): sampling step smaller than the spacing.
* :func:`frequency_domain`: two- or three-point inversion of the difference signal by DFT, with the
  suppressed harmonics reported and left out.
* :func:`combined` (section 4, steps 1-5): GTP shape, STRP yaw with mean and slope removed, STP per
  group with that yaw (eq 13), groups joined to the GTP shape by least squares (eq 18-19).

Error analysis in closed form (checked by simulation in the tests): probe offsets accumulate
linearly in STP and quadratically in STRP (eq 9-11; the printed eq 10-11 slip, see
docs/straightness.md), neglected yaw in STP (eq 14, 17) and sensor noise per method.

All recurrences are cumulative sums; no Python loop runs over the points. Separated profiles are
defined up to a straight line (R and S share it; gamma up to a constant): the first point(s) of
each chain are set to zero.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_count, check_instance, check_number, check_same_length, is_real
from axiscal.units import MM

__all__ = [
    "METHODS",
    "ProbeReadings",
    "Separation",
    "simulate_readings",
    "uneven_step",
    "reversal",
    "sequential_two_point",
    "sequential_three_point",
    "fine_sequential_three_point",
    "generalized_two_point",
    "gtp_amplitude_response",
    "frequency_domain",
    "combined",
    "separate",
    "stp_offset_error",
    "strp_offset_error",
    "strp_yaw_offset_error",
    "stp_yaw_neglect_error",
    "stp_residual_yaw_error",
    "stp_noise_std",
    "strp_noise_std",
    "gtp_noise_std",
    "NoisePropagation",
    "noise_propagation",
]

#: names accepted by :func:`separate` (reversal takes two runs: :func:`reversal`)
METHODS = ("stp", "strp", "fstrp", "gtp", "frequency", "combined")

_EMPTY = np.empty(0)


@dataclass(frozen=True)
class ProbeReadings:
    """Readings of two or three probes on one carriage, indexed by the position of probe A.

    Attributes
    ----------
    position_m : ndarray, shape (n,)
        Position of probe A along the workpiece at each reading, metres.
    a_m, b_m : ndarray, shape (n,)
        Readings of probes A and B, metres.
    c_m : ndarray, shape (n,) or None
        Readings of probe C, metres; None for a two-probe set-up.
    spacing_ab_m : float
        Distance d1 from probe A to probe B, metres.
    spacing_bc_m : float or None
        Distance d2 from probe B to probe C, metres; None for a two-probe set-up.
    """

    position_m: np.ndarray
    a_m: np.ndarray
    b_m: np.ndarray
    c_m: np.ndarray | None
    spacing_ab_m: float
    spacing_bc_m: float | None = None

    def __post_init__(self) -> None:
        for name in ("position_m", "a_m", "b_m", "c_m"):
            value = getattr(self, name)
            if value is not None or name != "c_m":
                object.__setattr__(self, name, check_array(name, value, ndim=1))
        check_same_length(position_m=self.position_m, a_m=self.a_m, b_m=self.b_m, c_m=self.c_m)
        d1, d2 = self.spacing_ab_m, self.spacing_bc_m
        if not (is_real(d1) and math.isfinite(d1) and d1 > 0):
            raise AxiscalError(f"spacing_ab_m must be a positive, finite number of metres, not {d1!r}")
        object.__setattr__(self, "spacing_ab_m", float(d1))
        # the B-C spacing is checked by the methods that use it, which name what they need of it
        if d2 is not None and not is_real(d2):
            raise AxiscalError(f"spacing_bc_m must be a number of metres or None, not {d2!r}")



def _readings(readings: ProbeReadings) -> ProbeReadings:
    check_instance("readings", readings, ProbeReadings, what="ProbeReadings")
    return readings


@dataclass(frozen=True)
class Separation:
    """Result of an error separation, one row per position the method resolves.

    Attributes
    ----------
    method : str
        Name of the method.
    position_m : ndarray, shape (n,)
        Workpiece positions of the separated profile, metres.
    profile_m : ndarray, shape (n,)
        Workpiece profile R, metres, up to a straight line.
    motion_m : ndarray, shape (n,)
        Slide straightness motion S at the carriage position where probe A was at that position,
        metres (R and S share the undetermined line); NaN where probe A has no reading.
    yaw_rad : ndarray, shape (n,)
        Slide yaw gamma, radians, up to a constant; NaN where the method does not resolve yaw.
    lost_wavelength_m : ndarray, shape (k,)
        Wavelengths the method cannot see and left out (frequency-domain methods), metres.
    """

    method: str
    position_m: np.ndarray
    profile_m: np.ndarray
    motion_m: np.ndarray
    yaw_rad: np.ndarray
    lost_wavelength_m: np.ndarray


# ---------------------------------------------------------------------------------------------
# simulation


def simulate_readings(
    position_m: np.ndarray,
    profile: Callable[[np.ndarray], np.ndarray],
    motion: Callable[[np.ndarray], np.ndarray],
    yaw: Callable[[np.ndarray], np.ndarray] | None = None,
    *,
    spacing_ab_m: float,
    spacing_bc_m: float | None = None,
    offsets_m: tuple[float, float, float] = (0.0, 0.0, 0.0),
    noise_m: float = 0.0,
    rng: np.random.Generator | None = None,
) -> ProbeReadings:
    """Probe readings of paper 001 eq (1) with the zero offsets of eq (8) and Gaussian noise.

    Parameters
    ----------
    position_m : array_like, shape (n,)
        Positions of probe A, metres.
    profile, motion : callable
        R(x) and S(x): arrays of positions (m) to deviations (m).
    yaw : callable, optional
        gamma(x): positions (m) to yaw (rad); no yaw when omitted.
    spacing_ab_m, spacing_bc_m : float, keyword-only
        Probe spacings d1 and d2, metres; ``spacing_bc_m=None`` simulates two probes.
    offsets_m : (float, float, float), keyword-only
        Zero offsets xi_a, xi_b, xi_c, metres, subtracted from the readings as in eq (8).
    noise_m : float, keyword-only
        Standard deviation of independent Gaussian noise on every reading, metres.
    rng : numpy.random.Generator, optional
        Source of the noise (default ``np.random.default_rng(0)``).

    Returns
    -------
    ProbeReadings
        The readings, metres.

    Examples
    --------
    >>> import numpy as np
    >>> x = np.arange(5) * 1e-3
    >>> data = simulate_readings(x, lambda p: 0 * p, lambda p: 1e-6 + 0 * p, spacing_ab_m=1e-3)
    >>> data.a_m.tolist()
    [-1e-06, -1e-06, -1e-06, -1e-06, -1e-06]
    """
    x = check_array("position_m", position_m, ndim=1, min_len=1)
    for name, function in (("profile", profile), ("motion", motion), ("yaw", yaw)):
        if not (callable(function) or function is None and name == "yaw"):
            raise AxiscalError(f"{name} must be a function of the positions (metres), not {function!r}")
    offsets_m = check_array("offsets_m", offsets_m, ndim=1)
    if offsets_m.shape != (3,):
        raise AxiscalError(f"offsets_m must be 3 numbers of metres (probes A, B, C), not shape {offsets_m.shape}")
    noise_m = check_number("noise_m", noise_m, nonnegative=True)
    check_number("spacing_ab_m", spacing_ab_m, positive=True)
    if spacing_bc_m is not None:
        check_number("spacing_bc_m", spacing_bc_m, positive=True)
    rng = _rng(rng)
    s = _evaluated("motion", motion, x)
    g = np.zeros_like(x) if yaw is None else _evaluated("yaw", yaw, x)

    def noisy(v: np.ndarray) -> np.ndarray:
        return v + noise_m * rng.standard_normal(v.shape) if noise_m > 0 else v

    d1 = float(spacing_ab_m)
    a = noisy(_evaluated("profile", profile, x) - s - offsets_m[0])
    b = noisy(_evaluated("profile", profile, x + d1) - s - d1 * g - offsets_m[1])
    c = None
    if spacing_bc_m is not None:
        d12 = d1 + float(spacing_bc_m)
        c = noisy(_evaluated("profile", profile, x + d12) - s - d12 * g - offsets_m[2])
    return ProbeReadings(x, a, b, c, d1, None if spacing_bc_m is None else float(spacing_bc_m))


def _evaluated(name: str, function: Callable[[np.ndarray], np.ndarray], x: np.ndarray) -> np.ndarray:
    """``function(x)`` as a finite float array of x's shape (a constant is spread), refused naming ``name`` otherwise."""
    values = check_array(f"{name}(position_m)", function(x))
    if values.ndim == 0:
        values = np.full(x.shape, float(values))
    if values.shape != x.shape:
        raise AxiscalError(f"{name} must return one value per position, shape {x.shape}, not {values.shape}")
    return values


def _rng(rng: np.random.Generator | None) -> np.random.Generator:
    if rng is None:
        return np.random.default_rng(0)
    if not isinstance(rng, np.random.Generator):
        raise AxiscalError(f"rng must be a numpy.random.Generator, not {type(rng).__name__}")
    return rng


# ---------------------------------------------------------------------------------------------
# checks at the boundary of each method


def uneven_step(position_m: np.ndarray) -> int | None:
    """Index k of the first reading whose step to reading k + 1 is not the first step, or None.

    A first step that is not positive counts as uneven at k = 0. Steps agree within 1e-6 of
    the first step (positions read from files carry rounding).

    Parameters
    ----------
    position_m : ndarray, shape (n,), n >= 2
        Positions of probe A, metres.

    Returns
    -------
    int or None
        The index, or None when every step equals the first.

    Examples
    --------
    >>> import numpy as np
    >>> uneven_step(np.array([0.0, 1.0, 2.0, 4.0]))
    2
    """
    steps = np.diff(check_array("position_m", position_m, ndim=1, min_len=2))
    if not steps[0] > 0:
        return 0
    bad = np.flatnonzero(~(np.abs(steps - steps[0]) <= 1e-6 * steps[0]))
    return int(bad[0]) if bad.size else None


def _step(position: np.ndarray, method: str) -> float:
    if position.size < 2:
        raise AxiscalError(f"{method} needs at least 2 readings, got {position.size}")
    step = float(position[1] - position[0])
    k = uneven_step(position)
    if k is not None:
        if not step > 0:
            raise AxiscalError(f"{method} needs increasing positions (the first step is {step / MM:g} mm)")
        raise AxiscalError(
            f"{method} needs evenly stepped positions: the step after {position[k] / MM:g} mm is "
            f"{(position[k + 1] - position[k]) / MM:g} mm, the first step is {step / MM:g} mm"
        )
    return step


def _steps_in(spacing: float, step: float, method: str, what: str = "probe spacing") -> int:
    if not (math.isfinite(spacing) and spacing > 0):
        raise AxiscalError(f"{method} needs a positive, finite {what}, got {spacing / MM:g} mm")
    ratio = spacing / step
    m = int(round(ratio))
    if m < 1 or abs(ratio - m) > 1e-6 * max(1.0, ratio):
        raise AxiscalError(
            f"{method} needs the {what} to be a whole number of steps: {spacing / MM:g} mm is "
            f"{ratio:g} steps of {step / MM:g} mm"
        )
    return m


def _third_probe(readings: ProbeReadings, method: str) -> tuple[np.ndarray, float]:
    if readings.c_m is None or readings.spacing_bc_m is None:
        raise AxiscalError(f"{method} needs three probes: readings of probe C (column c_um) and the B-C spacing are missing")
    return readings.c_m, readings.spacing_bc_m


def _finish(
    method: str,
    position: np.ndarray,
    profile: np.ndarray,
    readings: ProbeReadings,
    yaw_at_a: np.ndarray | None = None,
    lost: np.ndarray = _EMPTY,
) -> Separation:
    """Motion S = R - a where probe A read at the profile's positions; yaw carried where given.

    Where the profile's positions fall between readings (GTP with an even number of steps per
    spacing), ``a`` and the yaw are interpolated linearly.
    """
    xa = readings.position_m
    inside = (position >= xa[0] - 1e-12) & (position <= xa[-1] + 1e-12)
    motion = np.full(position.shape, np.nan)
    motion[inside] = profile[inside] - np.interp(position[inside], xa, readings.a_m)
    yaw = np.full(position.shape, np.nan)
    if yaw_at_a is not None and yaw_at_a.size:
        known = inside & (position <= xa[yaw_at_a.size - 1] + 1e-12)
        yaw[known] = np.interp(position[known], xa[: yaw_at_a.size], yaw_at_a)
    return Separation(method, position, profile, motion, yaw, lost)


def _yaw_from_profile(readings: ProbeReadings, position: np.ndarray, profile: np.ndarray) -> np.ndarray:
    """Yaw at the readings whose probe B is on the profile: eq (2) with S = R - a.

    ``gamma(x) = (R(x + d1) - R(x) + a(x) - b(x)) / d1``; returns the leading readings for which
    x + d1 is within the profile's positions.
    """
    x, d = readings.position_m, readings.spacing_ab_m
    ahead = np.interp(x + d, position, profile, right=np.nan)
    yaw = (ahead - np.interp(x, position, profile) + readings.a_m - readings.b_m) / d
    return yaw[np.isfinite(yaw)]


# ---------------------------------------------------------------------------------------------
# methods


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


def frequency_domain(
    readings: ProbeReadings, *, probes: int = 3, min_gain: float = 0.05, parabola: bool = True
) -> Separation:
    """Frequency-domain two- or three-point separation with the suppressed harmonics left out.

    The difference signal ``T(n) = sum_k w_k y_k(n) = sum_k w_k R(n + o_k)`` (offsets o_k in steps)
    removes S; its DFT is ``H(f) R(f)`` with ``H(f) = sum_k w_k exp(2 pi i f o_k / N)``.

    * ``probes=2``: ``T = b - a``, ``H = exp(2 pi i f p / N) - 1``; yaw neglected.
    * ``probes=3``: ``w = (-d2, d1 + d2, -d1) / (d1 + d2)`` cancels S and the yaw; with d1 != d2
      H vanishes only at the common harmonics of d1 and d2, which is how the three-point version
      handles the harmonic suppression of the two-point one (zeros at every wavelength d1 / j).

    The record is treated as one period of N = number of readings. A straight line in R is
    invisible (it is the undetermined line). With ``parabola=True`` (default) the parabola, which
    the periodic model cannot hold, is taken out first in closed form (from the trend of T for two
    probes, from the mean of T for three); this suits open straightness profiles, whose bow is
    their largest term. ``parabola=False`` treats R as exactly periodic over the record.

    Harmonic suppression: at low frequencies |H| falls as (2 pi f / N)^j times the first
    non-zero moment of the weights (j = 1 for two probes, 2 for three) -- that is the integration,
    not a loss. A harmonic whose |H| is below ``min_gain`` times that envelope (capped at
    max |H|) sits at or near a zero of H; inverting it would amplify noise by 1/|H|, so it is left
    out and its wavelength is returned in ``lost_wavelength_m``.

    Parameters
    ----------
    readings : ProbeReadings
        Evenly stepped, spacings whole numbers of steps, more readings than the probes span steps.
    probes : {2, 3}, keyword-only
        Probes used (default 3).
    min_gain : float, keyword-only
        Fraction of the gain envelope below which a harmonic is left out, 0 <= min_gain < 1
        (default 0.05). Harmonics where H is exactly zero are always left out.
    parabola : bool, keyword-only
        Take the parabola out in closed form first (default True).

    Returns
    -------
    Separation
        Profile at every reading; the yaw with three probes; ``lost_wavelength_m`` the wavelengths
        left out.

    Raises
    ------
    AxiscalError
        ``min_gain`` outside [0, 1), probes not 2 or 3, probe C missing for three, uneven steps,
        spacings not whole numbers of steps, or no more readings than the probes span steps.
    """
    _readings(readings)
    if not (is_real(min_gain) and 0.0 <= min_gain < 1.0):
        raise AxiscalError(f"the frequency-domain method needs 0 <= min_gain < 1, got {min_gain!r}")
    if not isinstance(parabola, (bool, np.bool_)):
        raise AxiscalError(f"parabola must be True or False, not {parabola!r}")
    x = readings.position_m
    step = _step(x, "the frequency-domain method")
    p = _steps_in(readings.spacing_ab_m, step, "the frequency-domain method", "A-B spacing")
    n_pts = x.size
    n = np.arange(n_pts, dtype=float)
    if probes == 2:
        offsets, weights = np.array([0, p]), np.array([-1.0, 1.0])
        signal = readings.b_m - readings.a_m
        curvature = np.polyfit(n, signal, 1)[0] / (2.0 * p) if parabola else 0.0
    elif probes == 3:
        c, d2 = _third_probe(readings, "the three-point frequency-domain method")
        q = p + _steps_in(d2, step, "the frequency-domain method", "B-C spacing")
        d1, d12 = readings.spacing_ab_m, readings.spacing_ab_m + d2
        offsets = np.array([0, p, q])
        weights = np.array([-d2 / d12, 1.0, -d1 / d12])
        signal = weights[0] * readings.a_m + weights[1] * readings.b_m + weights[2] * c
        second_moment = float(np.dot(weights, offsets.astype(float) ** 2))
        curvature = float(np.mean(signal)) / second_moment if parabola else 0.0
    else:
        raise AxiscalError(f"the frequency-domain method uses 2 or 3 probes, not {probes}")
    if offsets[-1] >= n_pts:
        raise AxiscalError(
            f"the frequency-domain method needs more readings than the probes span steps: the probes span "
            f"{offsets[-1]} steps of {step / MM:g} mm, the record has {n_pts} readings"
        )
    bow = curvature * n**2
    residual = signal - sum(w * curvature * (n + o) ** 2 for w, o in zip(weights, offsets))
    freq = np.arange(n_pts // 2 + 1)
    gain = (weights[None, :] * np.exp(2j * np.pi * np.outer(freq, offsets) / n_pts)).sum(axis=1)
    spectrum = np.fft.rfft(residual)
    order = 1 if probes == 2 else 2
    moment = abs(float(np.dot(weights, offsets.astype(float) ** order))) / math.factorial(order)
    envelope = np.minimum(moment * (2.0 * np.pi * freq / n_pts) ** order, np.abs(gain).max())
    usable = (np.abs(gain) >= min_gain * envelope) & (np.abs(gain) > 0.0)
    usable[0] = False
    solved = np.zeros_like(spectrum)
    solved[usable] = spectrum[usable] / gain[usable]
    profile = np.fft.irfft(solved, n=n_pts) + bow
    profile -= profile[0]
    lost = n_pts * step / freq[1:][~usable[1:]]
    name = f"frequency-{'two' if probes == 2 else 'three'}-point"
    if probes == 2:
        return _finish(name, x.copy(), profile, readings, lost=lost)
    return _finish(name, x.copy(), profile, readings, _yaw_from_profile(readings, x, profile), lost)


def combined(
    readings: ProbeReadings, *, calibration_m: tuple[float, float] | None = None
) -> Separation:
    """The combined method of paper 001, section 4, steps 1-5.

    1. Three probes with d1 = d2 = d = K s, sampled at the step s.
    2. GTP (eq 7) over all readings gives the shape z(n) at full resolution (smoothed), placed at
       the centre of the window it averages (``generalized_two_point``), not at x_n as the paper
       indexes it: that would compare the groups with a shape shifted by (d - s) / 2.
    3. The readings are split into K groups one spacing apart (group i starts at reading i); STRP
       (eq 2) on each group gives its yaw, whose mean and slope are removed (eq 15) because zero
       offsets corrupt exactly those (eq 11).
    4. STP with that yaw (eq 13) on each group gives p_ij, p_i0 = 0.
    5. Each group is lifted by b_i = mean over the calibration region of (z - p_i) (eq 18-19).

    Each group's STRP fixes its own line, so step 3 must remove each group's yaw mean; that also
    removes the true yaw's mean and slope over that group's samples. Each group spans a window
    shifted by s, so when the yaw has waves comparable to the length the fitted lines differ from
    group to group: the groups come out with their own tilts and bows (eq 17 per group), a
    saw-tooth across the interleaved profile (docs/straightness.md gives numbers).

    Parameters
    ----------
    readings : ProbeReadings
        Three probes with equal spacings, evenly stepped, the spacing a whole number of steps.
    calibration_m : (float, float), optional, keyword-only
        Positions (m) bounding the smooth region where the groups are joined to the GTP shape;
        default: everywhere z is known.

    Returns
    -------
    Separation
        Profile at every step of the groups, motion and yaw where resolved.

    Raises
    ------
    AxiscalError
        Probe C missing, unequal spacings, uneven steps, fewer than two readings per group, or a
        calibration region missing a group.
    """
    x = _readings(readings).position_m
    if calibration_m is not None:
        calibration_m = check_array("calibration_m", calibration_m, ndim=1)
        if calibration_m.shape != (2,) or not calibration_m[0] < calibration_m[1]:
            raise AxiscalError(f"calibration_m must be (start, end) in metres with start < end, not {calibration_m.tolist()}")
    c, d2 = _third_probe(readings, "the combined method")
    d = readings.spacing_ab_m
    if not abs(d2 - d) <= 1e-9 * d:
        raise AxiscalError(f"the combined method needs equal spacings (A-B {d / MM:g} mm, B-C {d2 / MM:g} mm)")
    step = _step(x, "the combined method")
    k = _steps_in(d, step, "the combined method")
    n_read = x.size
    if n_read < 2 * k:
        raise AxiscalError(f"the combined method needs at least two readings per group: {2 * k} readings, got {n_read}")
    shape = generalized_two_point(readings)
    groups = n_read // k
    used = groups * k
    # reading n = i + j K belongs to group i, chain point j: reshape to (groups, K), columns are groups
    a = readings.a_m[:used].reshape(groups, k)
    b = readings.b_m[:used].reshape(groups, k)
    cc = c[:used].reshape(groups, k)
    second = cc - 2.0 * b + a
    slope = np.vstack([np.zeros(k), np.cumsum(second, axis=0)])
    strp = np.vstack([np.zeros(k), np.cumsum(slope, axis=0)])
    yaw = (strp[1:-1] - strp[:-2] + a - b) / d
    j = np.arange(groups, dtype=float)
    jc = j - j.mean()
    yaw_slope = (jc @ (yaw - yaw.mean(axis=0))) / float(jc @ jc)
    yaw_flat = yaw - yaw.mean(axis=0) - np.outer(jc, yaw_slope)
    group_profile = np.vstack([np.zeros(k), np.cumsum(b - a + d * yaw_flat, axis=0)])
    index = (np.arange(groups + 1)[:, None] * k + np.arange(k)[None, :]).ravel()
    flat = group_profile.ravel()
    position = x[0] + step * index
    in_z = (position >= shape.position_m[0] - 1e-12) & (position <= shape.position_m[-1] + 1e-12)
    if calibration_m is not None:
        in_z &= (position >= calibration_m[0] - 1e-12) & (position <= calibration_m[1] + 1e-12)
    group_of = np.tile(np.arange(k), groups + 1)
    counts = np.bincount(group_of[in_z], minlength=k)
    if np.any(counts == 0):
        raise AxiscalError("the combined method's calibration region must hold at least one point of every group")
    z = np.interp(position[in_z], shape.position_m, shape.profile_m)
    lift = np.bincount(group_of[in_z], weights=z - flat[in_z], minlength=k) / counts
    profile = flat + lift[group_of]
    return _finish("combined", position, profile, readings, _yaw_from_profile(readings, position, profile))


def separate(
    readings: ProbeReadings,
    *,
    method: str,
    probes: int | None = None,
    min_gain: float = 0.05,
    parabola: bool = True,
    calibration_m: tuple[float, float] | None = None,
) -> Separation:
    """Run a separation method by name: ``stp``, ``strp``, ``fstrp``, ``gtp``, ``frequency``, ``combined``.

    Parameters
    ----------
    readings : ProbeReadings
        The readings (see each method for what it needs).
    method : {"stp", "strp", "fstrp", "gtp", "frequency", "combined"}, keyword-only
        The method.
    probes : {2, 3}, optional, keyword-only
        Frequency method only: probes used (default: 3 when probe C is present, else 2).
    min_gain, parabola : keyword-only
        Frequency method only, see :func:`frequency_domain`.
    calibration_m : (float, float), optional, keyword-only
        Combined method only, see :func:`combined`.

    Returns
    -------
    Separation

    Raises
    ------
    AxiscalError
        An unknown method, or readings the method refuses (see each method).

    Examples
    --------
    >>> import numpy as np
    >>> x = np.arange(0, 31) * 1e-3
    >>> data = simulate_readings(x, lambda p: 1e-3 * (p - 0.02) ** 2, lambda p: 0 * p,
    ...                          spacing_ab_m=5e-3, spacing_bc_m=5e-3)
    >>> separate(data, method="strp").method
    'strp'
    """
    if not isinstance(method, str) or method not in METHODS:
        raise AxiscalError(f"unknown separation method {method!r}; use one of {', '.join(METHODS)}")
    _readings(readings)
    if probes is not None and method == "frequency":
        probes = check_count("probes", probes, minimum=2, maximum=3)
    if method == "stp":
        return sequential_two_point(readings)
    if method == "strp":
        return sequential_three_point(readings)
    if method == "fstrp":
        return fine_sequential_three_point(readings)
    if method == "gtp":
        return generalized_two_point(readings)
    if method == "frequency":
        chosen = probes if probes is not None else (3 if readings.c_m is not None else 2)
        return frequency_domain(readings, probes=chosen, min_gain=min_gain, parabola=parabola)
    if method == "combined":
        return combined(readings, calibration_m=calibration_m)
    raise AxiscalError(f"unknown separation method '{method}'; use one of {', '.join(METHODS)}")


# ---------------------------------------------------------------------------------------------
# error analysis (closed forms; the tests check each against simulation)


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


@dataclass(frozen=True)
class NoisePropagation:
    """How independent probe noise propagates through a method (Monte Carlo).

    Attributes
    ----------
    method : str
        Name of the method.
    position_m : ndarray, shape (n,)
        Positions of the separated profile, metres.
    std_m : ndarray, shape (n,)
        Standard deviation of the separated profile at each position about each run's
        least-squares line, metres.
    mean_pv_m : float
        Mean peak-to-valley of the separated profile about its least-squares line, metres: the
        straightness a perfect workpiece on a perfect slide would show.
    """

    method: str
    position_m: np.ndarray
    std_m: np.ndarray
    mean_pv_m: float


def noise_propagation(
    readings: ProbeReadings, *, method: str, noise_m: float, trials: int = 1000, rng: np.random.Generator | None = None
) -> NoisePropagation:
    """Separate pure noise (R = S = gamma = 0, every reading N(0, noise_m^2)) ``trials`` times.

    Every method is linear in the readings, so this is exactly the noise part of any separation
    with this set-up. ``readings`` supplies the positions and spacings (its values are ignored);
    ``method`` is a name accepted by :func:`separate`, or ``"reversal"`` (two runs of probe A).

    Parameters
    ----------
    readings : ProbeReadings
        The set-up: positions and spacings.
    method : str, keyword-only
        A method of :func:`separate`, or ``"reversal"``.
    noise_m : float, keyword-only
        Standard deviation of each reading, metres.
    trials : int, keyword-only
        Number of noisy separations (default 1000).
    rng : numpy.random.Generator, optional, keyword-only
        Source of the noise (default ``np.random.default_rng(0)``).

    Returns
    -------
    NoisePropagation

    Raises
    ------
    AxiscalError
        A method the set-up does not allow (see :func:`separate`).
    """
    check_choice("separation method", method, ("reversal", *METHODS))
    x = _readings(readings).position_m
    noise_m = check_number("noise_m", noise_m, positive=True)
    trials = check_count("trials", trials, minimum=2)
    rng = _rng(rng)
    residuals = []
    for _ in range(trials):
        a, b, c = noise_m * rng.standard_normal((3, x.size))
        if method == "reversal":
            result = reversal(x, a, b)
        else:
            noisy = ProbeReadings(x, a, b, None if readings.c_m is None else c, readings.spacing_ab_m, readings.spacing_bc_m)
            result = separate(noisy, method=method)
        pos, prof = result.position_m, result.profile_m
        slope, offset = np.polyfit(pos - pos.mean(), prof, 1)
        residuals.append(prof - (slope * (pos - pos.mean()) + offset))
    runs = np.array(residuals)
    return NoisePropagation(result.method, pos, runs.std(axis=0), float(np.ptp(runs, axis=1).mean()))
