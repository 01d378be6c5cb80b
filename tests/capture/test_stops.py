"""Stop detection: the streaming detector against a plain per-sample reference, batches, properties."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.capture.stops import StopDetector, detect_stops
from axiscal.errors import AxiscalError


def still_flags(t, x, stability, window):
    """Plain loops: still where the window [t - window, t] is covered and within the stability."""
    still = []
    for i in range(t.size):
        inside = x[(t >= t[i] - window) & (t <= t[i])]
        covered = t[0] <= t[i] - window
        still.append(bool(covered and inside.max() - inside.min() <= stability))
    return still


def still_runs(still):
    """(first, last) of every run of still samples."""
    runs, i = [], 0
    while i < len(still):
        if not still[i]:
            i += 1
            continue
        a = i
        while i + 1 < len(still) and still[i + 1]:
            i += 1
        runs.append((a, i))
        i += 1
    return runs


def reference_stops(t, x, stability, window):
    """Plain loops: a stop is a run of still samples; a run whose first window reaches back into the
    previous stop is that stop; the first stop starts at 0 when every sample before it is within the stability."""
    merged = []  # [first sample of the stop's window, last still sample]
    for a, i in still_runs(still_flags(t, x, stability, window)):
        first = min(j for j in range(t.size) if t[j] >= t[a] - window)
        if merged and first <= merged[-1][1]:
            merged[-1][1] = i
            continue
        if not merged and max(x[: a + 1]) - min(x[: a + 1]) <= stability:
            first = 0
        merged.append([first, i])
    stops = []
    for first, i in merged:
        last = [x[j] for j in range(t.size) if t[i] - window <= t[j] <= t[i]]
        stops.append((first, i, float(np.mean(last))))
    return stops


def staircase(rng, n=600):
    """A reading that moves between random levels and rests in between, with noise, at uneven times."""
    t = np.cumsum(rng.uniform(0.5e-3, 1.5e-3, n))
    levels = np.repeat(rng.uniform(-0.01, 0.01, 8), n // 8 + 1)[:n]
    x = np.convolve(levels, np.ones(15) / 15, mode="same") + rng.normal(0, 0.05e-6, n)
    return t, x


def ringing(rng, n=1000):
    """The axis stands at 0, moves 10 mm and creeps 3 um into place while ringing at 100 Hz, then goes back:
    at uneven times, the peak to peak over a 0.05 s window hovers at 1 um and crosses it several times."""
    t = np.cumsum(rng.uniform(0.5e-3, 1.5e-3, n))
    x = np.interp(t, [0, 0.1, 0.15, 0.8, 0.85, 2], [0, 0, 0.01, 0.01, 0, 0])
    d = t - 0.15
    on = (d >= 0) & (t <= 0.8)
    x[on] += -3e-6 * np.exp(-d[on] / 0.2) + 0.3e-6 * np.exp(-d[on] / 1.0) * np.sin(2 * np.pi * 100 * d[on])
    return t, x + rng.normal(0, 0.02e-6, n)


@pytest.mark.parametrize("signal, seed", [(staircase, s) for s in range(6)] + [(ringing, s) for s in range(3)])
def test_detector_matches_the_plain_reference(signal, seed):
    t, x = signal(np.random.default_rng(seed))
    got = detect_stops(t, x, stability_m=1e-6, window_s=0.03 if signal is staircase else 0.05)
    want = reference_stops(t, x, 1e-6, 0.03 if signal is staircase else 0.05)
    assert [(s.first_index, s.last_index) for s in got] == [(a, b) for a, b, _ in want]
    assert [s.value_m for s in got] == pytest.approx([v for _, _, v in want], abs=1e-15)


@pytest.mark.parametrize("seed", range(3))
def test_a_ringing_stop_is_one_stop(seed):
    # the stillness breaks several times as the axis rings into place: one stop, disjoint from the others,
    # its value the mean of the last window before the axis moves on
    t, x = ringing(np.random.default_rng(seed))
    runs = still_runs(still_flags(t, x, 1e-6, 0.05))
    assert len([r for r in runs if 0.1 < t[r[0]] < 0.8]) >= 4  # the window's peak to peak crossed 1 um 7 times or more
    stops = detect_stops(t, x, stability_m=1e-6, window_s=0.05)
    assert [round(s.value_m * 1e3, 2) for s in stops] == [0.0, 10.0, 0.0]
    assert all(b.first_index > a.last_index for a, b in zip(stops, stops[1:]))
    assert stops[1].value_m == pytest.approx(x[(t >= stops[1].end_s - 0.05) & (t <= stops[1].end_s)].mean(), abs=1e-15)
    assert stops[1].approach == "+" and stops[2].approach == "-"


def test_a_standing_start_begins_at_sample_0_at_uneven_times():
    # host time stamps: the first whole window ends between two samples, so its first sample is not 0
    rng = np.random.default_rng(7)
    t = np.cumsum(rng.uniform(0.5e-3, 1.5e-3, 2000))
    x = np.interp(t, [0, 0.5, 0.6, 2.5], [0, 0, 0.01, 0.01]) + rng.normal(0, 0.02e-6, t.size)
    first_still = still_flags(t, x, 1e-6, 0.1).index(True)
    assert t[0] < t[first_still] - 0.1 < t[1]  # its window reaches back to between samples 0 and 1
    standing, moved = detect_stops(t, x, stability_m=1e-6, window_s=0.1)
    assert standing.first_index == 0 and standing.start_s == t[0] and moved.first_index > 0
    # a reading that moved before its first still window is not a standing start
    k = int(np.searchsorted(t, 0.55))  # the middle of the move
    (late,) = detect_stops(t[k:], x[k:], stability_m=1e-6, window_s=0.1)
    assert late.first_index > 0 and late.value_m == pytest.approx(0.01, abs=1e-7)


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
