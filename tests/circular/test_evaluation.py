"""ISO 230-4:2005 clause 3 figures G, H, F and the least-squares centre, against plain reference computations."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.circular.evaluation import (
    MIN_POINTS,
    BallbarTrace,
    coverage_gap,
    iso230_4,
    lsq_circle,
    plane_axes,
    radial_deviations,
)
from axiscal.circular.report import MS, PPM
from axiscal.circular.simulation import simulate_ballbar
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM

R = 100.0 * MM


def _reference_lsq_centre(angles, deviations, radius):
    """Plain reference: the algebraic (Kasa) least-squares circle through the measured points."""
    r = radius + np.asarray(deviations)
    x, y = r * np.cos(angles), r * np.sin(angles)
    a = np.column_stack([x, y, np.ones_like(x)])
    sol, *_ = np.linalg.lstsq(a, x * x + y * y, rcond=None)
    cx, cy = sol[0] / 2, sol[1] / 2
    return cx, cy, math.sqrt(sol[2] + cx * cx + cy * cy) - radius


def _reference_h(a_ccw, r_ccw, a_cw, r_cw):
    """Plain reference of H: at each ccw angle, the cw path by linear interpolation between its two neighbours."""
    order = np.argsort(a_cw)
    a_cw, r_cw = a_cw[order], r_cw[order]
    worst = 0.0
    for a, r in zip(a_ccw, r_ccw):
        k = np.searchsorted(a_cw, a)
        lo, hi = (k - 1) % a_cw.size, k % a_cw.size
        a_lo, a_hi = a_cw[lo], a_cw[hi]
        span = (a_hi - a_lo) % (2 * math.pi)
        w = ((a - a_lo) % (2 * math.pi)) / span if span else 0.0
        worst = max(worst, abs(r - ((1 - w) * r_cw[lo] + w * r_cw[hi])))
    return worst


def test_lsq_centre_agrees_with_the_kasa_circle():
    trace = simulate_ballbar(centre_offset={"X": 15 * UM, "Y": -9 * UM}, scale={"X": 10 * PPM}, backlash={"Y": 3 * UM},
                             noise=0.2 * UM, step=math.radians(0.5))
    ours = lsq_circle(trace.angles, trace.deviations, R)
    ref = _reference_lsq_centre(trace.angles, trace.deviations, R)
    np.testing.assert_allclose(ours, ref, atol=2e-9)  # equal to second order: (15 um)^2 / 100 mm = 2 nm
    assert ours[0] == pytest.approx(15 * UM, abs=0.05 * UM)
    assert ours[1] == pytest.approx(-9 * UM, abs=0.05 * UM)


def test_an_offset_circle_has_no_circular_deviation():
    trace = simulate_ballbar(centre_offset={"X": 30 * UM, "Y": 20 * UM}, step=math.radians(0.5))
    f = iso230_4(trace)
    assert f.G["ccw"] < 0.01 * UM and f.G["cw"] < 0.01 * UM and f.H < 0.01 * UM
    # F is about the nominal centre: the offset shows in full
    assert f.F_max == pytest.approx(math.hypot(30, 20) * UM, rel=1e-3)
    assert f.F_min == pytest.approx(-math.hypot(30, 20) * UM, rel=1e-3)
    assert f.centre == pytest.approx((30 * UM, 20 * UM), abs=1e-9)


def test_g_of_a_scale_mismatch_is_its_peak_to_peak():
    # dR = R (s1 - s2)/2 cos 2a: the two enveloping circles are R |s1 - s2| apart
    trace = simulate_ballbar(scale={"X": 12 * PPM, "Y": -8 * PPM}, step=math.radians(0.25))
    f = iso230_4(trace)
    assert f.G["ccw"] == pytest.approx(R * 20 * PPM, rel=1e-3)
    assert f.radius_offset == pytest.approx(R * 2 * PPM, rel=1e-3)


def test_h_of_a_backlash_is_the_backlash():
    # ccw and cw differ by b * (step signature), whose largest value is b just after a reversal
    trace = simulate_ballbar(backlash={"X": 6 * UM}, step=math.radians(0.1))
    assert iso230_4(trace).H == pytest.approx(6 * UM, rel=1e-3)


def test_h_agrees_with_a_plain_reference():
    trace = simulate_ballbar(backlash={"X": 4 * UM, "Y": 2 * UM}, servo_mismatch=4 * MS, noise=0.3 * UM, step=math.radians(0.7))
    f = iso230_4(trace)
    paths = {}
    for d in ("ccw", "cw"):
        a, dev = trace.path(d)
        paths[d] = (a, radial_deviations(a, dev, R, f.centre))
    assert f.H == pytest.approx(_reference_h(*paths["ccw"], *paths["cw"]), rel=1e-12)


def test_one_direction_has_no_hysteresis():
    f = iso230_4(simulate_ballbar(directions=("ccw",), step=math.radians(1.0)))
    assert math.isnan(f.H) and set(f.G) == {"ccw"}


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(-50.0, 50.0), min_size=MIN_POINTS, max_size=80))
def test_g_is_the_spread_about_the_lsq_centre(values):
    a = np.linspace(0, 2 * math.pi, len(values), endpoint=False)
    dev = np.array(values) * UM
    f = iso230_4(BallbarTrace(a, ("ccw",) * a.size, dev, radius=R))
    r = radial_deviations(a, dev, R, f.centres["ccw"])
    assert f.G["ccw"] == pytest.approx(r.max() - r.min(), abs=1e-15)
    assert f.F_max == dev.max() and f.F_min == dev.min()
    assert f.G["ccw"] <= (dev.max() - dev.min()) + 1e-12 + 2 * math.hypot(*f.centres["ccw"])


def test_plane_axes_and_coverage():
    assert plane_axes("xz") == ("X", "Z")
    with pytest.raises(AxiscalError, match="unknown plane"):
        plane_axes("XX")
    gap, k = coverage_gap(np.radians([10.0, 20.0, 200.0]))
    assert math.degrees(gap) == pytest.approx(180.0) and k == 1


@pytest.mark.parametrize(
    "change, message",
    [
        ({"radius": 0.0}, "radius"),
        ({"plane": "XQ"}, "plane"),
        ({"directions": ("up",) * 360}, "direction"),
        ({"angles": np.radians(np.arange(0.0, 340.0, 340.0 / 360))}, "unmeasured"),
        ({"deviations": np.zeros(359)}, "length"),
    ],
)
def test_bad_traces_are_refused(change, message):
    kwargs = {"angles": np.radians(np.arange(0.0, 360.0)), "directions": ("ccw",) * 360, "deviations": np.zeros(360), "radius": R}
    kwargs.update(change)
    with pytest.raises(AxiscalError, match=message):
        BallbarTrace(**kwargs)


def test_too_few_points():
    a = np.radians(np.arange(0.0, 360.0, 12.0))
    with pytest.raises(AxiscalError, match=f"at least {MIN_POINTS}"):
        BallbarTrace(a, ("cw",) * a.size, np.zeros(a.size), radius=R)
