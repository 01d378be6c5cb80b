"""Thermal tests: a drift with a known time constant and a displacement following a temperature with a
known lag and sensitivity are recovered; the FFT correlation agrees with a plain loop over the lags."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as hs

from axiscal.errors import AxiscalError
from axiscal.thermal import correlate, etve, fit_time_constant, thermal_drift

HOUR = 3600.0


def smooth_temperature(rng, n):
    """A temperature wandering smoothly by a kelvin or so: a random walk, averaged."""
    walk = np.cumsum(rng.normal(0, 0.05, n + 40))
    return 20 + np.convolve(walk, np.ones(40) / 40, mode="valid")[:n]


def plain_correlation(d, t, max_lag):
    """Reference: Pearson's r at every lag, by np.corrcoef on the overlapping pairs."""
    best = (0.0, 0, 0.0)
    r0 = np.corrcoef(d, t)[0, 1]
    for lag in range(-max_lag, max_lag + 1):
        a, b = (d[lag:], t[:t.size - lag]) if lag >= 0 else (d[:lag], t[-lag:])
        r = np.corrcoef(a, b)[0, 1]
        slope = np.polyfit(b, a, 1)[0]
        if abs(r) > abs(best[0]) + 1e-12 or (abs(abs(r) - abs(best[0])) <= 1e-12 and abs(lag) < abs(best[1])):
            best = (r, lag, slope)
    return r0, best


