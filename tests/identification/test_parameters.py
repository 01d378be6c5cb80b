"""The batched Jacobian against a plain reference: each column by two machines built with tables, through Machine.volumetric_error."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.identification import ParameterSet, parse_model
from axiscal.model.machine import Axis, Machine

TRAVEL = {"X": (0.0, 0.4), "Y": (0.0, 0.3), "Z": (0.0, 0.2)}


@pytest.mark.parametrize("chain,model", [("FYXZ", "poly:3"), ("XFYZ", "spline:4"), ("YXFZ", "poly:2")])
def test_batched_jacobian_equals_columns_through_written_tables(chain, model):
    rng = np.random.default_rng(7)
    ideal = Machine(chain, {k: Axis(k) for k in "XYZ"}, tool_m=(0.02, -0.01, -0.1))
    parameters = ParameterSet(ideal, parse_model(model), TRAVEL)
    theta = 5e-6 * rng.standard_normal(len(parameters.terms))
    positions = {k: rng.uniform(*TRAVEL[k], 40) for k in "XYZ"}
    fast = parameters.jacobian(theta, positions, np.array(ideal.tool_m))
    step = 1e-6
    for k in rng.choice(len(parameters.terms), 8, replace=False):
        shift = np.zeros(len(theta))
        shift[k] = step
        plus = parameters.identified_machine(theta + shift).volumetric_error(positions)
        minus = parameters.identified_machine(theta - shift).volumetric_error(positions)
        # the tables of a polynomial are cubic splines through 101 samples: equal to 1e-6 of the column
        assert np.allclose(fast[:, :, k], (plus - minus) / (2 * step), rtol=0, atol=1e-6 * np.abs(fast[:, :, k]).max() + 1e-12)


def test_the_start_is_the_projection_of_the_machine_files_tables():
    rng = np.random.default_rng(8)
    ideal = Machine("FYXZ", {k: Axis(k) for k in "XYZ"})
    parameters = ParameterSet(ideal, parse_model("poly:3"), TRAVEL)
    theta = 5e-6 * rng.standard_normal(len(parameters.terms))
    again = ParameterSet(parameters.identified_machine(theta), parse_model("poly:3"), TRAVEL)
    assert np.allclose(again.start(), theta, atol=1e-12)


def test_a_fixed_term_that_names_nothing_is_refused():
    ideal = Machine("FXY", {k: Axis(k) for k in "XY"})
    with pytest.raises(AxiscalError, match="fix EZZ"):
        ParameterSet(ideal, parse_model("poly:2"), TRAVEL, fix=("EZZ",))
