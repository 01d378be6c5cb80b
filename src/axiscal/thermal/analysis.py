"""Thermal tests of machine tools: the environmental temperature variation error, thermal drift,
and how the drift follows the temperatures.

ISO 230-3 (thermal effects): the ETVE test logs the displacement of the functional point against
a fixed artefact (sensors in X, Y, Z and tilts about two axes) together with temperatures while
the machine stands still for hours; the ETVE of a direction is the range (max - min) of its
displacement over the test. The distortion tests log the same while a spindle rotates or a linear
axis moves (heating) and after it stops (cooling); the drift of a direction is its displacement
from the start of the test. The analysis adds what a technician reads from the plot: the
correlation of each displacement with each temperature with the lag that makes it largest (a
displacement that follows a temperature with a delay) and the sensitivity at that lag, and the
time constant of a first-order settling ``d(t) = c + A (1 - exp(-(t - t0) / tau))`` fitted to a
heating phase.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_mapping, check_number, check_same_length, is_real

__all__ = [
    "DIRECTIONS",
    "LINEAR_DIRECTIONS",
    "Correlation",
    "correlate",
    "fit_time_constant",
    "EtveResult",
    "etve",
    "DriftResult",
    "thermal_drift",
]

#: displacement directions: X, Y, Z (metres) and the tilts A, B (radians)
DIRECTIONS = ("X", "Y", "Z", "A", "B")
#: the directions of which a test needs one at least: the ETVE and the drift are displacements of the
#: functional point, the tilts are read beside them (a run of tilts alone has no figure to check)
LINEAR_DIRECTIONS = ("X", "Y", "Z")
#: the largest value taken, in SI (m, rad, s, degC)
_LIMIT = 1e9


@dataclass(frozen=True)
class Correlation:
    """How one displacement follows one temperature.

    Attributes
    ----------
    direction : str
        ``"X"``, ``"Y"``, ``"Z"``, ``"A"`` or ``"B"``.
    sensor : str
        The temperature's place (``"spindle"`` for ``temperature_spindle_c``).
    r : float
        Pearson's correlation coefficient at no lag (NaN when either does not vary).
    lag_s : float
        The delay of the displacement behind the temperature that makes ``|r|`` largest, seconds
        (negative: the displacement leads).
    r_at_lag : float
        The correlation coefficient at that lag.
    sensitivity : float
        The slope of the displacement against the temperature at that lag, SI per kelvin (m/K, or
        rad/K for a tilt).
    """

    direction: str
    sensor: str
    r: float
    lag_s: float
    r_at_lag: float
    sensitivity: float

    def __post_init__(self) -> None:
        for name in ("direction", "sensor"):
            if not isinstance(getattr(self, name), str):
                raise AxiscalError(f"{name} must be a name, not {getattr(self, name)!r}")
        object.__setattr__(self, "lag_s", check_number("lag_s", self.lag_s))
        for name in ("r", "r_at_lag", "sensitivity"):  # NaN: not defined (a series that does not vary)
            if not is_real(getattr(self, name)):
                raise AxiscalError(f"{name} must be a number (NaN where it is not defined), not {getattr(self, name)!r}")


def _series(time_s, values: Mapping, name: str) -> dict[str, np.ndarray]:
    check_mapping(name, values, what=f"a mapping of names to series ({name})")
    out = {}
    for key, series in values.items():
        if not isinstance(key, str) or not key:
            raise AxiscalError(f"{name} must be keyed by names, not {key!r}")
        out[key] = check_array(f"{name}[{key!r}]", series, ndim=1, limit=_LIMIT)
        check_same_length(time_s=time_s, **{f"{name}[{key!r}]": out[key]})
    return out


def _time(time_s) -> np.ndarray:
    time = check_array("time_s", time_s, ndim=1, min_len=3, limit=_LIMIT)
    steps = np.diff(time)
    if np.any(steps <= 0.0):
        k = int(np.flatnonzero(steps <= 0.0)[0]) + 1
        raise AxiscalError(f"time_s must increase: sample {k} is at {time[k]:g} s after {time[k - 1]:g} s")
    return time


def _uniform(time: np.ndarray, *series: np.ndarray) -> tuple[float, list[np.ndarray]]:
    """The series on an even time grid of the median step (interpolated when the steps differ by > 1 %)."""
    steps = np.diff(time)
    step = float(np.median(steps))
    if np.all(np.abs(steps - step) <= 0.01 * step):
        return step, list(series)
    grid = time[0] + step * np.arange(int(np.floor((time[-1] - time[0]) / step + 1e-9)) + 1)
    return step, [np.interp(grid, time, s) for s in series]


def _lagged_sums(d: np.ndarray, t: np.ndarray, max_lag: int) -> tuple[np.ndarray, ...]:
    """For each lag L in -max_lag..max_lag the count, sums, sums of squares and cross sum of the
    pairs (d[i + L], t[i]), from cumulative sums and one FFT cross-correlation."""
    from scipy.signal import correlate

    n = d.size
    lags = np.arange(-max_lag, max_lag + 1)
    cross = correlate(d, t, mode="full", method="fft")[lags + n - 1]
    zero = np.zeros(1)
    cd, cd2 = np.concatenate([zero, np.cumsum(d)]), np.concatenate([zero, np.cumsum(d * d)])
    ct, ct2 = np.concatenate([zero, np.cumsum(t)]), np.concatenate([zero, np.cumsum(t * t)])
    count = n - np.abs(lags)
    d_lo, d_hi = np.maximum(lags, 0), np.minimum(n, n + lags)
    t_lo, t_hi = np.maximum(-lags, 0), np.minimum(n, n - lags)
    return (lags, count, cd[d_hi] - cd[d_lo], cd2[d_hi] - cd2[d_lo], ct[t_hi] - ct[t_lo], ct2[t_hi] - ct2[t_lo], cross)


def correlate(
    time_s: np.ndarray, displacement: np.ndarray, temperature_c: np.ndarray, *, max_lag_s: float | None = None,
    direction: str = "X", sensor: str = "temperature",
) -> Correlation:
    """Correlation of a displacement with a temperature, and the lag that makes it largest.

    Parameters
    ----------
    time_s : array_like, shape (n,)
        Sample times, seconds, increasing (resampled on an even grid of the median step when the
        steps differ by more than 1 %).
    displacement : array_like, shape (n,)
        The displacement, metres (or radians for a tilt).
    temperature_c : array_like, shape (n,)
        The temperature, degC.
    max_lag_s : float, optional, keyword-only
        The largest lag tried either way, seconds (default a quarter of the test's duration); at
        least three pairs overlap at every lag.
    direction, sensor : str, keyword-only
        The names the result carries.

    Returns
    -------
    Correlation

    Raises
    ------
    AxiscalError
        Fewer than 3 samples, arrays of different lengths, values that are not finite, times that
        do not increase, a negative lag.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 36000, 60.0)
    >>> def warming(t):
    ...     return 20 - np.expm1(-np.clip(t, 0, None) / 7200)
    >>> c = correlate(t, 5e-6 * (warming(t - 1800) - 20), warming(t))
    >>> c.lag_s, round(c.r_at_lag, 9), round(c.sensitivity / 1e-6, 6)
    (1800.0, 1.0, 5.0)
    """
    time = _time(time_s)
    d = check_array("displacement", displacement, ndim=1, limit=_LIMIT)
    temperature = check_array("temperature_c", temperature_c, ndim=1, limit=_LIMIT)
    check_same_length(time_s=time, displacement=d, temperature_c=temperature)
    for name, value in (("direction", direction), ("sensor", sensor)):
        if not isinstance(value, str):
            raise AxiscalError(f"{name} must be a name, not {value!r}")
    duration = float(time[-1] - time[0])
    max_lag_s = 0.25 * duration if max_lag_s is None else check_number("max_lag_s", max_lag_s, nonnegative=True)
    step, (d, temperature) = _uniform(time, d, temperature)
    d = d - d.mean()
    temperature = temperature - temperature.mean()
    max_lag = int(min(np.floor(max_lag_s / step + 1e-9), d.size - 3))
    lags, m, sd, sd2, st, st2, cross = _lagged_sums(d, temperature, max(max_lag, 0))
    covariance = m * cross - sd * st
    var_d, var_t = m * sd2 - sd * sd, m * st2 - st * st
    scale_d, scale_t = np.max(d * d) * m * m, np.max(temperature * temperature) * m * m
    defined = (var_d > 1e-12 * scale_d) & (var_t > 1e-12 * scale_t)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(defined, covariance / np.sqrt(np.where(defined, var_d * var_t, 1.0)), np.nan)
        slope = np.where(defined, covariance / np.where(defined, var_t, 1.0), np.nan)
    zero = int(np.flatnonzero(lags == 0)[0])
    if not np.any(defined):
        return Correlation(direction, sensor, float("nan"), 0.0, float("nan"), float("nan"))
    strength = np.where(np.isfinite(r), np.abs(r), -1.0)
    ties = np.flatnonzero(strength >= strength.max() - 1e-9)  # a periodic record: the shortest lag
    best = int(ties[np.argmin(np.abs(lags[ties]))])
    return Correlation(direction, sensor, float(r[zero]), float(lags[best] * step), float(r[best]), float(slope[best]))


def fit_time_constant(time_s: np.ndarray, values: np.ndarray) -> tuple[float, float]:
    """Fit a first-order settling ``c + A (1 - exp(-(t - t0) / tau))`` and return ``(tau_s, A)``.

    For each trial ``tau`` the offset and amplitude follow by linear least squares; ``tau`` is
    searched over a logarithmic grid from a tenth of the sample step to ten times the duration,
    then refined. A drift that does not settle inside that range (a straight ramp, no change)
    gives NaN for both.

    Parameters
    ----------
    time_s : array_like, shape (n,)
        Sample times, seconds, increasing; at least 4.
    values : array_like, shape (n,)
        The drift, SI.

    Returns
    -------
    tau_s : float
        The time constant, seconds (NaN when none is found).
    amplitude : float
        ``A``, the drift still to come at ``t0`` (its final value less its first), SI (NaN likewise).

    Raises
    ------
    AxiscalError
        Fewer than 4 samples, arrays of different lengths, values that are not finite, times that
        do not increase.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 4 * 3600, 60.0)
    >>> tau, amplitude = fit_time_constant(t, 12e-6 * (1 - np.exp(-t / 2700)))
    >>> round(tau, 3), round(amplitude / 1e-6, 6)
    (2700.0, 12.0)
    """
    from scipy.optimize import minimize_scalar

    time = _time(time_s)
    y = check_array("values", values, ndim=1, limit=_LIMIT)
    check_same_length(time_s=time, values=y)
    if time.size < 4:
        raise AxiscalError(f"{time.size} samples: a time constant needs at least 4")
    t = time - time[0]
    duration = float(t[-1])
    step = float(np.min(np.diff(t)))
    if np.ptp(y) == 0.0:
        return float("nan"), float("nan")

    def misfit(log_tau: float) -> float:
        basis = np.column_stack([np.ones_like(t), -np.expm1(-t / np.exp(log_tau))])
        coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
        return float(np.sum((y - basis @ coef) ** 2))

    low, high = np.log(0.1 * step), np.log(10.0 * duration)
    grid = np.linspace(low, high, 241)
    costs = np.array([misfit(g) for g in grid])
    k = int(np.argmin(costs))
    if k in (0, grid.size - 1):
        return float("nan"), float("nan")
    found = minimize_scalar(misfit, bounds=(grid[k - 1], grid[k + 1]), method="bounded", options={"xatol": 1e-10})
    tau = float(np.exp(found.x))
    basis = np.column_stack([np.ones_like(t), -np.expm1(-t / tau)])
    coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
    return tau, float(coef[1])


@dataclass(frozen=True)
class EtveResult:
    """The environmental temperature variation error of a test (ISO 230-3).

    Attributes
    ----------
    etve : dict of str to float
        Per direction, the range (max - min) of the displacement over the test, metres (X, Y, Z)
        or radians (A, B).
    temperature_range_c : dict of str to float
        Per sensor, the range of the temperature over the test, kelvin.
    correlations : tuple of Correlation
        Every direction against every sensor.
    duration_s : float
        The test's duration, seconds.
    """

    etve: dict[str, float]
    temperature_range_c: dict[str, float]
    correlations: tuple[Correlation, ...]
    duration_s: float

    def __post_init__(self) -> None:
        check_mapping("etve", self.etve)
        check_mapping("temperature_range_c", self.temperature_range_c)
        if not isinstance(self.correlations, tuple) or not all(isinstance(c, Correlation) for c in self.correlations):
            raise AxiscalError("correlations must be a tuple of Correlation")
        object.__setattr__(self, "duration_s", check_number("duration_s", self.duration_s, nonnegative=True))


def _directions(displacements: Mapping, time: np.ndarray) -> dict[str, np.ndarray]:
    series = _series(time, displacements, "displacements")
    if not series:
        raise AxiscalError(f"displacements must hold one direction at least ({', '.join(DIRECTIONS)})")
    for key in series:
        if key not in DIRECTIONS:
            raise AxiscalError(f"unknown direction {key!r}; use {', '.join(DIRECTIONS)}")
    if not set(series) & set(LINEAR_DIRECTIONS):
        raise AxiscalError(f"displacements must hold {', '.join(LINEAR_DIRECTIONS[:-1])} or {LINEAR_DIRECTIONS[-1]}"
                           f" (the tilts {', '.join(sorted(series))} are read beside one, never alone)")
    return series


def etve(
    time_s: np.ndarray, displacements: Mapping[str, np.ndarray], temperatures_c: Mapping[str, np.ndarray], *,
    max_lag_s: float | None = None,
) -> EtveResult:
    """The ETVE per direction with the temperatures' ranges and the correlations (ISO 230-3).

    Parameters
    ----------
    time_s : array_like, shape (n,)
        Sample times, seconds, increasing.
    displacements : mapping of str to array_like, shape (n,)
        Direction (``"X"``, ``"Y"``, ``"Z"`` in metres, ``"A"``, ``"B"`` in radians) to the
        displacement of the functional point.
    temperatures_c : mapping of str to array_like, shape (n,)
        Sensor place to temperature, degC; at least one.
    max_lag_s : float, optional, keyword-only
        The largest lag of the correlations, seconds (default a quarter of the duration).

    Returns
    -------
    EtveResult

    Raises
    ------
    AxiscalError
        No direction or no temperature, an unknown direction, series of another length than
        ``time_s``, values that are not finite, times that do not increase.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 7200, 60.0)
    >>> result = etve(t, {"X": 2e-6 * np.sin(t / 1000)}, {"air": 20 + np.sin(t / 1000)})
    >>> round(result.etve["X"] / 1e-6, 2), round(result.correlations[0].r, 6)
    (4.0, 1.0)
    """
    time = _time(time_s)
    directions = _directions(displacements, time)
    temperatures = _series(time, temperatures_c, "temperatures_c")
    if not temperatures:
        raise AxiscalError("temperatures_c must hold one temperature at least: the ETVE is read against them")
    correlations = tuple(
        correlate(time, d, temperature, max_lag_s=max_lag_s, direction=name, sensor=place)
        for name, d in directions.items() for place, temperature in temperatures.items()
    )
    return EtveResult({k: float(np.ptp(v)) for k, v in directions.items()},
                      {k: float(np.ptp(v)) for k, v in temperatures.items()}, correlations, float(time[-1] - time[0]))


@dataclass(frozen=True)
class DriftResult:
    """The thermal drift of a distortion test (ISO 230-3), per direction.

    Attributes
    ----------
    drift_max : dict of str to float
        The drift (displacement less its first value) largest in magnitude over the test, signed, SI.
    drift_range : dict of str to float
        Max - min of the displacement over the test, SI.
    drift_end : dict of str to float
        The drift at the end of the test, SI.
    drift_heating_end : dict of str to float
        The drift at the last sample of the last heating phase, SI (empty without phases).
    time_constant_s : dict of str to float
        The time constant of the first heating phase (of the whole test without phases), seconds;
        NaN when the drift does not settle like a first-order system.
    temperature_range_c : dict of str to float
        Per sensor, the range of the temperature, kelvin.
    heating_phases : int
        The number of heating phases (0 without a ``running`` series).
    duration_s : float
        The test's duration, seconds.
    """

    drift_max: dict[str, float]
    drift_range: dict[str, float]
    drift_end: dict[str, float]
    drift_heating_end: dict[str, float]
    time_constant_s: dict[str, float]
    temperature_range_c: dict[str, float]
    heating_phases: int
    duration_s: float

    def __post_init__(self) -> None:
        for name in ("drift_max", "drift_range", "drift_end", "drift_heating_end", "time_constant_s", "temperature_range_c"):
            check_mapping(name, getattr(self, name))
        check_count("heating_phases", self.heating_phases, minimum=0)
        object.__setattr__(self, "duration_s", check_number("duration_s", self.duration_s, nonnegative=True))


def thermal_drift(
    time_s: np.ndarray, displacements: Mapping[str, np.ndarray], temperatures_c: Mapping[str, np.ndarray] | None = None,
    *, running: np.ndarray | None = None,
) -> DriftResult:
    """The drift per direction of a thermal distortion test: heating and cooling cycles (ISO 230-3).

    Parameters
    ----------
    time_s : array_like, shape (n,)
        Sample times, seconds, increasing.
    displacements : mapping of str to array_like, shape (n,)
        Direction (``"X"``, ``"Y"``, ``"Z"`` in metres, ``"A"``, ``"B"`` in radians) to displacement.
    temperatures_c : mapping of str to array_like, shape (n,), optional
        Sensor place to temperature, degC.
    running : array_like of 0 and 1, shape (n,), optional, keyword-only
        1 while the spindle rotates or the axis moves (heating), 0 while it stands (cooling).

    Returns
    -------
    DriftResult

    Raises
    ------
    AxiscalError
        No direction, an unknown direction, series of another length, values that are not finite,
        times that do not increase, a ``running`` series holding other than 0 and 1.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 4 * 3600, 60.0)
    >>> result = thermal_drift(t, {"Z": -8e-6 * (1 - np.exp(-t / 1800))})
    >>> round(result.time_constant_s["Z"], 3), round(result.drift_end["Z"] / 1e-6, 3)
    (1800.0, -7.997)
    """
    time = _time(time_s)
    directions = _directions(displacements, time)
    temperatures = _series(time, temperatures_c if temperatures_c is not None else {}, "temperatures_c")
    heating = None
    if running is not None:
        flags = check_array("running", running, ndim=1)
        check_same_length(time_s=time, running=flags)
        if not np.all((flags == 0) | (flags == 1)):
            raise AxiscalError("running must hold 1 (heating: spindle or axis running) and 0 (cooling) only")
        heating = flags.astype(bool)
    starts = np.flatnonzero(np.diff(np.concatenate([[0], heating.astype(int)])) == 1) if heating is not None else np.array([], int)
    drift_max, drift_range, drift_end, at_heating_end, tau = {}, {}, {}, {}, {}
    if heating is not None and starts.size:
        first = int(starts[0])
        after = np.flatnonzero(~heating[first:])
        window = slice(first, first + int(after[0]) if after.size else time.size)
        last_heating = int(np.flatnonzero(heating)[-1])
    else:
        window, last_heating = slice(0, time.size), None
    for name, d in directions.items():
        drift = d - d[0]
        k = int(np.argmax(np.abs(drift)))
        drift_max[name] = float(drift[k])
        drift_range[name] = float(np.ptp(d))
        drift_end[name] = float(drift[-1])
        if last_heating is not None:
            at_heating_end[name] = float(drift[last_heating])
        segment = slice(window.start, window.stop)
        tau[name] = fit_time_constant(time[segment], d[segment])[0] if time[segment].size >= 4 else float("nan")
    return DriftResult(drift_max, drift_range, drift_end, at_heating_end, tau,
                       {k: float(np.ptp(v)) for k, v in temperatures.items()}, int(starts.size), float(time[-1] - time[0]))