@pytest.mark.parametrize("seed", range(5))
def test_the_lagged_correlation_agrees_with_a_plain_loop(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(20, 300))
    step = float(rng.uniform(10, 600))
    time = np.arange(n) * step
    temperature = smooth_temperature(rng, n)
    d = rng.normal(0, 1e-6, n) + 3e-6 * np.roll(temperature, int(rng.integers(0, 5)))
    max_lag = int(rng.integers(0, n // 3))
    got = correlate(time, d, temperature, max_lag_s=max_lag * step)
    r0, (r, lag, slope) = plain_correlation(d, temperature, max_lag)
    assert got.r == pytest.approx(r0, abs=1e-9)
    assert got.r_at_lag == pytest.approx(r, abs=1e-9)
    assert got.lag_s == pytest.approx(lag * step)
    assert got.sensitivity == pytest.approx(slope, rel=1e-6)


def test_a_known_lag_and_sensitivity_are_recovered():
    rng = np.random.default_rng(7)
    step, lag = 300.0, 9  # 45 min behind the temperature
    temperature = smooth_temperature(rng, 400)
    d = np.full(400, np.nan)
    d[lag:] = -4.2e-6 * (temperature[:-lag] - 20)
    d[:lag] = d[lag]
    c = correlate(np.arange(400) * step, d, temperature, max_lag_s=3 * HOUR)
    assert c.lag_s == 2700.0
    assert c.r_at_lag == pytest.approx(-1.0, abs=1e-6)
    assert c.sensitivity == pytest.approx(-4.2e-6, rel=1e-3)


def test_uneven_samples_are_put_on_an_even_grid():
    time = np.cumsum(np.r_[0, np.where(np.arange(199) % 2, 50.0, 70.0)])
    temperature = 20 + np.sin(time / 4000)
    c = correlate(time, 2e-6 * np.sin(time / 4000), temperature, max_lag_s=0.0)
    assert c.r == pytest.approx(1.0, abs=1e-3) and c.sensitivity == pytest.approx(2e-6, rel=1e-2)


def test_a_constant_temperature_correlates_with_nothing():
    time = np.arange(50) * 60.0
    c = correlate(time, np.sin(time), np.full(50, 20.0))
    assert np.isnan(c.r) and np.isnan(c.r_at_lag) and np.isnan(c.sensitivity)


@pytest.mark.parametrize("tau_h", [0.3, 0.8, 2.5])
def test_a_known_time_constant_is_recovered(tau_h):
    rng = np.random.default_rng(11)
    t = np.arange(0, 6 * HOUR, 120.0)
    drift = -12e-6 * (1 - np.exp(-t / (tau_h * HOUR))) + rng.normal(0, 0.03e-6, t.size)
    tau, amplitude = fit_time_constant(t, drift)
    assert tau / HOUR == pytest.approx(tau_h, rel=0.03)
    assert amplitude == pytest.approx(-12e-6, rel=0.03)


def test_a_straight_ramp_has_no_time_constant():
    t = np.arange(0, 4 * HOUR, 60.0)
    assert all(np.isnan(fit_time_constant(t, 1e-9 * t)))
    assert all(np.isnan(fit_time_constant(t, np.zeros_like(t))))


def test_drift_figures_of_heating_and_cooling_cycles():
    t = np.arange(0, 8 * HOUR, 60.0)
    running = ((t % (4 * HOUR)) < 3 * HOUR).astype(float)
    state = np.zeros_like(t)
    for k in range(1, t.size):
        a = np.exp(-60.0 / 1800.0)
        state[k] = a * state[k - 1] + (1 - a) * running[k - 1]
    result = thermal_drift(t, {"Z": -10e-6 * state, "A": 2e-6 * state}, {"spindle": 20 + 5 * state}, running=running)
    assert result.heating_phases == 2
    assert result.time_constant_s["Z"] == pytest.approx(1800.0, rel=1e-3)
    last_heating = np.flatnonzero(running)[-1]
    assert result.drift_heating_end["Z"] == pytest.approx(-10e-6 * state[last_heating])
    assert result.drift_max["Z"] == pytest.approx(-10e-6 * state.max())
    assert result.drift_end["A"] == pytest.approx(2e-6 * state[-1])
    assert result.temperature_range_c["spindle"] == pytest.approx(5 * np.ptp(state))


def test_etve_is_the_range_of_each_displacement():
    t = np.arange(0, 10 * HOUR, 300.0)
    rng = np.random.default_rng(2)
    d = {"X": rng.normal(0, 1e-6, t.size), "B": rng.normal(0, 1e-6, t.size)}
    result = etve(t, d, {"air": smooth_temperature(rng, t.size)})
    assert result.etve == {"X": pytest.approx(np.ptp(d["X"])), "B": pytest.approx(np.ptp(d["B"]))}
    assert [(c.direction, c.sensor) for c in result.correlations] == [("X", "air"), ("B", "air")]


def test_bad_series_are_refused():
    t = np.arange(5) * 60.0
    with pytest.raises(AxiscalError, match="unknown direction"):
        etve(t, {"W": np.zeros(5)}, {"air": np.zeros(5)})
    with pytest.raises(AxiscalError, match="one temperature"):
        etve(t, {"X": np.zeros(5)}, {})
    with pytest.raises(AxiscalError, match="time_s must increase"):
        thermal_drift(t[::-1], {"X": np.zeros(5)})
    with pytest.raises(AxiscalError, match="running"):
        thermal_drift(t, {"X": np.zeros(5)}, running=[0, 1, 2, 1, 0])
    with pytest.raises(AxiscalError, match="displacements"):
        thermal_drift(t, {"X": np.zeros(4)})


@settings(max_examples=60, deadline=None)
@given(hs.lists(hs.floats(allow_nan=True, allow_infinity=True, width=32), min_size=0, max_size=12))
def test_any_displacements_give_finite_figures_or_are_refused(values):
    t = np.arange(len(values)) * 60.0
    try:
        result = thermal_drift(t, {"Z": values}, {"air": np.linspace(20, 21, len(values))})
    except AxiscalError:
        return
    assert np.isfinite(result.drift_max["Z"]) and np.isfinite(result.drift_range["Z"])


def test_tilts_alone_are_refused():
    """The ETVE and the drift are displacements of the functional point: X, Y or Z, the tilts beside one."""
    t = np.arange(5) * 60.0
    with pytest.raises(AxiscalError, match=r"displacements must hold X, Y or Z \(the tilts A, B are read beside one"):
        etve(t, {"A": np.zeros(5), "B": np.ones(5)}, {"air": np.arange(5.0)})
    with pytest.raises(AxiscalError, match="displacements must hold X, Y or Z"):
        thermal_drift(t, {"B": np.zeros(5)})
