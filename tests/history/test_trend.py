"""Drift fits, crossing dates and calibration intervals: against plain references and known drifts."""

from __future__ import annotations

import datetime as _dt
import json

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.history import Drift, add_results, drifting_results, figure_trend, write_results
from axiscal.history.trend import crossing, date_of, fit_drift, staircase, trend_of, years


def test_the_weighted_fit_is_numpys_weighted_polyfit():
    rng = np.random.default_rng(0)
    for _ in range(20):
        t = np.sort(rng.uniform(0, 5, 7))
        U = rng.uniform(0.5, 2.0, 7)
        y = 3 + 1.5 * t + rng.normal(0, U / 2)
        fit = fit_drift(t, y, U)
        coef, cov = np.polyfit(t - fit.t0, y, 1, w=2 / U, cov="unscaled")
        birge = max(1.0, fit.chi2 / fit.dof)
        assert fit.b == pytest.approx(coef[0], rel=1e-10) and fit.a == pytest.approx(coef[1], rel=1e-10)
        assert fit.u_b == pytest.approx(np.sqrt(cov[0, 0] * birge), rel=1e-10)


def test_without_u_the_fit_is_ordinary_least_squares_with_its_residual_scale():
    rng = np.random.default_rng(1)
    t = np.arange(6.0)
    y = 2 - 0.5 * t + rng.normal(0, 0.3, 6)
    fit = fit_drift(t, y)
    coef, cov = np.polyfit(t - fit.t0, y, 1, cov=True)
    assert fit.b == pytest.approx(coef[0]) and fit.u_b == pytest.approx(np.sqrt(cov[0, 0]))


def test_fiellers_interval_is_where_the_band_holds_the_limit():
    rng = np.random.default_rng(2)
    t = np.arange(5.0)
    fit = fit_drift(t, 1 + 2 * t + rng.normal(0, 0.5, 5), np.full(5, 1.0))
    t_cross, low, high = crossing(fit, 15.0)
    grid = np.linspace(0, 20, 400001)
    inside = np.abs(fit.at(grid) - 15.0) <= 2 * fit.u_at(grid)
    assert low == pytest.approx(grid[inside][0], abs=1e-4) and high == pytest.approx(grid[inside][-1], abs=1e-4)
    assert low < t_cross < high and fit.at(t_cross) == pytest.approx(15.0)


def test_a_slope_that_is_not_significant_gives_an_unbounded_interval():
    fit = fit_drift(np.arange(4.0), np.array([1.0, 1.2, 0.9, 1.1]), np.full(4, 1.0))
    _, low, high = crossing(fit, 10.0)
    assert low is None and high is None


def test_the_staircase_extends_after_a_pass_and_shrinks_after_a_fail():
    assert staircase([]) == 365.0
    assert staircase([True]) == 365.0 * 1.25
    assert staircase([True, False]) == 365.0 * 1.25 * 0.5
    assert staircase([True] * 20) == 1095.0
    assert staircase([False] * 20) == 30.0


def _machine_trend(seed: int, slope: float):
    payloads = drifting_results({"positioning.X.E": Drift(8.0, slope, 1.0, 20.0)}, campaigns=8, seed=seed)
    dates = [_dt.date.fromisoformat(p["campaign"]["campaign"]["date"]) for p in payloads]
    values = [p["tests"][0]["figures"]["E"] for p in payloads]
    return dates, values, trend_of("m", "positioning.X.E", dates, values, [1.0] * 8, 20.0, [True] * 8, unit="um")


def test_known_drifts_are_recovered_within_their_uncertainty_95_percent_of_the_time():
    slope = 4.0
    start = _dt.date(2020, 1, 6)
    true_crossing = years(start) + (20.0 - 8.0) / slope
    slope_hits = crossing_hits = 0
    for seed in range(50):
        _, _, trend = _machine_trend(seed, slope)
        slope_hits += abs(trend.fit.b - slope) <= 2 * trend.fit.u_b
        low, high = trend.crossing_interval
        crossing_hits += low is not None and high is not None and years(low) <= true_crossing <= years(high)
    assert 0.88 <= slope_hits / 50 <= 1.0
    assert 0.88 <= crossing_hits / 50 <= 1.0


