"""SI results and their display columns: um for error translations, mm for positions, urad for angles."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.measurement.display import display_factor, display_name, to_display


@pytest.mark.parametrize(
    ("name", "shown"),
    [("EXX_m", "EXX_um"), ("EAZ_rad", "EAZ_urad"), ("ex_m", "ex_um"), ("e_m", "e_um"), ("x_m", "x_mm"), ("x_cmd_m", "x_cmd_mm"), ("pz_m", "pz_mm"), ("t_s", "t_s"), ("fault", "fault")],
)
def test_display_names(name, shown):
    assert display_name(name) == shown


@given(st.floats(-1.0, 1.0, allow_nan=False), st.sampled_from(["EXX_m", "ECZ_rad", "x_m", "py_m"]))
def test_display_values_are_the_si_values_over_the_unit(value, name):
    shown = to_display({name: np.array([value])})
    assert shown[display_name(name)][0] == pytest.approx(value / display_factor(name), rel=1e-15)


def test_display_keeps_order_and_integer_faults():
    shown = to_display({"t_s": np.array([1.0]), "fault": np.array([4]), "ex_m": np.array([1e-6])})
    assert list(shown) == ["t_s", "fault", "ex_um"] and shown["fault"].dtype.kind == "i" and shown["ex_um"][0] == pytest.approx(1.0)
    with pytest.raises(AxiscalError, match="both show as"):
        to_display({"ex_m": np.zeros(1), "ex_um": np.zeros(1)})
