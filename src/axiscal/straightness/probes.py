"""Multi-probe error separation, its set-up and its result: probe readings, the separation, simulated readings and the checks every method makes (paper 001).

Probe A sits at the position x, probe B at x + d1 and probe C at x + d1 + d2 on a carriage that
moves along the workpiece; with probe zero offsets xi (eq 8) they read (eq 1)::

    a(x) = R(x)           - S(x)                   - xi_a
    b(x) = R(x + d1)      - S(x) - d1 gamma(x)       - xi_b
    c(x) = R(x + d1 + d2) - S(x) - (d1 + d2) gamma(x) - xi_c

The methods (:mod:`axiscal.straightness.sequential`, :mod:`axiscal.straightness.frequency`,
:mod:`axiscal.straightness.separation`) take :class:`ProbeReadings` and return a :class:`Separation`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_number, check_same_length, is_real
from axiscal.units import MM

__all__ = [
    "METHODS",
    "ProbeReadings",
    "Separation",
    "simulate_readings",
    "uneven_step",
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
