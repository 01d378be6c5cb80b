"""Machine errors read from a ballbar trace: squareness, scale mismatch, backlash, reversal spikes, cyclic error, servo mismatch.

To first order a point of the path that is off by (e1, e2) along the plane's axes reads
``dR = e1 cos(a) + e2 sin(a)`` (the first-order radial model of the ballbar literature, e.g.
Bryan 1982, Kakino et al. 1987). Each error has its own signature in
``dR(a)``; the trace is fitted to all of them at once by linear least squares (see
docs/ballbar.md for the derivation of every term and its sign):

- centre offset (c1, c2): ``c1 cos a + c2 sin a`` (each direction its own);
- scale mismatch s1 - s2: ``R (s1 - s2)/2 cos 2a``;
- squareness (included angle of +first and +second minus 90 deg) q: ``-R q/2 sin 2a``;
- servo mismatch (lag of the first axis minus that of the second) t: ``+-F t/2 sin 2a``, the sign
  that of the direction (F the feed), so q comes from the mean of the two directions' sin 2a
  terms and t from their difference;
- backlash b of an axis: a step of b outwards where that axis reverses;
- reversal spike: the largest residual just after a reversal, in the direction of travel;
- cyclic error: a sinusoid of an axis' own position, ``e1 = c sin(2 pi x1 / p + phi)``, its pitch p
  found by a least-squares periodogram of the residual.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from axiscal.circular.evaluation import BallbarTrace
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_instance, check_same_length, is_real
from axiscal.units import MM, UM

__all__ = [
    "SPIKE_WINDOW_DEG",
    "MIN_PITCH_M",
    "SERVO_WARNING",
    "BallbarDiagnostics",
    "reversal_angles",
    "backlash_signature",
    "diagnose",
]

#: the arc after each reversal (deg) in which the spike is sought; it is left out of the fit
SPIKE_WINDOW_DEG = 10.0
#: the shortest pitch of a cyclic error looked for, metres
MIN_PITCH_M = 1.0 * MM
#: said when only one direction was measured (squareness and servo mismatch cannot be told apart)
SERVO_WARNING = (
    "one direction only: squareness and servo mismatch both show as a sin 2a term and cannot be told"
    " apart; the squareness assumes no servo mismatch"
)


@dataclass(frozen=True)
class BallbarDiagnostics:
    """The machine errors read from a ballbar trace (SI units; per-axis values keyed by axis letter).

    Attributes
    ----------
    squareness : float, radians
        Included angle between the positive first and second axis minus 90 degrees.
    scale_mismatch : float
        Scale error of the first axis minus that of the second (dimensionless; 1e-6 is 1 ppm).
    backlash : dict of str to float, metres
        Lost motion of each axis on reversal (positive: the trace steps outwards).
    reversal_spike : dict of str to dict of str to float, metres
        Per axis, per direction measured: the spike height after that axis' reversals (mean of
        its two reversal points), measured from the fitted trace (positive: outwards).
    cyclic_error : dict of str to float, metres
        Amplitude of the cyclic error found along each axis.
    cyclic_pitch : dict of str to float, metres
        Its pitch (period in the axis' position); NaN when the amplitude is within what the
        noise of the trace alone would give.
    servo_mismatch : float, seconds
        Lag of the first axis minus lag of the second; NaN without both directions and a feed.
    residual_rms : float, metres
        Root mean square of what the fit leaves (outside the spike windows).
    warnings : tuple of str
    """

    squareness: float
    scale_mismatch: float
    backlash: dict[str, float]
    reversal_spike: dict[str, dict[str, float]]
    cyclic_error: dict[str, float]
    cyclic_pitch: dict[str, float]
    servo_mismatch: float
    residual_rms: float
    warnings: tuple[str, ...] = ()



def reversal_angles(axis: int) -> tuple[float, float]:
    """Angles at which an axis of the plane reverses its direction of motion on the circle.

    Parameters
    ----------
    axis : int
        0 for the plane's first axis, 1 for its second.

    Returns
    -------
    tuple of float, radians
        (0, pi) for the first axis, (pi/2, 3 pi/2) for the second.

    Examples
    --------
    >>> [round(math.degrees(a)) for a in reversal_angles(1)]
    [90, 270]
    """
    axis = check_count("axis", axis, minimum=0, maximum=1)
    return (0.0, math.pi) if axis == 0 else (math.pi / 2, 3 * math.pi / 2)


def backlash_signature(angles: np.ndarray, signs: np.ndarray, axis: int) -> np.ndarray:
    """The radial deviation caused by a backlash of 2 (any unit) of one axis: steps of 2 outwards at its reversals.

    The axis lags its command by half the backlash against its direction of motion, ``e = -b/2
    sign(v)``; for the first axis, moving as ``-sign sin(a)``, that reads
    ``dR = (b/2) sign * sign(sin a) cos a``; for the second ``dR = -(b/2) sign * sign(cos a) sin a``.

    Parameters
    ----------
    angles : ndarray, shape (n,), radians
    signs : ndarray, shape (n,)
        +1 for ccw points, -1 for cw.
    axis : int
        0 for the plane's first axis, 1 for its second.

    Returns
    -------
    ndarray, shape (n,)
        ``dR`` per unit of b/2.
    """
    axis = check_count("axis", axis, minimum=0, maximum=1)
    a = check_array("angles", angles, ndim=1, unit="radians")
    signs = check_array("signs", signs, ndim=1, unit="")
    check_same_length(angles=a, signs=signs)
    if not np.all(np.abs(signs) == 1.0):
        raise AxiscalError("signs must be +1 (ccw) or -1 (cw) for every point")
    if axis == 0:
        return signs * np.sign(np.sin(a)) * np.cos(a)
    return -signs * np.sign(np.cos(a)) * np.sin(a)


def _spike_windows(angles: np.ndarray, signs: np.ndarray, width: float) -> dict[tuple[int, str, int], np.ndarray]:
    """Rows within ``width`` after each reversal in the direction of travel, per (axis, direction, point)."""
    out = {}
    for axis in (0, 1):
        for point, at in enumerate(reversal_angles(axis)):
            after = np.mod(signs * (angles - at), 2 * math.pi)  # angle travelled since the reversal
            for d, sign in (("ccw", 1.0), ("cw", -1.0)):
                rows = np.flatnonzero((signs == sign) & (after < width))
                if rows.size:
                    out[(axis, d, point)] = rows
    return out


def _model(trace: BallbarTrace) -> tuple[np.ndarray, list[str]]:
    """Design matrix: per direction 1, cos a, sin a, cos 2a, sin 2a; then both axes' backlash steps."""
    a = trace.angles
    signs = trace.signs
    columns, names = [], []
    for d in trace.present:
        mask = np.zeros(a.size)
        mask[trace.rows(d)] = 1.0
        for name, f in (("r0", np.ones_like(a)), ("c1", np.cos(a)), ("c2", np.sin(a)),
                        ("cos2", np.cos(2 * a)), ("sin2", np.sin(2 * a))):
            columns.append(mask * f)
            names.append(f"{name}_{d}")
    for axis in (0, 1):
        columns.append(backlash_signature(a, signs, axis))
        names.append(f"backlash_{axis}")
    return np.column_stack(columns), names


class _CyclicBasis:
    """sin and cos of 2 pi k x (x the axis' position) times the radial projection of the axis, per wavenumber k."""

    def __init__(self, angles: np.ndarray, radius: float, axis: int):
        self.proj = np.cos(angles) if axis == 0 else np.sin(angles)
        self.x = radius * self.proj

    def __call__(self, wavenumber: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        phase = 2 * math.pi * np.outer(self.x, wavenumber)
        return self.proj[:, None] * np.sin(phase), self.proj[:, None] * np.cos(phase)


def _fit_amplitude(residual: np.ndarray, s: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Least-squares amplitudes of ``alpha s + beta c`` for each column; the sum of squares each explains."""
    ss, cc, sc = (s * s).sum(0), (c * c).sum(0), (s * c).sum(0)
    rs, rc = (residual[:, None] * s).sum(0), (residual[:, None] * c).sum(0)
    det = ss * cc - sc * sc
    det = np.where(det > 0, det, np.inf)
    alpha = (cc * rs - sc * rc) / det
    beta = (ss * rc - sc * rs) / det
    return alpha, beta, alpha * rs + beta * rc


def _pitch_search(trace: BallbarTrace, residual: np.ndarray, keep: np.ndarray, axis: int) -> tuple[float, float, int]:
    """Wavenumber (1/m) of the strongest cyclic error of one axis in ``residual`` (a periodogram), the grid step, the pitches tried."""
    radius = trace.radius
    k_min, k_max = 2.0 / radius, 1.0 / MIN_PITCH_M
    step = 1.0 / (16.0 * radius)  # a quarter of the wavenumber resolution of a record 4 R long
    grid = np.arange(k_min, max(k_max, k_min + step), step)
    basis = _CyclicBasis(trace.angles[keep], radius, axis)
    r = residual[keep]
    explained = np.zeros(grid.size)
    for start in range(0, grid.size, 256):
        explained[start : start + 256] = _fit_amplitude(r, *basis(grid[start : start + 256]))[2]
    return float(grid[int(np.argmax(explained))]), step, int(grid.size)


def _joint_fit(design: np.ndarray, trace: BallbarTrace, keep: np.ndarray, y: np.ndarray, wavenumbers: list[float]):
    """Least squares of the model plus a cyclic error of each axis at the given wavenumbers: coefficients, full design, sum of squares."""
    columns = [design]
    for axis, k in enumerate(wavenumbers):
        s, c = _CyclicBasis(trace.angles, trace.radius, axis)(np.array([k]))
        columns.extend([s, c])
    full = np.column_stack(columns)
    a = full[keep]
    # normal equations: the columns are harmonics, steps and sinusoids of order one, well conditioned
    coef = np.linalg.solve(a.T @ a, a.T @ y[keep])
    r = y[keep] - a @ coef
    return coef, full, float(r @ r)


def diagnose(trace: BallbarTrace, *, feed: float | None = None, spike_window: float = math.radians(SPIKE_WINDOW_DEG)) -> BallbarDiagnostics:
    """Read squareness, scale mismatch, backlash, reversal spikes, cyclic error and servo mismatch from a trace.

    Parameters
    ----------
    trace : BallbarTrace
        One or both directions of a full circle.
    feed : float, optional, m/s
        The feed (tangential speed) of the test; needed, with both directions, for the servo
        mismatch.
    spike_window : float, radians, keyword-only
        Arc after each axis reversal searched for the spike and left out of the fit.

    Returns
    -------
    BallbarDiagnostics

    Raises
    ------
    AxiscalError
        If ``feed`` is given but not a positive speed, or the spike window is not between 0 and
        45 degrees.

    Examples
    --------
    >>> a = np.radians(np.arange(0.05, 360.0, 0.5))
    >>> q = 20e-6  # included angle 20 urad over 90 deg
    >>> t = BallbarTrace(a, ("ccw",) * a.size, -0.1 * q / 2 * np.sin(2 * a), radius=0.1)
    >>> round(diagnose(t).squareness * 1e6, 3)
    20.0
    """
    check_instance("trace", trace, BallbarTrace, what="a BallbarTrace")
    if feed is not None and not (is_real(feed) and math.isfinite(feed) and feed > 0):
        raise AxiscalError(f"the feed must be a positive speed, got {feed!r} m/s")
    if not (is_real(spike_window) and 0 < spike_window < math.pi / 4):
        raise AxiscalError(f"the spike window (spike_window) must be between 0 and 45 deg, got {spike_window!r} rad")
    R = trace.radius
    a, signs, y = trace.angles, trace.signs, trace.deviations
    windows = _spike_windows(a, signs, spike_window)
    keep = np.ones(a.size, dtype=bool)
    for rows in windows.values():
        keep[rows] = False
    design, names = _model(trace)
    column = {n: i for i, n in enumerate(names)}
    letters = trace.axes
    # the model first; then the strongest cyclic error of each axis in what it leaves; then all together,
    # each pitch refined on the joint fit
    coef, *_ = np.linalg.lstsq(design[keep], y[keep], rcond=None)
    residual = y - design @ coef
    wavenumbers, steps, tried = [], [], []
    for axis in (0, 1):
        k, step, count = _pitch_search(trace, residual, keep, axis)
        tried.append(count)
        wavenumbers.append(k)
        steps.append(step)
        s, c = _CyclicBasis(trace.angles[keep], R, axis)(np.array([k]))
        alpha, beta, _ = _fit_amplitude(residual[keep], s, c)
        residual[keep] -= alpha[0] * s[:, 0] + beta[0] * c[:, 0]
    for _ in range(2):
        for axis in (0, 1):
            def cost(k: float, axis: int = axis) -> float:
                trial = list(wavenumbers)
                trial[axis] = k
                return _joint_fit(design, trace, keep, y, trial)[2]

            found = minimize_scalar(
                cost,
                bounds=(wavenumbers[axis] - steps[axis], wavenumbers[axis] + steps[axis]),
                method="bounded",
                options={"xatol": steps[axis] * 1e-4},
            )
            wavenumbers[axis] = float(found.x)
    coef, full, _ = _joint_fit(design, trace, keep, y, wavenumbers)
    residual = y - full @ coef
    n = design.shape[1]
    cyclic_error = {letters[axis]: float(math.hypot(coef[n + 2 * axis], coef[n + 2 * axis + 1])) for axis in (0, 1)}
    # noise alone gives the best of M pitches an amplitude of about se sqrt(2 ln M) (se: the standard error
    # of one amplitude); below twice that the pitch found means nothing and is not given
    sigma = float(np.sqrt(np.mean(residual[keep] ** 2)))
    cyclic_pitch = {}
    for axis in (0, 1):
        proj = np.cos(a[keep]) if axis == 0 else np.sin(a[keep])
        se = sigma / math.sqrt(max(float(proj @ proj) / 2.0, 1.0))
        floor = max(2.0 * se * math.sqrt(2.0 * math.log(max(tried[axis], 2))), 1e-4 * UM)  # and 0.1 nm of rounding
        found_pitch = 1.0 / wavenumbers[axis]
        cyclic_pitch[letters[axis]] = found_pitch if cyclic_error[letters[axis]] > floor else math.nan

    sin2 = [coef[column[f"sin2_{d}"]] for d in trace.present]
    cos2 = [coef[column[f"cos2_{d}"]] for d in trace.present]
    squareness = -2.0 * float(np.mean(sin2)) / R
    scale = 2.0 * float(np.mean(cos2)) / R
    warnings = []
    servo = math.nan
    if len(trace.present) == 1:
        warnings.append(SERVO_WARNING)
    elif feed is not None:
        servo = float(coef[column["sin2_ccw"]] - coef[column["sin2_cw"]]) / feed
    backlash = {letters[axis]: 2.0 * float(coef[column[f"backlash_{axis}"]]) for axis in (0, 1)}
    spikes: dict[str, dict[str, float]] = {}
    for axis in (0, 1):
        per: dict[str, float] = {}
        for d in trace.present:
            heights = []
            for point in (0, 1):
                rows = windows.get((axis, d, point))
                if rows is None:
                    continue
                r = residual[rows]
                heights.append(float(r[int(np.argmax(np.abs(r)))]))
            per[d] = float(np.mean(heights)) if heights else math.nan
        spikes[letters[axis]] = per
    return BallbarDiagnostics(
        squareness=squareness,
        scale_mismatch=scale,
        backlash=backlash,
        reversal_spike=spikes,
        cyclic_error=cyclic_error,
        cyclic_pitch=cyclic_pitch,
        servo_mismatch=servo,
        residual_rms=float(np.sqrt(np.mean(residual[keep] ** 2))),
        warnings=tuple(warnings),
    )

