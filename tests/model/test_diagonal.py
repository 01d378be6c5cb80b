"""Diagonal check from the model (ISO 230-6; paper 000 eq 13)."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.model.diagonal import diagonal_check
from axiscal.model.machine import Axis, Machine
from axiscal.model.tables import ErrorTable


def test_ideal_machine_has_no_diagonal_error():
    machine = Machine("FXZ", {"X": Axis("X"), "Z": Axis("Z")})
    result = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}, 19)
    np.testing.assert_allclose(result.nominal_m, np.linspace(0, 0.19 * np.sqrt(2), 20))
    np.testing.assert_allclose(result.model_error_m, 0.0, atol=1e-16)


def test_squareness_shows_on_the_diagonal_as_half_angle_times_length():
    # EB0Z = alpha turns Z towards +X: at (x, z) = (L, L) the tool is off by alpha * L in X,
    # along the diagonal u = (1, 0, 1)/sqrt(2) that is alpha * L / sqrt(2)
    alpha = 100e-6
    machine = Machine("FXZ", {"X": Axis("X"), "Z": Axis("Z")}, squareness_rad={"EB0Z": alpha})
    result = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.2, "Z": 0.2}, 4)
    np.testing.assert_allclose(result.model_error_m, alpha * np.linspace(0, 0.2, 5) / np.sqrt(2), rtol=1e-6)


def test_paper000_eq13_before_and_after():
    # paper 000 eq (13): E_BD = nominal - P, E_AD = |actual| - P; with readings equal to the model the
    # error after the model vanishes and the error before it is minus the model's error
    position = np.linspace(0, 0.19, 20)
    x = ErrorTable.from_components("X", position, {"EXX": 20e-6 * position / 0.19, "EBX": 30e-6 * np.sin(position * 20)})
    machine = Machine("FXZ", {"X": Axis("X", x), "Z": Axis("Z", origin_m=(0, 0, 0.05))}, tool_m=(0, -0.04, 0))
    model = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}, 19, measure="length")
    checked = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}, 19, measured_m=model.predicted_m, measure="length")
    np.testing.assert_allclose(checked.error_after_m, 0.0, atol=1e-15)
    np.testing.assert_allclose(checked.error_before_m, -model.model_error_m, atol=1e-15)
    projection = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}, 19)
    assert np.abs(projection.predicted_m - model.predicted_m).max() < 1e-9


def test_bad_diagonals():
    machine = Machine("FXZ", {"X": Axis("X"), "Z": Axis("Z")})
    with pytest.raises(AxiscalError, match="same point"):
        diagonal_check(machine, {"X": 0.1, "Z": 0.1}, {"X": 0.1, "Z": 0.1}, 5)
    with pytest.raises(AxiscalError, match="different axes"):
        diagonal_check(machine, {"X": 0.0}, {"X": 0.1, "Z": 0.1}, 5)
    with pytest.raises(AxiscalError, match="readings"):
        diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.1, "Z": 0.1}, 5, measured_m=np.zeros(3))