def test_the_fixed_risk_date_is_where_the_band_reaches_the_tolerance():
    _, _, trend = _machine_trend(3, 4.0)
    t = years(trend.fixed_risk_date)
    assert trend.fit.at(t) + 1.6449 * trend.fit.u_at(t) == pytest.approx(20.0, abs=0.02)
    assert trend.next_date == min(trend.fixed_risk_date, trend.staircase_date)
    assert trend.crossing_interval[0] <= trend.crossing_date <= trend.crossing_interval[1]


def test_the_robust_fit_resists_an_outlying_campaign():
    dates, values, _ = _machine_trend(4, 2.0)
    values[5] += 25.0
    plain = trend_of("m", "f", dates, values, [1.0] * 8, 20.0, [True] * 8)
    robust = trend_of("m", "f", dates, values, [1.0] * 8, 20.0, [True] * 8, method="robust")
    assert abs(robust.fit.b - 2.0) < 2 * robust.fit.u_b
    assert abs(plain.fit.b - 2.0) > abs(robust.fit.b - 2.0)


def test_history_trend_json_recovers_a_generated_fleets_drifts(db_url, tmp_path, run_cli):
    slopes = {"A": 3.0, "B": -2.0, "C": 0.5}
    for n, (machine, slope) in enumerate(slopes.items()):
        payloads = drifting_results({"positioning.X.E": Drift(12.0 if slope > 0 else -12.0, slope, 1.0, 30.0)},
                                    machine=machine, campaigns=7, seed=10 + n)
        add_results(write_results(tmp_path / machine, payloads), url=db_url)
    for machine, slope in slopes.items():
        status, out, _ = run_cli("history", "trend", machine, "--figure", "positioning.X.E", "--json", "--db", db_url)
        assert status == 0
        fit = json.loads(out)["fit"]
        assert abs(fit["slope_per_year"] - slope) <= 2 * fit["u_slope_per_year"]


def test_fewer_than_three_campaigns_or_no_tolerance_is_refused(tmp_path, run_cli):
    db = tmp_path / "h.sqlite"
    payloads = drifting_results({"positioning.X.E": Drift(5.0, 1.0, 1.0, 20.0)}, machine="M", campaigns=3)
    for p in payloads[1:]:
        p["tests"][0]["tolerances"] = {}
    add_results(write_results(tmp_path / "m", payloads[:2]), url=str(db))
    status, _, err = run_cli("history", "trend", "M", "--figure", "positioning.X.E", "--db", db)
    assert status == 2 and err == "axiscal: error: a trend needs three campaigns at least: M has 2 with 'positioning.X.E'\n"
    add_results(write_results(tmp_path / "m", payloads, prefix="all"), url=str(db))
    status, _, err = run_cli("history", "trend", "M", "--figure", "positioning.X.E", "--db", db)
    assert status == 2 and "has no tolerance in its latest campaign" in err
    status, _, err = run_cli("history", "trend", "M", "--figure", "positioning.Q.E", "--db", db)
    assert status == 2 and "has no figure 'positioning.Q.E'" in err


def test_trend_writes_its_plot(tmp_path, run_cli):
    db = tmp_path / "h.sqlite"
    add_results(write_results(tmp_path / "m", drifting_results({"positioning.X.E": Drift(5.0, 2.0, 1.0, 20.0)},
                                                               machine="M")), url=str(db))
    status, out, _ = run_cli("history", "trend", "M", "--figure", "positioning.X.E", "--db", db, "--plot",
                             tmp_path / "t.svg")
    assert status == 0 and "next calibration" in out and (tmp_path / "t.svg").read_text().count("<svg") == 1
    trend = figure_trend("M", "positioning.X.E", url=str(db))
    assert date_of(years(trend.dates[-1])) == trend.dates[-1]


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_reals = st.one_of(st.floats(-100.0, 100.0), st.floats(allow_nan=True, allow_infinity=True, width=64))


