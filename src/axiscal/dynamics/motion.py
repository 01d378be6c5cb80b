"""Dynamics of an axis from a laser's timebase recording: velocity, acceleration and jerk, moves and stops.

What laser software calls a timebase (dynamic) capture: the reading sampled at a steady rate while
the axis moves and stops. From it:

- **Derivatives** by a Savitzky-Golay smoothing differentiator (Savitzky and Golay, Analytical
  Chemistry 36, 1964): a polynomial of degree ``polyorder`` fitted by least squares over a window
  of ``window_s`` around each sample, differentiated. Its bandwidth is stated: the frequency at
  which the smoothing filter's gain has fallen to 1/sqrt(2) (-3 dB), computed from its own
  coefficients (Schafer, "What is a Savitzky-Golay filter?", IEEE Signal Processing Magazine 28(4),
  2011, gives ``f_c ~ (N + 1) / (3.2 M - 4.6) * f_s / 2`` for a window of ``2M + 1`` samples).
- **Moves**: where the speed exceeds ``moving_m_s``; each move's largest speed, acceleration and
  jerk.
- **Stops**: from the end of a move to the start of the next. The final value is the mean of the
  stop's last ``final_window_s``; the settling time is the time from the end of
  the move until the reading last leaves the band ``final +/- band_m``; the overshoot is how far
  the reading went past the final value in the direction of travel; the ringing frequency ``f_d``
  and the decay time ``tau`` come from a damped sine fitted by least squares to the stop's start,
  ``x = final + A exp(-t / tau) sin(2 pi f_d t + phi)``, and the damping ratio of the equivalent
  second-order system is ``zeta = sigma / sqrt(sigma^2 + (2 pi f_d)^2)`` with ``sigma = 1 / tau``.
- **Spectrum**: Welch's averaged periodogram (Welch, IEEE Trans. Audio Electroacoustics 15, 1967)
  of the reading with each segment's straight line removed, as an amplitude spectral density;
  over the stops, where the axis rests and its vibration is not hidden by its moves (over the
  whole recording where there is no stop).

Samples not evenly spaced (a live record's jitter) are first interpolated onto an even grid at the
median interval; the result says so. Two samples at one time, a gap longer than the
differentiator's window (its derivatives there would be those of the straight line drawn across
it) and a grid more than twice as long as the samples (most of it made up) are refused before
anything is allocated.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_number

__all__ = [
    "Derivatives",
    "Spectrum",
    "MoveDynamics",
    "StopDynamics",
    "savgol_bandwidth_hz",
    "derivatives",
    "welch_spectrum",
]


@dataclass(frozen=True)
class Derivatives:
    """Position and its derivatives on an even time grid.

    Attributes
    ----------
    time_s : ndarray, shape (n,), seconds
    reading_m : ndarray, shape (n,), metres
        The reading at those times (interpolated where the samples were not evenly spaced).
    position_m : ndarray, shape (n,), metres
        The smoothed position.
    velocity_m_s, acceleration_m_s2, jerk_m_s3 : ndarray, shape (n,)
        Its first three derivatives.
    window_s : float, seconds
        The differentiator's window.
    polyorder : int
        Degree of its polynomial.
    bandwidth_hz : float, hertz
        The -3 dB frequency of its smoothing filter.
    resampled : bool
        True when the samples were interpolated onto an even grid first.
    """

    time_s: np.ndarray
    reading_m: np.ndarray
    position_m: np.ndarray
    velocity_m_s: np.ndarray
    acceleration_m_s2: np.ndarray
    jerk_m_s3: np.ndarray
    window_s: float
    polyorder: int
    bandwidth_hz: float
    resampled: bool


@dataclass(frozen=True)
class Spectrum:
    """Welch's amplitude spectral density of the reading.

    Attributes
    ----------
    frequency_hz : ndarray, shape (k,), hertz
    density_m_rthz : ndarray, shape (k,), metres per root hertz
    segment_s : float, seconds
        Length of Welch's segments (Hann window, half overlap).
    resolution_hz : float, hertz
        Frequency step (1 / segment).
    peak_hz : float, hertz
        Frequency of the largest density above the lowest two bins (NaN when there are none).
    over : str
        ``"recording"`` (the whole reading) or ``"stops"`` (averaged over the stops, where the
        axis rests and its vibration is not hidden by its moves).
    """

    frequency_hz: np.ndarray
    density_m_rthz: np.ndarray
    segment_s: float
    resolution_hz: float
    peak_hz: float
    over: str = "recording"


@dataclass(frozen=True)
class MoveDynamics:
    """One move of the axis.

    Attributes
    ----------
    start_s, end_s : float, seconds
        When the speed rose above and fell below the moving threshold.
    from_m, to_m : float, metres
        The reading at the start and at the end.
    peak_velocity_m_s, peak_acceleration_m_s2, peak_jerk_m_s3 : float
        Largest magnitudes over the move (acceleration and jerk over the move and its braking).
    direction : str
        ``"+"`` or ``"-"``: the sign of the velocity.
    """

    start_s: float
    end_s: float
    from_m: float
    to_m: float
    peak_velocity_m_s: float
    peak_acceleration_m_s2: float
    peak_jerk_m_s3: float
    direction: str


@dataclass(frozen=True)
class StopDynamics:
    """How the axis came to rest after one move.

    Attributes
    ----------
    arrival_s, departure_s : float, seconds
        End of the move before, start of the move after (the recording's end for the last stop).
    final_m : float, metres
        Mean reading over the stop's last window.
    settling_s : float, seconds
        Time from arrival until the reading last left the band (0 when it never left it; NaN when
        it was still outside at the final window).
    overshoot_m : float, metres
        Largest excursion past the final value in the direction of travel (>= 0).
    ringing_hz : float, hertz
        Frequency of the fitted damped sine (NaN when no ringing is resolved).
    decay_s : float, seconds
        Its decay time constant (NaN likewise).
    damping_ratio : float
        ``sigma / sqrt(sigma^2 + (2 pi f)^2)`` (NaN likewise).
    direction : str
        ``"+"`` or ``"-"``: the direction of the move that ended here.
    step : int or None
        The plan's step this stop is at (None without a plan or where no step matches).
    """

    arrival_s: float
    departure_s: float
    final_m: float
    settling_s: float
    overshoot_m: float
    ringing_hz: float
    decay_s: float
    damping_ratio: float
    direction: str
    step: int | None = None


def savgol_bandwidth_hz(window: int, polyorder: int, rate_hz: float) -> float:
    """The -3 dB frequency of a Savitzky-Golay smoothing filter, from its coefficients.

    Parameters
    ----------
    window : int
        Window length in samples (odd, > polyorder).
    polyorder : int
        Degree of the polynomial.
    rate_hz : float, hertz
        Sample rate.

    Returns
    -------
    float, hertz
        The lowest frequency at which the filter's gain is 1/sqrt(2).

    Raises
    ------
    AxiscalError
        For a window that is even, not above the order, or a rate that is not positive.

    Examples
    --------
    >>> round(savgol_bandwidth_hz(21, 3, 1000.0), 1)
    50.9
    """
    window = check_count("window", window, minimum=3)
    polyorder = check_count("polyorder", polyorder, minimum=0)
    rate_hz = check_number("rate_hz", rate_hz, positive=True, unit="Hz")
    if window % 2 == 0 or window <= polyorder:
        raise AxiscalError(f"window must be an odd number of samples above polyorder ({polyorder}), not {window}")
    return _bandwidth(window, polyorder, rate_hz)


def _bandwidth(window: int, polyorder: int, rate_hz: float) -> float:
    from scipy.signal import savgol_coeffs

    h = savgol_coeffs(window, polyorder)
    m = (window - 1) // 2
    k = np.arange(-m, m + 1)
    f = np.linspace(0.0, 0.5, 2049)
    gain = np.abs(np.cos(2 * np.pi * np.outer(f, k)) @ h)  # symmetric filter: a real response
    below = np.flatnonzero(gain < 1 / math.sqrt(2))
    if below.size == 0:
        return rate_hz / 2
    i = int(below[0])
    # linear interpolation between the grid points either side of the crossing
    f0, f1, g0, g1 = f[i - 1], f[i], gain[i - 1], gain[i]
    return float((f0 + (1 / math.sqrt(2) - g0) * (f1 - f0) / (g1 - g0)) * rate_hz)


#: the even grid may hold at most this many times the samples recorded
_GRID_LIMIT = 2


def _window_samples(window_s: float, polyorder: int, step: float) -> int:
    """The differentiator's window in samples: odd, at least ``polyorder + 2``."""
    return max(int(round(window_s / step)) // 2 * 2 + 1, (polyorder + 2) // 2 * 2 + 1)


def _time_problem(t: np.ndarray, window_s: float | None = None, polyorder: int = 3) -> tuple[int, str] | None:
    """The first sample whose time the differentiator or the spectrum cannot use, and why; None when all are usable.

    Parameters
    ----------
    t : ndarray, shape (n,), seconds
        Sample times, not going back (at least 2).
    window_s : float, optional
        The differentiator's window: a gap longer than it is refused (no gap bound without it).
    polyorder : int
        Its degree.

    Returns
    -------
    (int, str) or None
        The index of the sample at fault and the problem, in words that name the times.
    """
    dt = np.diff(t)
    same = np.flatnonzero(dt == 0)
    if same.size:
        k = int(same[0]) + 1
        return k, f"the time {t[k]:g} s is given twice: two samples at one time"
    step = float(np.median(dt))
    if window_s is not None:
        span = _window_samples(window_s, polyorder, step) * step
        gap = np.flatnonzero(dt > span)
        if gap.size:
            k = int(gap[0]) + 1
            return k, (f"the time jumps from {t[k - 1]:g} s to {t[k]:g} s: a gap of {dt[k - 1]:g} s, longer than the "
                       f"differentiator's window ({span:g} s), would be differentiated as a straight line")
    count = (t[-1] - t[0]) / step + 1
    if count > _GRID_LIMIT * t.size:
        k = int(np.argmax(dt)) + 1
        return k, (f"the samples span {t[-1] - t[0]:g} s at {step:g} s apart ({count:.3g} samples of an even grid for "
                   f"{t.size} recorded; the largest gap, {dt[k - 1]:g} s, ends here): most of it would be made up")
    return None


def _even(time_s: np.ndarray, reading_m: np.ndarray) -> tuple[np.ndarray, np.ndarray, float, bool]:
    dt = np.diff(time_s)
    step = float(np.median(dt))
    if not step > 0:
        raise AxiscalError("the recording's times do not advance: its samples need distinct times")
    if np.all(np.abs(dt - step) <= 1e-3 * step):
        return time_s, reading_m, step, False
    grid = time_s[0] + step * np.arange(int(math.floor((time_s[-1] - time_s[0]) / step)) + 1)
    return grid, np.interp(grid, time_s, reading_m), step, True


def derivatives(time_s: Any, reading_m: Any, *, window_s: float = 0.02, polyorder: int = 3) -> Derivatives:
    """Velocity, acceleration and jerk of a reading by a Savitzky-Golay smoothing differentiator.

    Parameters
    ----------
    time_s : array_like, shape (n,), seconds
        Sample times, increasing.
    reading_m : array_like, shape (n,), metres
        The reading.
    window_s : float, seconds, keyword-only
        The differentiator's window (default 20 ms); rounded to an odd number of samples, at
        least ``polyorder + 2`` (the window used is the result's ``window_s``).
    polyorder : int, keyword-only
        Degree of the fitted polynomial (default 3, the least that gives a jerk).

    Returns
    -------
    Derivatives

    Raises
    ------
    AxiscalError
        For arrays of different lengths, times that go back, two samples at one time, a gap longer
        than the window, samples too sparse for an even grid, or a window longer than the recording.
    """
    t = check_array("time_s", time_s, ndim=1, min_len=2, unit="s")
    x = check_array("reading_m", reading_m, ndim=1, unit="m")
    if x.size != t.size:
        raise AxiscalError(f"reading_m must hold one reading per time ({t.size}), not {x.size}")
    if np.any(np.diff(t) < 0):
        raise AxiscalError("time_s must not go back")
    window_s = check_number("window_s", window_s, positive=True, unit="s")
    polyorder = check_count("polyorder", polyorder, minimum=3, maximum=7)
    problem = _time_problem(t, window_s, polyorder)
    if problem is not None:
        raise AxiscalError(f"time_s[{problem[0]}]: {problem[1]}")
    return _derivatives(t, x, window_s, polyorder)


def _derivatives(t: np.ndarray, x: np.ndarray, window_s: float, polyorder: int) -> Derivatives:
    from scipy.signal import savgol_filter

    t, x, step, resampled = _even(t, x)
    # an odd number of samples, at least polyorder + 2 (the window used is in the result, with its bandwidth)
    window = _window_samples(window_s, polyorder, step)
    if window > x.size:
        raise AxiscalError(f"window_s ({window_s:g} s) is longer than the recording ({x.size} samples)")
    out = [savgol_filter(x, window, polyorder, deriv=k, delta=step, mode="interp") for k in range(4)]
    return Derivatives(t, x, out[0], out[1], out[2], out[3], window * step, polyorder,
                       _bandwidth(window, polyorder, 1 / step), resampled)


def welch_spectrum(time_s: Any, reading_m: Any, *, segment_s: float = 1.0) -> Spectrum:
    """Welch's amplitude spectral density of a reading (Hann segments, half overlap, lines removed).

    Parameters
    ----------
    time_s : array_like, shape (n,), seconds
    reading_m : array_like, shape (n,), metres
    segment_s : float, seconds, keyword-only
        Length of a segment (default 1 s; the whole recording when it is shorter).

    Returns
    -------
    Spectrum

    Raises
    ------
    AxiscalError
        For arrays of different lengths, fewer than 8 samples, times that go back, two samples at
        one time, samples too sparse for an even grid, or a segment that is not positive.
    """
    t = check_array("time_s", time_s, ndim=1, min_len=8, unit="s")
    x = check_array("reading_m", reading_m, ndim=1, unit="m")
    if x.size != t.size:
        raise AxiscalError(f"reading_m must hold one reading per time ({t.size}), not {x.size}")
    if np.any(np.diff(t) < 0):
        raise AxiscalError("time_s must not go back")
    segment_s = check_number("segment_s", segment_s, positive=True, unit="s")
    problem = _time_problem(t)
    if problem is not None:
        raise AxiscalError(f"time_s[{problem[0]}]: {problem[1]}")
    t, x, step, _ = _even(t, x)
    return _welch(x, step, segment_s)


def _welch(x: np.ndarray, step: float, segment_s: float) -> Spectrum:
    return _welch_pieces([x], step, segment_s, "recording")


def _welch_pieces(pieces: list[np.ndarray], step: float, segment_s: float, over: str) -> Spectrum:
    """Welch's density averaged over pieces of a reading (each piece's periodogram weighted by its length)."""
    from scipy.signal import welch

    n = int(min(min(p.size for p in pieces), max(8, round(segment_s / step))))
    total, weight = None, 0
    for piece in pieces:
        f, p = welch(piece, fs=1 / step, window="hann", nperseg=n, detrend="linear", scaling="density")
        total = p * piece.size if total is None else total + p * piece.size
        weight += piece.size
    density = np.sqrt(total / weight)
    peak = float(f[2 + int(np.argmax(density[2:]))]) if f.size > 2 else math.nan
    return Spectrum(f, density, n * step, float(f[1] - f[0]) if f.size > 1 else math.nan, peak, over)


def _damped_sine(t: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Frequency (Hz) and decay time (s) of ``y ~ A exp(-t/tau) sin(2 pi f t + phi)`` (NaN, NaN if none)."""
    from scipy.optimize import least_squares

    if y.size < 8 or not np.any(y):
        return math.nan, math.nan
    # the starting frequency: the peak of the zero-padded spectrum (noise crossings in the decayed tail would mislead a count)
    step = float(t[1] - t[0])
    n = 16 * y.size
    spectrum = np.abs(np.fft.rfft(y - y.mean(), n))
    freq = np.fft.rfftfreq(n, step)
    low = max(1, int(np.searchsorted(freq, 2.0 / (t[-1] - t[0]))))
    if low >= freq.size - 1:
        return math.nan, math.nan
    f0 = float(freq[low + int(np.argmax(spectrum[low:]))])
    peak = float(np.max(np.abs(y)))
    span = t[-1] - t[0]

    def residual(p):
        a, inv_tau, f, phi = p
        return a * np.exp(-inv_tau * t) * np.sin(2 * np.pi * f * t + phi) - y

    best = None
    for phi in (0.0, np.pi / 2, np.pi, 3 * np.pi / 2):
        fit = least_squares(residual, (peak, 3 / span, f0, phi), x_scale=(peak, 1 / span, f0, 1.0),
                            bounds=((-np.inf, 0.0, 0.2 * f0, -10.0), (np.inf, np.inf, 5 * f0, 10.0)))
        if best is None or fit.cost < best.cost:
            best = fit
    a, inv_tau, f, _ = best.x
    explained = 1 - 2 * best.cost / float(np.sum(y**2))
    if explained < 0.5 or abs(a) == 0:
        return math.nan, math.nan
    return float(f), (math.inf if inv_tau == 0 else float(1 / inv_tau))


def _stop_dynamics(
    time_s: np.ndarray, reading_m: np.ndarray, *, move_s: float, rest_s: float, departure_s: float, direction: str,
    band_m: float, final_window_s: float, ring_s: float,
) -> StopDynamics:
    """Settling, overshoot and ringing of one stop (inner: its caller checked the arguments).

    Parameters
    ----------
    time_s, reading_m : ndarray, shape (n,)
        The recording (seconds, metres).
    move_s, rest_s, departure_s : float, seconds
        Start of the last move before the stop, when its speed fell below the threshold, and
        when the next move began. The final value is the mean over ``[rest, departure]``'s last
        window; the stop begins (arrival) when the reading first reached the final value after
        ``move_s``, so that an axis that overshoots by more than the threshold speed allows is
        measured from its first arrival.
    direction : str
        ``"+"`` or ``"-"``, the direction of the move that ended.
    band_m : float, metres
        Half-width of the settling band.
    final_window_s : float, seconds
        The final value is the mean over the stop's last window.
    ring_s : float, seconds
        Length of the stop's start over which the damped sine is fitted.

    Returns
    -------
    StopDynamics
    """
    sign = 1.0 if direction == "+" else -1.0
    r0, b = np.searchsorted(time_s, [rest_s, departure_s])
    if b <= r0:
        nan = math.nan
        return StopDynamics(rest_s, departure_s, nan, nan, nan, nan, nan, nan, direction)
    tail = time_s[r0:b] >= time_s[b - 1] - final_window_s
    final_value = float(reading_m[r0:b][tail].mean())
    m0 = int(np.searchsorted(time_s, move_s))
    reached = np.flatnonzero(sign * (reading_m[m0:b] - final_value) >= 0)
    a = m0 + int(reached[0]) if reached.size else r0
    arrival_s = float(time_s[a])
    t, x = time_s[a:b] - arrival_s, reading_m[a:b]
    last = t >= t[-1] - final_window_s
    final = final_value
    outside = np.flatnonzero(np.abs(x - final) > band_m)
    if outside.size == 0:
        settling = 0.0
    elif last[outside[-1]] and outside[-1] == x.size - 1:
        settling = math.nan
    else:
        settling = float(t[min(outside[-1] + 1, t.size - 1)])
    overshoot = max(0.0, float(np.max(sign * (x - final))))
    ring = t <= ring_s
    f, tau = _damped_sine(t[ring], x[ring] - final)
    zeta = math.nan
    if math.isfinite(f):
        sigma = 0.0 if math.isinf(tau) else 1 / tau
        zeta = sigma / math.hypot(sigma, 2 * math.pi * f)
    return StopDynamics(float(arrival_s), float(departure_s), final, settling, overshoot, f, tau, zeta, direction)
