"""The correction on a regular grid: each row's command puts the tool on the nominal point of its programmed one."""

from __future__ import annotations

import json

import numpy as np
import pandas
import pytest

from axiscal.errors import AxiscalError
from axiscal.precompensation import GRID_COLUMNS, correction_grid, export_correction_grid, precompensate_points

from .machines import machines

MACHINES = machines()


def test_grid_rows_are_the_pre_compensated_points_in_c_order(tmp_path):
    machine = MACHINES["xfyz"]
    result = export_correction_grid(machine, "X=50:750:350,Y=100:400:150,Z=60", tmp_path / "grid.csv")
    frame = pandas.read_csv(tmp_path / "grid.csv")
    assert tuple(frame.columns) == GRID_COLUMNS and len(frame) == 3 * 3
    assert list(frame["x_mm"]) == [50.0] * 3 + [400.0] * 3 + [750.0] * 3 and list(frame["y_mm"][:3]) == [100, 250, 400]
    points = frame[["x_mm", "y_mm", "z_mm"]].to_numpy() * 1e-3
    command = points + frame[["x_correction_um", "y_correction_um", "z_correction_um"]].to_numpy() * 1e-6
    q = {k: command[:, i] for i, k in enumerate("XYZ")}
    nominal = machine.nominal_point({k: points[:, i] for i, k in enumerate("XYZ")})
    assert np.abs(machine.actual_point(q) - nominal).max() < 1e-10      # the file's 0.1 nm resolution
    assert np.allclose(result.correction_m, precompensate_points(machine, points).correction_m, atol=1e-15)
    sidecar = json.loads((tmp_path / "grid.json").read_text())
    assert sidecar["grid"]["X"] == {"start_mm": 50.0, "step_mm": 350.0, "count": 3} and sidecar["order"].startswith("C")


def test_a_trunnion_grid_names_its_rotary_angles_once():
    result = correction_grid(MACHINES["trunnion"], "A=-10,C=45,X=-100:100:100,Y=-100:100:100,Z=-300")
    assert result.correction_m.shape == (9, 3) and np.abs(result.correction_m).max() > 1e-6
    with pytest.raises(AxiscalError, match="rotary axis C stands still"):
        correction_grid(MACHINES["trunnion"], "C=0:90:45,X=0,Y=0,Z=-300")


@pytest.mark.parametrize(("grid", "message"), [
    ("X=0:100:50,Y=100", "must name every linear axis of chain 'XFYZ'; add Z"),
    ("X=100,Y=100,Z=100,C=0", "names C, not an axis"),
    ("X=0:800:100,Y=0:500:100,Z=100", "grid point 1 (X=0, Y=0, Z=100 mm): needs"),
])
def test_bad_grids(grid, message):
    with pytest.raises(AxiscalError, match=message.replace("(", r"\(").replace(")", r"\)")):
        correction_grid(MACHINES["xfyz"], grid)
