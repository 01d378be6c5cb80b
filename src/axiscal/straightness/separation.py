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

This module is the room's entry to separation: :func:`separate` (by method name), :func:`combined`
and :func:`noise_propagation` are here, and every name of the modules it builds on is importable
from here: the set-up and result (:mod:`axiscal.straightness.probes`), the point-by-point methods
(:mod:`axiscal.straightness.sequential`), the frequency-domain method
(:mod:`axiscal.straightness.frequency`) and the closed-form error analysis
(:mod:`axiscal.straightness.error_analysis`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_count, check_number
from axiscal.straightness.error_analysis import (
    gtp_noise_std,
    stp_noise_std,
    stp_offset_error,
    stp_residual_yaw_error,
    stp_yaw_neglect_error,
    strp_noise_std,
    strp_offset_error,
    strp_yaw_offset_error,
)
from axiscal.straightness.frequency import frequency_domain
from axiscal.straightness.probes import (
    METHODS,
    ProbeReadings,
    Separation,
    _finish,
    _readings,
    _rng,
    _step,
    _steps_in,
    _third_probe,
    _yaw_from_profile,
    simulate_readings,
    uneven_step,
)
from axiscal.straightness.sequential import (
    fine_sequential_three_point,
    generalized_two_point,
    gtp_amplitude_response,
    reversal,
    sequential_three_point,
    sequential_two_point,
)
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
