"""Reference lines and straightness (ISO 230-1): exact minimum zone, invariances, bad input."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog

from axiscal.errors import AxiscalError
from axiscal.straightness.reference import REFERENCES, ReferenceLine, reference_line


def brute_force_minimum_zone(x: np.ndarray, y: np.ndarray) -> float:
    """Plain reference: the minimum zone's slope is that of a line through two of the points."""
    best = np.inf
    for i in range(len(x)):
        for j in range(len(x)):
            if x[j] != x[i]:
                k = (y[j] - y[i]) / (x[j] - x[i])
                r = y - k * x
                best = min(best, r.max() - r.min())
    return best


def linprog_minimum_zone(x: np.ndarray, y: np.ndarray) -> float:
    """Reference by linear programming: minimise h with 0 <= y - k x - c <= h (variables k, c, h)."""
    n = len(x)
    a_ub = np.vstack([np.column_stack([x, np.ones(n), np.zeros(n)]), np.column_stack([-x, -np.ones(n), -np.ones(n)])])
    b_ub = np.concatenate([y, -y])
    res = linprog([0, 0, 1], A_ub=a_ub, b_ub=b_ub, bounds=[(None, None)] * 3, method="highs")
    return res.fun


def test_hand_computed_example():
    # points (0,0) (1,2) (2,1) (3,3): least squares y = 0.8 x + 0.3 by the normal equations
    x = np.array([0.0, 1.0, 2.0, 3.0])
    y = np.array([0.0, 2.0, 1.0, 3.0])
    ls = reference_line(x, y)
    assert ls.slope == pytest.approx(0.8) and ls.intercept_m == pytest.approx(0.3)
    r = y - (0.8 * x + 0.3)
    assert ls.straightness_m == pytest.approx(r.max() - r.min())
    ep = reference_line(x, y, reference="end-points")
    assert ep.slope == pytest.approx(1.0) and ep.intercept_m == pytest.approx(0.0)
    assert ep.straightness_m == pytest.approx(2.0)  # residuals 0, 1, -1, 0
    mz = reference_line(x, y, reference="minimum-zone")
    # hull edges have slopes 2 and 1/2; with slope 1/2 the residuals are 0, 1.5, 0, 1.5
    assert mz.slope == pytest.approx(0.5) and mz.intercept_m == pytest.approx(0.75)
    assert mz.straightness_m == pytest.approx(1.5)
    assert ls.straightness_m == pytest.approx(1.8)
    res = mz.residuals(x, y)
    assert res.max() == pytest.approx(-res.min())  # the minimum-zone line is the zone's mid-line


@pytest.mark.parametrize("seed", range(20))
def test_minimum_zone_is_exact_against_brute_force_and_linprog(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 25))
    x = np.sort(rng.uniform(0.0, 0.5, n))
    y = 1e-6 * rng.normal(size=n) + 1e-4 * x
    mz = reference_line(x, y, reference="minimum-zone")
    assert mz.straightness_m == pytest.approx(brute_force_minimum_zone(x, y), rel=1e-9, abs=1e-18)
    assert mz.straightness_m == pytest.approx(linprog_minimum_zone(x / 0.5, y / 1e-6) * 1e-6, rel=1e-6, abs=1e-15)
    r = mz.residuals(x, y)
    assert r.max() - r.min() == pytest.approx(mz.straightness_m, rel=1e-12, abs=1e-20)


def test_minimum_zone_with_repeated_positions_and_unsorted_input():
    rng = np.random.default_rng(0)
    x = np.repeat(np.linspace(0.0, 0.2, 8), 3)
    y = 1e-6 * rng.normal(size=x.size)
    perm = rng.permutation(x.size)
    mz = reference_line(x[perm], y[perm], reference="minimum-zone")
    assert mz.straightness_m == pytest.approx(brute_force_minimum_zone(x, y), rel=1e-9)
    ls = reference_line(x[perm], y[perm])
    assert ls.straightness_m >= mz.straightness_m


def test_long_convex_profile():
    # a parabola: every point is on the lower hull, the zone is the sagitta of the chord
    x = np.linspace(-1.0, 1.0, 200_001)
    y = 1e-6 * x**2
    mz = reference_line(x, y, reference="minimum-zone")
    assert mz.straightness_m == pytest.approx(1e-6, rel=1e-12)
    assert mz.slope == pytest.approx(0.0, abs=1e-18)


