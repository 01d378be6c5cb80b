"""Diagonal check from the model (ISO 230-6; paper 000 eq 13)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.model.diagonal import diagonal_check, diagonal_test
from axiscal.model.machine import Axis, Machine
from axiscal.model.plot import plot_diagonal
from axiscal.model.output import SIGN_CONVENTION
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


def test_paper000_eq13_before_and_after_with_the_sign_of_the_conventions():
    # paper 000 eq (13): E_BD = nominal - P, E_AD = |actual| - P. axiscal reports both as actual
    # minus nominal (docs/conventions.md): E_BD = P - nominal, E_AD = P - predicted. With readings
    # equal to the model, E_AD vanishes and E_BD is the model's own error, sign included.
    position = np.linspace(0, 0.19, 20)
    x = ErrorTable.from_components("X", position, {"EXX": 20e-6 * position / 0.19, "EBX": 30e-6 * np.sin(position * 20)})
    machine = Machine("FXZ", {"X": Axis("X", x), "Z": Axis("Z", origin_m=(0, 0, 0.05))}, tool_m=(0, -0.04, 0))
    model = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}, 19, measure="length")
    checked = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}, 19, measured_m=model.predicted_m, measure="length")
    np.testing.assert_allclose(checked.error_after_m, 0.0, atol=1e-15)
    np.testing.assert_allclose(checked.error_before_m, model.model_error_m, atol=1e-15)
    paper_e_bd = model.nominal_m - model.predicted_m
    np.testing.assert_allclose(checked.error_before_m, -paper_e_bd, atol=1e-15)
    projection = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}, 19)
    assert np.abs(projection.predicted_m - model.predicted_m).max() < 1e-9


def stretched_x_machine(ppm=100.0):
    """X goes further than commanded (EXX > 0): the tool overshoots along +X and so along the diagonal."""
    position = np.array([0.0, 0.2])
    x = ErrorTable.from_components("X", position, {"EXX": ppm * 1e-6 * position})
    return Machine("FXZ", {"X": Axis("X", x), "Z": Axis("Z")}, name="stretched")


def test_one_sign_actual_minus_nominal_in_every_output(tmp_path, monkeypatch):
    # docs/conventions.md: a machine that overshoots has a positive diagonal error in the result,
    # the CSV, the JSON summary and the plot; a laser reading more than nominal gives a positive E_BD
    machine = stretched_x_machine()
    nominal = np.linspace(0.0, 0.2 * np.sqrt(2), 5)
    readings = nominal + np.linspace(0.0, 3e-6, 5)  # the machine went 3 um further than nominal
    result = diagonal_test(machine, "X=0,Z=0", "X=200,Z=200", readings=readings)
    assert result.model_error_m[-1] == pytest.approx(100e-6 * 0.2 / np.sqrt(2), rel=1e-6) and result.model_error_m[-1] > 0
    assert result.error_before_m[-1] == pytest.approx(3e-6)
    assert result.error_after_m[-1] == pytest.approx(3e-6 - result.model_error_m[-1])
    columns = pd.read_csv(result.write_csv(tmp_path / "diagonal.csv"))
    assert list(columns.columns) == ["x_mm", "z_mm", "nominal_mm", "measured_mm", "model_error_um", "E_BD_um", "E_AD_um"]
    assert columns["model_error_um"].iloc[-1] == pytest.approx(14.142136, abs=1e-5)
    assert columns["E_BD_um"].iloc[-1] == pytest.approx(3.0, abs=1e-6)
    sidecar = json.loads((tmp_path / "diagonal.json").read_text())
    assert sidecar["sign"] == SIGN_CONVENTION and sidecar["kind"] == "diagonal displacement test"
    summary = result.summary()
    assert summary["points"]["model_error_um"][-1] > 0 and summary["points"]["E_BD_um"][-1] == pytest.approx(3.0)
    captured = {}
    monkeypatch.setattr("axiscal.model.plot.save_figure", lambda fig, path, dpi=120: captured.setdefault("fig", fig))
    plot_diagonal(result, tmp_path / "d.png")
    lines = {line.get_label().split(" ")[0]: line.get_ydata() for line in captured["fig"].axes[0].lines}
    np.testing.assert_allclose(lines["model"], result.model_error_m * 1e6)
    np.testing.assert_allclose(lines["E_BD"], result.error_before_m * 1e6)
    np.testing.assert_allclose(lines["E_AD"], result.error_after_m * 1e6)


def test_diagonal_text_names_the_ranges():
    result = diagonal_test(stretched_x_machine(), {"X": 0.0, "Z": 0.0}, {"X": 0.2, "Z": 0.2}, steps=4)
    assert result.text() == (
        "diagonal of stretched: 5 points, length 282.843 mm\n  model error along the diagonal: P-V 14.14 um\n"
    )
    with_readings = diagonal_test(stretched_x_machine(), "X=0,Z=0", "X=200,Z=200", readings=np.linspace(0, 0.2 * np.sqrt(2), 5))
    assert with_readings.text().splitlines()[2:] == ["  E_BD (before model): P-V 0.00 um", "  E_AD (after model):  P-V 14.14 um"]


def test_bad_diagonals():
    machine = Machine("FXZ", {"X": Axis("X"), "Z": Axis("Z")})
    with pytest.raises(AxiscalError, match="same point"):
        diagonal_check(machine, {"X": 0.1, "Z": 0.1}, {"X": 0.1, "Z": 0.1}, 5)
    with pytest.raises(AxiscalError, match="different axes"):
        diagonal_check(machine, {"X": 0.0}, {"X": 0.1, "Z": 0.1}, 5)
    with pytest.raises(AxiscalError, match="readings"):
        diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.1, "Z": 0.1}, 5, measured_m=np.zeros(3))
    with pytest.raises(AxiscalError, match="names axis Y, which is not in chain"):
        diagonal_check(machine, {"X": 0.0, "Z": 0.0, "Y": 0.0}, {"X": 0.1, "Z": 0.1, "Y": 0.0}, 5)
    table_machine = stretched_x_machine()
    with pytest.raises(AxiscalError, match="X = 300 mm is outside the error table"):
        diagonal_test(table_machine, "X=0,Z=0", "X=300,Z=300")


@settings(max_examples=40, deadline=None)
@given(ppm=st.floats(-200.0, 200.0), offsets_um=st.lists(st.floats(-50.0, 50.0), min_size=4, max_size=4))
def test_before_minus_after_is_the_models_error(ppm, offsets_um):
    # one sign for all three: (P - nominal) - (P - predicted) = predicted - nominal, whatever P is
    machine = stretched_x_machine(ppm)
    nominal = np.linspace(0.0, 0.2 * np.sqrt(2), 5)
    readings = nominal + np.array([0.0, *offsets_um]) * 1e-6
    result = diagonal_test(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.2, "Z": 0.2}, readings=readings)
    np.testing.assert_allclose(result.error_before_m - result.error_after_m, result.model_error_m, atol=1e-15)
    if abs(ppm) > 1e-3:
        assert np.sign(result.model_error_m[-1]) == np.sign(ppm)


def test_the_diagonal_plot_draws_another_test_behind(tmp_path):
    from importlib import resources
    from pathlib import Path

    from axiscal.model import load_machine
    from axiscal.model.plot import plot_diagonal

    folder = Path(str(resources.files("axiscal") / "data" / "xz_module"))
    result = diagonal_test(load_machine(folder / "machine.toml"), "X=0,Z=0", "X=190,Z=190", readings=folder / "diagonal_laser.csv")
    points = result.summary()["points"]
    overlay = {k: [float(v) * (1 if k.endswith("_mm") else 2) for v in values] for k, values in points.items()}
    plot_diagonal(result, tmp_path / "d.svg", overlay=overlay)
    text = (tmp_path / "d.svg").read_text()
    assert "before: model prediction" in text and "before: E_BD" in text and "before: E_AD" in text
