"""Stop detection: the streaming detector against a plain per-sample reference, batches, properties."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.capture.stops import StopDetector, detect_stops
from axiscal.errors import AxiscalError


def reference_stops(t, x, stability, window):
    """Plain loops: still where the window [t - window, t] is covered and within the stability; a stop is a run of still samples."""
    still = []
    for i in range(t.size):
        inside = [x[j] for j in range(t.size) if t[i] - window <= t[j] <= t[i]]
        covered = t[0] <= t[i] - window
        still.append(covered and max(inside) - min(inside) <= stability)
    stops, i = [], 0
    while i < t.size:
        if not still[i]:
            i += 1
            continue
        a = i
        while i + 1 < t.size and still[i + 1]:
            i += 1
        last = [x[j] for j in range(t.size) if t[i] - window <= t[j] <= t[i]]
        first = min(j for j in range(t.size) if t[j] >= t[a] - window)
        stops.append((first, i, float(np.mean(last))))
        i += 1
    return stops


def staircase(rng, n=600):
    """A reading that moves between random levels and rests in between, with noise, at uneven times."""
    t = np.cumsum(rng.uniform(0.5e-3, 1.5e-3, n))
    levels = np.repeat(rng.uniform(-0.01, 0.01, 8), n // 8 + 1)[:n]
    x = np.convolve(levels, np.ones(15) / 15, mode="same") + rng.normal(0, 0.05e-6, n)
    return t, x


@pytest.mark.parametrize("seed", range(6))
def test_detector_matches_the_plain_reference(seed):
    t, x = staircase(np.random.default_rng(seed))
    got = detect_stops(t, x, stability_m=1e-6, window_s=0.03)
    want = reference_stops(t, x, 1e-6, 0.03)
    assert [(s.first_index, s.last_index) for s in got] == [(a, b) for a, b, _ in want]
    assert [s.value_m for s in got] == pytest.approx([v for _, _, v in want], abs=1e-15)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 10_000), st.lists(st.integers(1, 200), min_size=1, max_size=12))
def test_batches_of_any_size_find_the_same_stops(seed, cuts):
    t, x = staircase(np.random.default_rng(seed), n=500)
    whole = detect_stops(t, x, stability_m=1e-6, window_s=0.03)
    detector = StopDetector(stability_m=1e-6, window_s=0.03)
    stops, start = [], 0
    for size in cuts * 50:
        if start >= t.size:
            break
        stops += detector.feed(t[start : start + size], x[start : start + size])
        start += size
    stops += detector.feed(t[start:], x[start:]) + detector.finish()
    assert [(s.first_index, s.last_index, s.value_m, s.low_m, s.high_m) for s in stops] == \
        [(s.first_index, s.last_index, s.value_m, s.low_m, s.high_m) for s in whole]


def test_the_value_is_where_the_axis_settled_not_where_it_first_held():
    # rings and creeps after it arrives: the mean is over the last window before it moves on
    t = np.arange(0, 4.0, 1e-3)
    arrive, leave = 1.0, 3.0
    dt = np.clip(t - arrive, 0, None)
    x = np.where(t < arrive, 0.0, 0.01 - 0.8e-6 * np.exp(-dt / 0.3))
    x = np.where(t > leave, 0.01 + (t - leave) * 0.01, x)
    (stop,) = [s for s in detect_stops(t, x, stability_m=1e-6, window_s=0.5) if s.value_m > 0.005]
    settled = x[(t >= leave - 0.5) & (t <= leave)].mean()
    assert stop.value_m == pytest.approx(settled, abs=2e-9)
    assert stop.approach == "+"


def test_sensor_channels_are_averaged_over_the_same_window():
    t = np.arange(0, 2.0, 1e-3)
    x = np.zeros_like(t)
    air = 20.0 + t
    (stop,) = detect_stops(t, x, stability_m=1e-6, window_s=0.5, channels={"air_temperature_c": air})
    assert stop.channels["air_temperature_c"] == pytest.approx(air[t >= t[-1] - 0.5].mean())


@pytest.mark.parametrize("kwargs, message", [
    ({"stability_m": 0.0, "window_s": 0.5}, "stability_m"),
    ({"stability_m": 1e-6, "window_s": float("nan")}, "window_s"),
])
def test_bad_settings_are_refused(kwargs, message):
    with pytest.raises(AxiscalError, match=message):
        detect_stops(np.arange(3.0), np.zeros(3), **kwargs)


def test_times_that_go_back_are_refused():
    with pytest.raises(AxiscalError, match="never go back"):
        detect_stops(np.array([0.0, 1.0, 0.5]), np.zeros(3), stability_m=1e-6, window_s=0.5)