finite = st.floats(-1e-4, 1e-4, allow_nan=False)


@st.composite
def profiles(draw):
    n = draw(st.integers(2, 30))
    steps = draw(st.lists(st.integers(0, 10_000), min_size=n, max_size=n, unique=True))
    x = np.sort(np.array(steps, dtype=float)) * 1e-4
    y = np.array(draw(st.lists(st.floats(-1e-5, 1e-5), min_size=n, max_size=n)))
    return x, y


@settings(max_examples=60, deadline=None)
@given(profiles(), finite, finite)
def test_straightness_is_invariant_under_adding_a_line(profile, slope, intercept):
    x, y = profile
    scale = max(np.ptp(y), 1e-12)
    for reference in REFERENCES:
        a = reference_line(x, y, reference=reference)
        b = reference_line(x, y + slope * x + intercept, reference=reference)
        assert b.straightness_m == pytest.approx(a.straightness_m, abs=1e-8 * scale + 1e-15)
        assert b.slope == pytest.approx(a.slope + slope, abs=1e-8 * scale / np.ptp(x) + 1e-14)


@settings(max_examples=80, deadline=None)
@given(profiles())
def test_minimum_zone_is_never_wider_than_the_other_two(profile):
    # the only law: minimum zone <= least squares and minimum zone <= end points
    # (least squares <= end points does NOT hold in general; see the counter-example below)
    x, y = profile
    mz = reference_line(x, y, reference="minimum-zone").straightness_m
    tol = 1e-12 * max(np.ptp(y), 1e-12)
    assert mz <= reference_line(x, y).straightness_m + tol
    assert mz <= reference_line(x, y, reference="end-points").straightness_m + tol


def test_least_squares_can_be_wider_than_end_points():
    # flat profile with one spike next to the end: the end-point line stays flat (zone 5 um), the
    # least-squares line tilts towards the spike and its zone is 5 um + slope * 1 m
    x = np.arange(10.0)
    y = np.zeros(10)
    y[8] = 5e-6
    ls, ep = reference_line(x, y), reference_line(x, y, reference="end-points")
    assert ep.straightness_m == pytest.approx(5e-6)
    assert ls.straightness_m == pytest.approx(5e-6 + ls.slope) and ls.slope > 0
    assert ls.straightness_m > ep.straightness_m


def test_returns_a_frozen_dataclass():
    line = reference_line([0.0, 1.0], [0.0, 1.0])
    assert isinstance(line, ReferenceLine) and line.reference == "least-squares"
    with pytest.raises(AttributeError):
        line.slope = 2.0  # type: ignore[misc]


@settings(max_examples=40, deadline=None)
@given(profiles(), st.sampled_from([np.nan, np.inf, -np.inf]), st.booleans(), st.sampled_from(REFERENCES), st.data())
def test_any_non_finite_value_is_refused(profile, bad, in_position, reference, data):
    x, y = (a.copy() for a in profile)
    k = data.draw(st.integers(0, x.size - 1))
    (x if in_position else y)[k] = bad
    with pytest.raises(AxiscalError, match="finite"):
        reference_line(x, y, reference=reference)


@pytest.mark.parametrize(
    ("position", "deviation", "reference", "needle"),
    [
        ([0.0], [0.0], "least-squares", "at least 2"),
        ([], [], "minimum-zone", "at least 2"),
        ([0.0, 1.0], [0.0, np.nan], "least-squares", "finite"),
        ([0.0, np.inf], [0.0, 1.0], "minimum-zone", "finite"),
        ([1.0, 1.0, 1.0], [0.0, 1.0, 2.0], "least-squares", "distinct positions"),
        ([1.0, 1.0], [0.0, 1.0], "minimum-zone", "distinct positions"),
        ([0.0, 0.0, 1.0], [0.0, 1.0, 2.0], "end-points", "end-point line"),
        ([0.0, 1.0, 2.0], [0.0, 1.0], "least-squares", "same length"),
        ([0.0, 1.0], [0.0, 1.0], "chebyshev", "unknown reference"),
    ],
)
def test_bad_input(position, deviation, reference, needle):
    with pytest.raises(AxiscalError, match=needle):
        reference_line(position, deviation, reference=reference)
