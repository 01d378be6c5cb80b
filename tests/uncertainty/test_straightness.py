"""Straightness and squareness uncertainty: each component alone, by hand, against numpy.polyfit's covariance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from axiscal.squareness import squareness
from axiscal.straightness.files import read_profile
from axiscal.uncertainty import (
    budget_from_dict,
    read_budget,
    squareness_uncertainty,
    straightness_uncertainty,
)

X = np.linspace(0.0, 0.5, 11)
ARCSEC = math.pi / 648000


def polyfit_slope_se(x, y):
    """Standard error of the least-squares slope as numpy.polyfit reports it (residual-scaled covariance)."""
    _, cov = np.polyfit(x, y, 1, cov=True)
    return math.sqrt(cov[0, 0])


def test_device_alone_on_a_straight_profile():
    # a perfect line: no fit scatter; T is the difference of two readings: u = sqrt(2) U / 2
    r = straightness_uncertainty(budget_from_dict({"instrument": {"straightness_U_um": 1.0}}), X, 3e-6 * X + 1e-6)
    assert r.value == pytest.approx(0.0, abs=1e-15)
    assert r.components["device"] == pytest.approx(math.sqrt(2) * 0.5e-6)
    assert r.components["fit"] == pytest.approx(0.0, abs=1e-15) and r.components["eve"] == 0.0
    assert r.U == pytest.approx(math.sqrt(2) * 1e-6)


def test_fit_alone_is_the_slope_standard_error_times_the_travel():
    y = 1e-6 * np.sin(9 * X) + 2e-6 * X
    r = straightness_uncertainty(budget_from_dict({}), X, y)
    assert r.components["fit"] == pytest.approx(polyfit_slope_se(X, y) * 0.5, rel=1e-9)
    assert r.degrees_of_freedom == pytest.approx(X.size - 2)
    assert r.U == pytest.approx(2 * r.components["fit"])


def test_eve_alone():
    r = straightness_uncertainty(budget_from_dict({"setup": {"eve_um": 1.0}}), X, 0 * X)
    assert r.components["eve"] == pytest.approx(1e-6 / (2 * math.sqrt(3)))


def test_prism_alone():
    k1, k2 = 20e-6, -5e-6
    r = squareness_uncertainty(budget_from_dict({"setup": {"prism_deviation_u_arcsec": 0.5}}), X, k1 * X, X, k2 * X,
                               prism_deviation_rad=2 * ARCSEC)
    assert r.value == pytest.approx(-math.atan(k1) - math.atan(k2) - 2 * ARCSEC, abs=1e-15)
    assert r.components["prism"] == pytest.approx(0.5 * ARCSEC)
    assert r.U == pytest.approx(ARCSEC, rel=1e-9)


def test_squareness_of_the_example_runs_by_hand(examples):
    budget = read_budget(examples / "uncertainty_budget.toml")
    x1, d1 = (lambda p: (p.position_m, p.deviation_m))(read_profile(examples / "squareness_x.csv"))
    x2, d2 = (lambda p: (p.position_m, p.deviation_m))(read_profile(examples / "squareness_y.csv"))
    r = squareness_uncertainty(budget, x1, d1, x2, d2)
    plain = squareness(x1, d1, x2, d2)
    assert r.value == pytest.approx(plain.squareness_rad, abs=1e-15)
    parts = {}
    for name, x, d, k in (("first_run", x1, d1, plain.slope_first), ("second_run", x2, d2, plain.slope_second)):
        instrument = math.sqrt(2) * 0.4e-6 / np.ptp(x)
        parts[name] = math.hypot(polyfit_slope_se(x, d), instrument) / (1 + k**2)
        assert r.components[name] == pytest.approx(parts[name], rel=1e-9)
    parts["prism"] = 0.5 * ARCSEC
    assert r.U == pytest.approx(2 * math.sqrt(sum(u**2 for u in parts.values())), rel=1e-9)


def test_the_figures_docs_quote(examples):
    budget = read_budget(examples / "uncertainty_budget.toml")
    x1, d1 = (lambda p: (p.position_m, p.deviation_m))(read_profile(examples / "squareness_x.csv"))
    x2, d2 = (lambda p: (p.position_m, p.deviation_m))(read_profile(examples / "squareness_y.csv"))
    r = squareness_uncertainty(budget, x1, d1, x2, d2)
    assert (round(r.value / ARCSEC, 2), round(r.U / ARCSEC, 2)) == (23.65, 1.37)
    t = straightness_uncertainty(budget, x1, d1)
    assert (round(t.value * 1e6, 2), round(t.U * 1e6, 2)) == (2.72, 1.90)