@settings(max_examples=300)
@given(data=st.data(), robust=st.booleans(), tolerance=_reals)
def test_any_numbers_give_a_finite_fit_or_a_clean_refusal(data, robust, tolerance):
    n = data.draw(st.integers(0, 8))
    same = data.draw(st.booleans())
    t = data.draw(st.lists(_reals, min_size=n, max_size=n) if same else st.lists(_reals, max_size=8))
    y = data.draw(st.lists(_reals, min_size=n, max_size=n))
    U = data.draw(st.one_of(st.none(), st.lists(_reals, min_size=n, max_size=n)))
    try:
        fit = fit_drift(np.array(t), np.array(y), None if U is None else np.array(U),
                        method="robust" if robust else "wls")
    except AxiscalError:
        return
    assert np.isfinite(fit.b) or not np.all(np.isfinite(np.array(y)))
    try:
        t_cross, low, high = crossing(fit, tolerance)
    except AxiscalError:
        return
    assert (low is None) == (high is None)


def test_a_figure_that_barely_changes_crosses_not_within_the_horizon(tmp_path, run_cli):
    # hand-computed: values 5.0, 5.000001, 5.0 over two years fit the slope 0 up to rounding and a
    # crossing of 20 um some 10^7 years on, after 9999-12-31: it is said, not dated
    dates = [_dt.date(2022, 1, 3), _dt.date(2023, 1, 2), _dt.date(2024, 1, 1)]
    trend = trend_of("m", "positioning.X.E", dates, [5.0, 5.000001, 5.0], [1.0] * 3, 20.0, [True] * 3, unit="um")
    assert trend.crossing_date is None and trend.crossing_note == "not within 100 years"
    assert trend.crossing_interval == (None, None) and trend.crossing_text == "not within 100 years"
    assert trend.payload()["crossing_note"] == "not within 100 years"
    # a line already beyond its tolerance that barely rises crossed it long before
    past = trend_of("m", "f", dates, [25.0, 25.000002, 25.000004], [1.0] * 3, 20.0, [False] * 3)
    assert past.crossing_date is None and past.crossing_note == "over 100 years before the last campaign"
    # a slope that reaches it within the horizon still gives the date
    near = trend_of("m", "f", dates, [5.0, 6.0, 7.0], [0.1] * 3, 20.0, [True] * 3)
    assert near.crossing_date is not None and near.crossing_note == "" and near.crossing_text.startswith("2036")
    # through the command line and the report's history section
    db = tmp_path / "h.sqlite"
    payloads = drifting_results({"positioning.X.E": Drift(5.0, 0.0, 1.0, 20.0)}, machine="M", campaigns=3)
    for p, value in zip(payloads, [5.0, 5.001, 5.002]):  # about 1 nm a year: a crossing some 15 000 years on
        p["tests"][0]["figures"]["E"] = value
    add_results(write_results(tmp_path / "m", payloads), url=str(db))
    status, out, err = run_cli("history", "trend", "M", "--figure", "positioning.X.E", "--db", db)
    assert status == 0, err
    assert "reaches the tolerance not within 100 years (k = 2: unbounded .. unbounded)" in out


def test_date_of_refuses_a_date_beyond_the_calendar_in_one_line():
    assert date_of(years(_dt.date(9999, 12, 31))) == _dt.date(9999, 12, 31)
    assert date_of(years(_dt.date(1, 1, 1))) == _dt.date(1, 1, 1)
    for t in (1e7, -1e7, float("inf"), float("nan")):
        with pytest.raises(AxiscalError, match="is not a date between 0001-01-01 and 9999-12-31"):
            date_of(t)
