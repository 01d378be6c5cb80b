"""The machine model written for the ISG kernel (TwinCAT CNC), read back from the files alone.

The volumetric file's component errors EXX, EYY, EZZ at every grid node are the model's volumetric
error there, with the sign of each axis's side (to the file's 0.1 nm); interpolated linearly between the nodes, as the kernel's GRID
interpolation does, they follow the model within what a 50 mm grid allows. The axis lists hold each
axis's own positioning error from its table, to their 0.1 um.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.interpolate import RegularGridInterpolator

from axiscal.compensation import grid_values, parse_twincat_table, read_isg_csv
from axiscal.model.machine import load_machine
from axiscal.precompensation import export_isg, isg_axis_tables
from axiscal.units import MM, UM

GRID = "X=50:750:50,Y=50:450:50,Z=50:350:50"


@pytest.fixture(scope="module")
def machine(examples):
    return load_machine(examples / "xfyz_machine" / "machine.toml")


@pytest.fixture(scope="module")
def examples():
    from pathlib import Path

    return Path(__file__).resolve().parents[2] / "examples"


def test_the_volumetric_file_holds_the_models_error_at_every_node(machine, tmp_path):
    written = export_isg(machine, GRID, tmp_path / "volcomp.csv")
    assert [f.name for f in written.files] == ["volcomp.csv", "volcomp.lis", "volcomp.json"]
    (table,) = read_isg_csv(tmp_path / "volcomp.csv")
    assert table.arguments == ("X", "Y", "Z") and table.parameters == ("EXX", "EYY", "EZZ")
    q = {k: table.argument_si[:, j] for j, k in enumerate("XYZ")}
    # the table X moves the workpiece: its column holds the error with the opposite sign, and the
    # list declares X the chain's one workpiece axis (tests/precompensation/test_isg_chains.py)
    side = np.array([-1.0, 1.0, 1.0])
    np.testing.assert_allclose(table.parameter_si, machine.volumetric_error(q) * side, rtol=0, atol=0.051e-9)
    listing = (tmp_path / "volcomp.lis").read_text().split()
    assert listing[listing.index("file[0]") + 1] == "volcomp.csv" and listing[listing.index("workpiece_axes") + 1] == "1"
    assert listing[listing.index("chain") + 1] == "XYZ"
    assert json.loads((tmp_path / "volcomp.json").read_text())["compensation_list"] == "volcomp.lis"
    # the kernel interpolates linearly between the nodes: off the nodes the model is followed to a
    # small part of the error itself (the example's tables have a point every 8 mm; the grid one
    # every 50 mm)
    nodes, values = grid_values(table)
    rng = np.random.default_rng(26)
    inside = {k: rng.uniform(nodes[k][0], nodes[k][-1], 500) for k in "XYZ"}
    between = RegularGridInterpolator(tuple(nodes[k] for k in "XYZ"), values)(np.column_stack([inside[k] for k in "XYZ"]))
    left = np.abs(between - machine.volumetric_error(inside) * side).max()
    assert left < np.abs(values).max() / 10


def test_the_axis_lists_hold_each_axis_positioning_error(machine, tmp_path):
    written = export_isg(machine, GRID, tmp_path / "axes", kind="axis", axis_numbers={"X": 1, "Y": 2, "Z": 4})
    assert [f.name for f in written.files] == ["axes_X.lis", "axes_Y.lis", "axes_Z.lis"]
    for k, row in zip("XYZ", range(3)):
        table = parse_twincat_table((tmp_path / f"axes_{k}.lis").read_text())
        assert table.axis == k and table.axis_number == {"X": 1, "Y": 2, "Z": 4}[k] and not table.bilateral
        assert table.interval == 500_000  # 50 mm in 0.1 um
        at = table.setpoints * 0.1 * UM
        np.testing.assert_allclose(at, np.unique(np.round(np.arange(50, 751 if k == "X" else 451 if k == "Y" else 351, 50) * MM, 9)))
        expected = machine.table(k).evaluate(at)[row]
        assert np.abs(table.pos * 0.1 * UM - expected).max() <= 0.05 * UM + 1e-15
    assert isg_axis_tables(machine, GRID)["Y"].axis_number == 2


def test_export_grid_formats_on_the_command_line(run_cli, tmp_path, examples):
    machine = examples / "xfyz_machine" / "machine.toml"
    status, stdout, err = run_cli("export", "grid", "--machine", machine, "--grid", "X=50:750:350,Y=50:450:200,Z=50:350:150",
                                  "--format", "isg", "-o", tmp_path / "v.csv")
    assert status == 0 and stdout == "" and "27 grid nodes, largest error" in err
    assert (tmp_path / "v.lis").exists() and read_isg_csv(tmp_path / "v.csv")[0].parameter_si.shape == (27, 3)
    status, _, err = run_cli("export", "grid", "--machine", machine, "--grid", GRID, "--format", "isg-axis",
                             "--axis-numbers", "X=1,Y=2,Z=3", "-o", tmp_path / "axis")
    assert status == 0 and "3 axis lists" in err and (tmp_path / "axis_Z.lis").exists()
    for argv, message in [
        (("--format", "isg", "--axis-numbers", "X=0"), "--axis-numbers must read like X=1,Y=2,Z=3"),
        (("--format", "csv", "--axis-numbers", "X=1"), "--axis-numbers applies to --format isg and isg-axis"),
        (("--format", "isg-axis", "--axis-numbers", "X=1"), "--axis-numbers gives no logical axis number for Y"),
    ]:
        status, stdout, err = run_cli("export", "grid", "--machine", machine, "--grid", GRID, *argv, "-o", tmp_path / "bad.csv")
        assert status == 2 and stdout == "" and err.count("\n") == 1 and message in err, err
