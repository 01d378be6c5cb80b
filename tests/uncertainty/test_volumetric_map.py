"""The volumetric map with uncertainty as one job: the example machine with _u columns, points, grid, files."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from axiscal.errors import AxiscalError
from axiscal.model import load_machine, volumetric_map
from axiscal.uncertainty import (
    load_machine_uncertainty,
    volumetric_monte_carlo,
    volumetric_uncertainty_map,
)

GRID = "X=0:800:400,Y=0:500:250,Z=100"


@pytest.fixture(scope="module")
def machine_path():
    from pathlib import Path

    return Path(__file__).resolve().parents[2] / "examples" / "xfyz_machine_u" / "machine.toml"


def test_the_example_machine_with_u_columns(machine_path):
    """Same tables as the XFYZ example; every error and squareness term has its u."""
    machine, u = load_machine_uncertainty(machine_path)
    plain = load_machine(machine_path.parent.parent / "xfyz_machine" / "machine.toml")
    for letter in "XYZ":
        np.testing.assert_array_equal(machine.table(letter).values, plain.table(letter).values)
        assert np.all(u.tables[letter] > 0)
    q = machine.table("X").position_m
    np.testing.assert_allclose(u.tables["X"][0], np.hypot(0.3e-6, 1.5e-6 * q), atol=1e-10)
    assert set(u.squareness_rad) == {"EC0Y", "EB0Z", "EA0Z"}


def test_the_map_is_the_monte_carlo_at_the_grid(machine_path):
    result = volumetric_uncertainty_map(machine_path, grid=GRID, draws=300, seed=4)
    nominal = volumetric_map(machine_path.parent.parent / "xfyz_machine" / "machine.toml", grid=GRID)
    assert list(result.positions_m) == ["X", "Y", "Z"]
    np.testing.assert_allclose(result.result.error, nominal.error_m)
    machine, u = load_machine_uncertainty(machine_path)
    direct = volumetric_monte_carlo(machine, u, nominal.positions_m, 300, seed=4)
    np.testing.assert_array_equal(result.result.high, direct.high)
    np.testing.assert_array_equal(result.result.magnitude_high, direct.magnitude_high)
    assert result.sources == (str(machine_path),) and result.seed == 4


def test_points_file_and_positions_give_the_same_map(machine_path, tmp_path):
    points = tmp_path / "points.csv"
    points.write_text("X_mm,Y_mm,Z_mm\n100,50,20\n700,450,380\n")
    by_file = volumetric_uncertainty_map(machine_path, points=points, draws=200, seed=1)
    by_arrays = volumetric_uncertainty_map(
        load_machine_uncertainty(machine_path),
        positions={"X": np.array([0.1, 0.7]), "Y": np.array([0.05, 0.45]), "Z": np.array([0.02, 0.38])},
        draws=200, seed=1,
    )
    np.testing.assert_allclose(by_file.result.low, by_arrays.result.low)
    assert by_file.sources == (str(machine_path), str(points))


def test_files_csv_sidecar_and_summary(machine_path, tmp_path):
    out, figure = tmp_path / "map.csv", tmp_path / "map.svg"
    result = volumetric_uncertainty_map(machine_path, grid=GRID, draws=200, output=out, plot_path=figure)
    frame = pd.read_csv(out)
    assert list(frame.columns[:4]) == ["x_mm", "y_mm", "z_mm", "ex_um"]
    assert list(frame.columns[-4:]) == ["e_um", "e_u_um", "e_low_um", "e_high_um"] and len(frame) == 9
    assert out.read_text() == result.csv()
    side = json.loads(out.with_suffix(".json").read_text())
    assert side["kind"] == "volumetric uncertainty" and side["draws"] == 200 and side["seed"] == 0
    assert "<svg" in figure.read_text()
    summary = result.summary()
    worst = int(frame["e_um"].idxmax())
    assert summary["max_e_um"] == pytest.approx(frame["e_um"][worst], abs=1e-6)
    assert summary["max_e_at_mm"] == {k: frame[f"{k.lower()}_mm"][worst] for k in "XYZ"}
    assert summary["max_e_interval_um"] == pytest.approx([frame["e_low_um"][worst], frame["e_high_um"][worst]], abs=1e-6)
    assert summary["max_e_high_um"] == pytest.approx(frame["e_high_um"].max(), abs=1e-6)
    assert summary["points"] == 9 and summary["probability"] == 0.95


def test_bad_input(machine_path, tmp_path):
    with pytest.raises(AxiscalError, match="exactly one"):
        volumetric_uncertainty_map(machine_path, draws=100)
    with pytest.raises(AxiscalError, match="figure format"):
        volumetric_uncertainty_map(machine_path, grid=GRID, draws=100, plot_path=tmp_path / "map.xyz")
    with pytest.raises(AxiscalError, match="outside"):
        volumetric_uncertainty_map(machine_path, grid="X=0:900:100,Y=0,Z=0", draws=100)
    with pytest.raises(AxiscalError, match="draw-points"):
        volumetric_uncertainty_map(machine_path, grid=GRID, draws=int(1e12))
    with pytest.raises(AxiscalError, match="positive whole number"):
        volumetric_uncertainty_map(machine_path, grid=GRID, draws=0)


def test_the_shipped_example_is_what_its_generator_writes(machine_path, tmp_path, same_text_to_precision):
    import importlib.util

    spec = importlib.util.spec_from_file_location("make_uncertainty_examples", machine_path.parents[1] / "make_uncertainty_examples.py")
    generator = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(generator)
    generator.TARGET = tmp_path
    generator.main()
    for path in machine_path.parent.iterdir():
        same_text_to_precision(path.read_text(), (tmp_path / path.name).read_text(), name=path.name)
