"""Coverage intervals of Monte Carlo draws (JCGM 101:2008, 7.7), against a plain sort-and-count reference."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.uncertainty import coverage_interval


def reference_shortest(x, p):
    x = np.sort(x)
    q = int(np.floor(p * x.size + 0.5))
    best = min(range(x.size - q + 1), key=lambda r: x[r + q - 1] - x[r])
    return x[best], x[best + q - 1]


def test_normal_draws_give_1_96_sigma():
    x = np.random.default_rng(0).normal(3.0, 2.0, 400_000)
    ci = coverage_interval(x)
    assert ci.low == pytest.approx(3.0 - 1.96 * 2.0, abs=0.03)
    assert ci.high == pytest.approx(3.0 + 1.96 * 2.0, abs=0.03)
    assert ci.half_width == pytest.approx(1.96 * 2.0, rel=0.01)


def test_shortest_interval_matches_the_reference_and_hugs_a_skewed_output():
    x = np.random.default_rng(1).exponential(1.0, 5000)
    ci = coverage_interval(x, shortest=True)
    assert (ci.low, ci.high) == reference_shortest(x, 0.95)
    assert ci.high - ci.low < coverage_interval(x).high - coverage_interval(x).low


def test_many_outputs_at_once():
    x = np.random.default_rng(2).normal(size=(3000, 4))
    low, high = coverage_interval(x)
    for j in range(4):
        ci = coverage_interval(x[:, j])
        assert (low[j], high[j]) == (ci.low, ci.high)


def test_bad_input():
    with pytest.raises(AxiscalError):
        coverage_interval(np.zeros(100), 1.5)
    with pytest.raises(AxiscalError, match="too few"):
        coverage_interval(np.zeros(5))
