"""Virtual machines with known polynomial errors, shared by the identification tests."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from axiscal.identification import ParameterSet, parse_model
from axiscal.model.machine import Axis, Machine


def polynomial_machine(chain: str, model: str, travel: dict, rng, *, translation_m=5e-6, angle_rad=10e-6, fix=()):
    """(ideal machine, true machine, true θ): random coefficients of ``model`` over ``travel``."""
    ideal = Machine(chain, {k: Axis(k) for k in chain.replace("F", "")})
    parameters = ParameterSet(ideal, parse_model(model), travel, fix)
    scale = np.array([translation_m if t.unit == "m" else angle_rad for t in parameters.terms])
    theta = scale * rng.standard_normal(len(parameters.terms))
    return ideal, parameters.identified_machine(theta), theta


def coverage(result, theta) -> np.ndarray:
    """|estimate - truth| / u of each determined machine term."""
    p = len(result.terms)
    z = (result.values[:p] - theta) / result.std[:p]
    return np.abs(z[np.isfinite(z)])


@pytest.fixture
def virtual():
    """The helpers above: ``virtual.polynomial_machine(...)``, ``virtual.coverage(...)``."""
    return SimpleNamespace(polynomial_machine=polynomial_machine, coverage=coverage)
