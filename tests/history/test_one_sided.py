"""A figure that cannot be negative has a one-sided limit: a falling E never crosses -tolerance."""

from __future__ import annotations

import datetime as _dt

import matplotlib

matplotlib.use("Agg")

from matplotlib.axes import Axes  # noqa: E402

from axiscal.history import one_sided_figure, plot_trend  # noqa: E402
from axiscal.history.trend import crossing, fit_drift, trend_of  # noqa: E402

DATES = [_dt.date(2024, 1, 1) + _dt.timedelta(days=91 * n) for n in range(6)]
FALLING = [12.0, 10.1, 8.0, 6.1, 4.0, 2.1]          # um: E after a repair, falling towards 0


def test_magnitudes_are_one_sided_and_a_squareness_is_not():
    assert all(one_sided_figure(f"positioning.X.{name}") for name in "AERBM")
    assert one_sided_figure("straightness.X.straightness_um")
    assert not one_sided_figure("squareness.XZ.squareness_arcsec")


def test_a_falling_magnitude_predicts_no_crossing_and_a_signed_figure_does():
    e = trend_of("m", "positioning.X.E", DATES, FALLING, [0.5] * 6, 15.0, [True] * 6, unit="um")
    assert e.one_sided and e.limits == (15.0,)
    assert e.crossing_date is None and e.crossing_interval == (None, None) and e.fixed_risk_date is None
    assert e.payload()["limits"] == [15.0]
    # the same numbers as a signed figure: the line reaches -15 (hand check: slope about -8 um/year,
    # from 2.1 um at 2025-04 down to -15 within about two years)
    signed = trend_of("m", "squareness.XZ.squareness_arcsec", DATES, FALLING, [0.5] * 6, 15.0, [True] * 6, unit="arcsec")
    assert not signed.one_sided and signed.crossing_date is not None
    assert _dt.date(2027, 1, 1) < signed.crossing_date < _dt.date(2027, 7, 1)
    fit = fit_drift(*[[1.0, 2.0, 3.0], [3.0, 2.0, 1.0]], None)
    assert crossing(fit, 5.0, one_sided=True) == (None, None, None)


def test_the_plot_names_its_limit_lines_in_the_legend(tmp_path, monkeypatch):
    e = trend_of("m", "positioning.X.E", DATES, FALLING, [0.5] * 6, 15.0, [True] * 6, unit="um")
    labels = []
    real = Axes.axhline

    def axhline(self, y=0, *args, **kwargs):
        labels.append((y, kwargs.get("label")))
        return real(self, y, *args, **kwargs)

    monkeypatch.setattr(Axes, "axhline", axhline)
    plot_trend(e, tmp_path / "trend.png")
    assert labels == [(15.0, "tolerance +15 um")]
