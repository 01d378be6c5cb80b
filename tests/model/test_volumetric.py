"""The volumetric map job: one call from a machine and positions to errors in SI, plain CSV + sidecar."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from axiscal.errors import AxiscalError
from axiscal.model.machine import load_machine
from axiscal.model.volumetric import volumetric_map


@pytest.fixture
def machine_file(examples):
    return examples / "xz_module" / "machine.toml"


def test_grid_points_and_positions_give_the_same_errors(machine_file, tmp_path):
    machine = load_machine(machine_file)
    by_grid = volumetric_map(machine_file, grid="Z=0:190:95,X=0:190:95")
    assert list(by_grid.positions_m) == ["X", "Z"]
    points = tmp_path / "p.csv"
    points.write_text("x_mm,z_mm\n" + "\n".join(f"{x * 1e3:.3f},{z * 1e3:.3f}" for x, z in zip(*by_grid.positions_m.values())))
    by_file = volumetric_map(machine, points=points)
    by_array = volumetric_map(machine, positions=by_grid.positions_m)
    np.testing.assert_allclose(by_file.error_m, by_grid.error_m, atol=1e-15)
    np.testing.assert_allclose(by_array.error_m, machine.volumetric_error(by_grid.positions_m), atol=0)
    assert by_grid.sources == (str(machine_file),) and by_file.sources == (str(points),)
    worst = int(np.argmax(np.linalg.norm(by_grid.error_m, axis=1)))
    assert by_grid.max_m == pytest.approx(np.linalg.norm(by_grid.error_m[worst]))
    assert by_grid.max_at_m == {k: q[worst] for k, q in by_grid.positions_m.items()}


def test_the_csv_is_plain_and_its_sidecar_says_what_it_is(machine_file, tmp_path):
    result = volumetric_map(machine_file, grid="X=0:190:95,Z=0:190:95")
    path = result.write_csv(tmp_path / "out" / "map.csv")
    table = pd.read_csv(path)
    assert list(table.columns) == ["x_mm", "z_mm", "ex_um", "ey_um", "ez_um", "e_um"]
    np.testing.assert_allclose(table["ex_um"], result.error_m[:, 0] * 1e6, atol=1e-4)
    np.testing.assert_allclose(table["e_um"], np.linalg.norm(result.error_m, axis=1) * 1e6, atol=1e-4)
    assert path.read_text() == result.csv()
    sidecar = json.loads((tmp_path / "out" / "map.json").read_text())
    assert sidecar["kind"] == "volumetric error" and sidecar["sign"].startswith("actual minus nominal")
    assert sidecar["sources"] == [str(machine_file)]


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({}, "exactly one of points, grid or positions"),
        ({"grid": "X=0", "positions": {"X": [0.0]}}, "exactly one of"),
        ({"grid": "X=0:190:10"}, "grid 'X=0:190:10' gives no positions for axis Z"),
        ({"grid": "X=0,Z=0,Y=0"}, "names axis Y, which is not in chain 'FXZ'"),
        ({"positions": {"X": [0.0], "Z": [0.3]}}, "Z = 300 mm is outside the error table"),
    ],
)
def test_bad_requests(machine_file, kwargs, message):
    with pytest.raises(AxiscalError, match=message):
        volumetric_map(machine_file, **kwargs)
