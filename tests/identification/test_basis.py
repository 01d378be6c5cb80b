"""The error functions: Legendre polynomials against their textbook forms, splines, the terms left out."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.identification import parse_model


def test_legendre_basis_is_the_textbook_polynomial_minus_its_start():
    # Abramowitz and Stegun 22.3.8: P2 = (3u² - 1)/2, P3 = (5u³ - 3u)/2
    model = parse_model("poly:3")
    u = np.random.default_rng(0).uniform(-1, 1, 50)
    assert np.allclose(model.evaluate(1, u), u + 1.0)
    assert np.allclose(model.evaluate(2, u), (3 * u**2 - 1) / 2 - 1.0)
    assert np.allclose(model.evaluate(3, u), (5 * u**3 - 3 * u) / 2 + 1.0)


def test_every_basis_function_is_zero_at_the_start_of_the_travel():
    for text in ("poly:5", "spline:6"):
        model = parse_model(text)
        for label in model.labels(straightness=False):
            assert model.evaluate(label, np.array([-1.0]))[0] == pytest.approx(0.0, abs=1e-15)


def test_straightness_functions_hold_no_line():
    u = np.linspace(-1, 1, 401)
    line = np.column_stack([np.ones_like(u), u])
    for text in ("poly:4", "spline:5"):
        model = parse_model(text)
        design = np.column_stack([model.evaluate(k, u) for k in model.labels(straightness=True)])
        # no combination of them is a straight line: adding the line raises the rank by two
        assert np.linalg.matrix_rank(np.hstack([design, line])) == design.shape[1] + 2


def test_spline_coefficients_are_the_values_at_the_knots():
    model = parse_model("spline:4")
    knots = np.linspace(-1, 1, 5)
    for label in model.labels(straightness=False):
        assert np.allclose(model.evaluate(label, knots), np.eye(5)[label])


@pytest.mark.parametrize("text", ["poly", "poly:0", "poly:x", "cubic:3", "spline:41", "", 3])
def test_a_bad_model_is_refused(text):
    with pytest.raises(AxiscalError):
        parse_model(text)
